// What a change saves: before → after cards for every job that changes a program (feeds,
// trochoids, plans), from the figures the job's result carries; and the estimate of a
// running job's remaining time.
import { h, num, minutes } from './ui.js';
import { length } from './units.js';

/** A change below this share of the "before" value counts as no change. */
const SAME_SHARE = 5e-4;
/** Progress below this, or fewer seconds than this, is too little to extrapolate from. */
const ETA_MIN_PROGRESS = 0.02;
const ETA_MIN_ELAPSED_S = 2;

/**
 * One card: label, before → after, and the change in per cent, marked good when it goes
 * the way that saves (`lowerIsBetter`). `after` undefined: the figure is not known after.
 */
function card(id, label, before, after, format, { note } = {}) {
  const known = (v) => typeof v === 'number' && Number.isFinite(v);
  let change = null;
  let hint = '';
  if (known(before) && known(after)) {
    const diff = after - before;
    if (Math.abs(diff) <= SAME_SHARE * Math.max(Math.abs(before), 1e-12)) {
      change = 'unchanged';
    } else {
      const share = before !== 0 ? `${diff < 0 ? '−' : '+'}${num(Math.abs(diff / before) * 100, 1)} %` : (diff < 0 ? 'less' : 'more');
      change = share;
      hint = diff < 0 ? 'good' : 'bad';
    }
  }
  return h('div', { class: `saving ${hint}`.trim(), dataset: { figure: id } },
    h('div', { class: 'saving-label' }, label),
    h('div', { class: 'saving-values' },
      h('span', { class: 'before' }, known(before) ? format(before) : '–'),
      h('span', { class: 'arrow', 'aria-label': 'becomes' }, ' → '),
      h('strong', { class: 'after' }, known(after) ? format(after) : '–')),
    change ? h('div', { class: 'saving-change' }, change) : null,
    note ? h('div', { class: 'saving-note' }, note) : null);
}

const share = (v) => `${num(v * 100, 2)} %`;
const money = (currency) => (v) => `${num(v, 2)} ${currency || ''}`.trim();

/** The figures before and after, by job kind: [id, label, before, after, format, note?]. */
const ROWS = {
  feeds(r) {
    const b = r.before || {}; const a = r.after || {};
    const s = r.analysis || {};
    const feedLength = s.cutting_length_mm != null ? s.cutting_length_mm + (s.air_cut_length_mm ?? 0) : null;
    const same = 'the path is the same: only feeds change';
    return {
      caption: ['Programmed feeds', 'optimised'],
      rows: [
        ['nominal-time', 'Time (nominal)', b.nominal_time_min ?? b.time_min, a.nominal_time_min ?? a.time_min, minutes],
        ['kinematic-time', 'Time (kinematic)', b.kinematic_time_min, a.kinematic_time_min, minutes],
        ['length', 'Feed length', feedLength, feedLength, length, same],
        ['air-cut', 'Air-cut length', s.air_cut_length_mm, s.air_cut_length_mm, length, same],
        ['tool-use', 'Tool use (of one tool)', b.consumption, a.consumption, share],
        ['cost', 'Cost', b.cost?.total, a.cost?.total, money(a.cost?.currency || b.cost?.currency)],
      ],
    };
  },
  trochoids(r) {
    const f = r.figures;
    if (!f) return null;
    const b = f.before; const a = f.after;
    return {
      caption: ['Base path', 'with trochoids'],
      rows: [
        ['nominal-time', 'Time (nominal)', b.nominal_time_min, a.nominal_time_min, minutes],
        ['kinematic-time', 'Time (kinematic)', b.kinematic_time_min, a.kinematic_time_min, minutes],
        ['length', 'Feed length', b.feed_length_mm, a.feed_length_mm, length],
        ['rapid-length', 'Rapid length', b.rapid_length_mm, a.rapid_length_mm, length],
        ['air-cut', 'Air-cut length', b.air_cut_length_mm, a.air_cut_length_mm, length],
        ['tool-use', 'Tool use (of one tool)', b.consumption, a.consumption, share],
        ['cost', 'Cost', b.cost?.total, a.cost?.total, money(a.cost?.currency || b.cost?.currency)],
        ['max-alpha', 'Max. engagement α', r.base_max_alpha_deg, r.verification?.outside_zcut?.max_alpha_deg, (v) => num(v, 1, '°')],
      ],
      note: a.cost ? `Tool use and cost with the tool’s life in ${r.material?.name || 'the material'} and the rates “${f.cost_rates?.name || 'default'}”.`
        : 'No tool-life data for this tool in this material: air-cut length, tool use and cost need it (add it under Database → Tool life).',
    };
  },
  plan(r) {
    const b = r.baseline; const t = r.totals;
    if (!b || !t) return null;
    const air = (f) => (f.feed_length_mm != null && f.cutting_length_mm != null ? f.feed_length_mm - f.cutting_length_mm : null);
    return {
      caption: [`Baseline (${b.tool})`, 'dieplan’s plan'],
      rows: [
        ['nominal-time', 'Time (nominal)', b.nominal_time_min, t.nominal_time_min, minutes],
        ['kinematic-time', 'Time (kinematic)', b.kinematic_time_min, t.kinematic_time_min, minutes],
        ['length', 'Feed length', b.feed_length_mm, t.feed_length_mm, length],
        ['air-cut', 'Air-cut length', air(b), air(t), length],
        ['tool-use', 'Tool use (of one tool)', b.consumption, t.consumption, share],
        ['cost', 'Cost', b.cost, t.cost, money(t.currency)],
      ],
    };
  },
};

/** The before → after cards of a finished job's result, or null for a kind that changes no program. */
export function savingsPanel(kind, result) {
  const made = ROWS[kind]?.(result || {});
  if (!made) return null;
  const [before, after] = made.caption;
  return h('section', { class: 'card savings-card', id: 'savings' },
    h('h2', {}, 'What the change saves'),
    h('p', { class: 'hint' }, h('strong', {}, before), ' → ', h('strong', {}, after)),
    h('div', { class: 'savings' }, made.rows.map(([id, label, b, a, format, note]) => card(id, label, b, a, format, { note }))),
    made.note ? h('p', { class: 'hint' }, made.note) : null);
}

/**
 * The remaining time of a running job, from its progress and the time it has run
 * (`started_at` to now), as text; null while there is too little to go by.
 */
export function remaining(progress, startedAt, now = Date.now()) {
  const started = Date.parse(startedAt || '');
  if (!Number.isFinite(started) || !(progress >= ETA_MIN_PROGRESS) || progress >= 1) return null;
  const elapsedS = (now - started) / 1000;
  if (elapsedS < ETA_MIN_ELAPSED_S) return null;
  const leftS = (elapsedS * (1 - progress)) / progress;
  return leftS < 60 ? `about ${Math.max(1, Math.round(leftS))} s left` : `about ${minutes(leftS / 60)} left`;
}
