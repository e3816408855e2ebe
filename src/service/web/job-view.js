// One job: progress (polled), cancel, and once succeeded the key figures, the drawing with
// its controls, the charts, the NC program download and the raw result.
import { h, api, problemBox, pretty, num, minutes, when, duration, figures, table, badge, tagList, parseTags, KIND_NAMES } from './ui.js';
import { drawingPanel } from './drawing.js';
import { savingsPanel, remaining } from './savings.js';
import { programPanel } from './program-view.js';
import { view3dPanel } from './view3d-panel.js';
import { length, area, feed, coordinate, lengthUnit } from './units.js';

const POLL_MS = 1000;
const line = (p) => (p && p.line !== undefined ? String(p.line) : '–');
// The program panel of the job shown: NC lines in the tables lead to it.
let program = null;
/** NC lines `from`–`to` of program `part` as a link to them in the program panel. */
function lineLink(part, from, to = from) {
  const text = from === to ? String(from) : `${from}–${to}`;
  if (from == null) return '–';
  return h('button', { type: 'button', class: 'link line-link', dataset: { part, from, to }, title: 'Show in the NC program',
    onclick: () => program?.show(part, from, to) }, text);
}
const lines = (a, b, part = 'input') => (a?.line == null ? '–' : lineLink(part, a.line, b?.line ?? a.line));
const words = (s) => (s == null ? '–' : String(s).replace(/_/g, ' '));
const stats = (s, digits, unit) => (s ? `${num(s.max, digits, unit)} max · ${num(s.mean, digits)} mean` : '–');

const TREATMENTS = { kept: 'kept (contour-parallel)', trochoid: 'trochoid', z_cut: 'z-cut division', opening: 'opening (helix + spiral)' };
/** A range of lengths in mm, in the display unit. */
const range = (lo, hi, digits = 2) => (lo == null ? '–' : Math.abs(lo - hi) < 10 ** -digits ? length(lo, digits) : `${coordinate(lo, digits)}–${length(hi, digits)}`);

const SUMMARIES = {
  analysis(r) {
    const s = r.summary || {};
    return [
      figures([
        ['Tool', r.tool?.name], ['Material', r.material?.name],
        ['Cutting length', length(s.cutting_length_mm)], ['Air-cut length', length(s.air_cut_length_mm)],
        ['Time at programmed feeds', minutes(s.time_at_programmed_feeds_min)],
        ['Engagement α', stats(s.alpha_deg, 1, '°'), s.alpha_deg?.max > s.alpha_limit_deg ? 'bad' : 'good'],
        ['Chip thickness t_m', stats(s.t_m_um, 1, 'µm')], ['Force', stats(s.force_n, 0, 'N')],
        ['Critical regions', `${s.critical_regions ?? 0} (${length(s.critical_length_mm)}) above ${num(s.alpha_limit_deg, 0)}°`, s.critical_regions ? 'bad' : 'good'],
      ]),
      regionsTable(r.critical_regions || []),
    ];
  },
  trochoids(r) {
    const v = r.verification || {};
    return [
      figures([
        ['Tool', r.tool?.name], ['Pocket area', area(r.pocket_area_mm2)],
        ['Before: max α', num(r.base_max_alpha_deg, 1, '°'), r.base_max_alpha_deg > (v.alpha_limit_deg ?? 40) ? 'bad' : 'good'],
        ['After: max α outside z-cuts', num(v.outside_zcut?.max_alpha_deg, 1, '°'), v.outside_zcut?.overloaded ? 'bad' : 'good'],
        ['Verification', v.passed ? 'passed' : 'FAILED', v.passed ? 'good' : 'bad'],
        ['Gouges', num(v.gouges, 0), v.gouges ? 'bad' : 'good'], ['Uncleared area', area(v.uncleared_area_mm2, 1)],
        ['Trochoids', String((r.treatments || []).filter((t) => t.kind === 'trochoid').length)],
        ['Program', `${num(r.program?.lines, 0)} lines`],
      ]),
      overloadsTable(r.verification?.overloads || [], r.verification?.overload_stretches),
      table([
        ['Treatment', (t) => TREATMENTS[t.kind] || t.kind], ['Class', (t) => t.class ?? '–'],
        ['Loops / passes', (t) => (t.kind === 'z_cut' ? `${num(t.passes_per_level, 0)} passes` : t.loops ? num(t.loops, 0) : '–')],
        ['Pitch', (t) => range(t.pitch_min_mm, t.pitch_max_mm)],
        ['Loop radius', (t) => range(t.loop_radius_min_mm, t.loop_radius_max_mm)],
        ['Area', (t) => area(t.area_mm2)], ['Time', (t) => minutes(t.time_min)],
      ], r.treatments || [], { limit: 15 }),
    ];
  },
  feeds(r) {
    const b = r.before || {}; const a = r.after || {};
    return [
      figures([
        ['Tool', r.tool?.name], ['Strategy', `${words(r.strategy)} (${words(r.mode)})`],
        ['Target force', num(r.target_force_n, 1, 'N')],
        ['Time before → after', `${minutes(b.time_min)} → ${minutes(a.time_min)}`],
        ['Force before', stats(b.force_n, 0, 'N')], ['Force after', stats(a.force_n, 0, 'N')],
        ['Feed after', `${feed(a.feed_mm_min?.mean)} mean (${feed(r.limits?.min_feed_mm_min)} to ${feed(r.limits?.max_feed_mm_min)} allowed)`],
        ['Shortfalls', String((r.shortfalls || []).length), (r.shortfalls || []).length ? 'warn' : 'good'],
        ['Program', `${num(r.program?.moves_in, 0)} → ${num(r.program?.moves_out, 0)} moves, ${num(r.program?.lines, 0)} lines`],
      ]),
      (r.shortfalls || []).length ? h('h3', {}, 'Where the target cannot be held') : null,
      (r.shortfalls || []).length ? table([
        ['Kind', (s) => words(s.kind)], ['NC lines', (s) => lines(s.start, s.end)], ['Length', (s) => length(s.length_mm)],
        ['Max α', (s) => num(s.max_alpha_deg, 1, '°')]], r.shortfalls, { limit: 15 }) : null,
    ];
  },
  costing(r) {
    const t = r.time || {}; const l = r.tool_life || {}; const c = r.cost || {};
    return [
      figures([
        ['Tool', r.tool?.name], ['Machine', r.machine?.name],
        ['Time (nominal)', minutes(t.nominal_min)], ['Time (with acceleration, jerk)', minutes(t.kinematic_min)],
        ['Tool-life consumption', `${num((l.consumption ?? 0) * 100, 2)} % of one tool`],
        ['Equivalent life', `${num(l.equivalent_life?.centre_path_m, 1, 'm')} of tool-centre path, ${num(l.equivalent_life?.machined_surface_m, 1, 'm')} of machined surface`],
        ['Cost', `${num(c.total, 2)} ${c.currency || ''}`], ['Machine / tool cost', `${num(c.machine, 2)} / ${num(c.tool, 2)} ${c.currency || ''}`],
        ['Removed', `${num((r.removed_volume_mm3 ?? 0) / 1000, 2)} cm³ at ${num(r.removal_rate_cm3_min, 2)} cm³/min`],
      ]),
      h('h3', {}, 'Where the tool wears'),
      table([['NC line', (w) => lineLink('input', w.line)], ['Share of wear', (w) => `${num(w.share * 100, 1)} %`],
        ['Cut', (w) => length(w.cutting_length_mm)], ['Max α (°)', (w) => num(w.max_alpha_deg, 1)]], (l.by_line || []).slice(0, 8)),
    ];
  },
  plan(r) {
    const tot = r.totals || {}; const tu = r.tuning || {}; const cmp = r.comparison;
    const chosen = (r.candidates || []).find((c) => c.tool_id === r.chosen_tool_id);
    return [
      figures([
        ['Chosen tool', chosen?.name || String(r.chosen_tool_id)], ['Layers', String((r.layers || []).length)],
        ['Cutting length', length(tot.cutting_length_mm, 0)], ['Time (kinematic)', minutes(tot.kinematic_time_min)],
        ['Cost', `${num(tot.cost, 2)} ${tot.currency || ''}`], ['Tool life used', `${num((tu.consumption ?? 0) * 100, 1)} % (force × ${num(tu.force_factor, 2)}, ${words(tu.outcome)})`],
        cmp ? ['Vs. ball-end baseline', `time × ${num(cmp.kinematic_time_ratio, 2)}, cost × ${num(cmp.cost_ratio, 2)}, saves ${minutes(cmp.time_saved_min)}`] : null,
      ]),
      h('h3', {}, 'Candidates'),
      table([['Tool', (c) => c.name], ['Status', (c) => words(c.status)], [`Cost (${tot.currency || ''})`, (c) => num(c.cost, 2)],
        ['Trochoids', (c) => num(c.trochoids, 0)], ['Max α (°)', (c) => num(c.max_alpha_deg, 1)], ['Why not', (c) => c.reason || '']], r.candidates || [], { limit: 15 }),
      h('h3', {}, 'Layers'),
      table([['Layer', (l) => l.index + 1], ['Role', (l) => words(l.role)], [`z (${lengthUnit()})`, (l) => `${coordinate(l.z_top)} → ${coordinate(l.z_bottom)}`],
        ['Trochoids', (l) => num(l.trochoids, 0)], ['Max α before → after (°)', (l) => `${num(l.base_max_alpha_deg, 1)} → ${num(l.max_alpha_deg, 1)}`],
        ['Checked', (l) => (l.verification_passed ? 'passed' : 'failed')]], r.layers || [], { limit: 15 }),
      overloadsTable((r.layers || []).flatMap((l) => l.overloads || [])),
    ];
  },
};

function regionsTable(regions) {
  if (!regions.length) return h('p', { class: 'muted' }, 'No critical regions: the engagement stays below the limit.');
  return h('div', {}, h('h3', {}, 'Critical regions'), table([
    ['Kind', (c) => words(c.kind)], ['NC lines', (c) => lines(c.start, c.end)], ['Length', (c) => length(c.length_mm)],
    ['Max α', (c) => num(c.max_alpha_deg, 1, '°')], ['Max force', (c) => num(c.max_force_n, 0, 'N')],
    ['At', (c) => (c.at_max ? `X${coordinate(c.at_max.x)} Y${coordinate(c.at_max.y)} Z${coordinate(c.at_max.z)}` : '–')]], regions, { limit: 15 }));
}

/** The overloads a check left (trochoids, plans), each with its lines of the job's program. */
function overloadsTable(list, count) {
  if (!list.length) return null;
  return h('div', {}, h('h3', {}, `Overloads left (${num(count ?? list.length, 0)})`), table([
    ['NC lines', (o) => (o.program_lines ? lineLink('main', o.program_lines[0], o.program_lines[1]) : '–')],
    ['Length', (o) => length(o.length_mm)], ['Max α', (o) => num(o.max_alpha_deg, 1, '°')],
    ['At', (o) => `X${coordinate(o.x)} Y${coordinate(o.y)} Z${coordinate(o.z)}`],
    ['Where', (o) => (o.in_zcut_region ? 'crossing a z-cut region' : 'outside the z-cut regions')]], list, { limit: 15 }));
}

function warnings(list) {
  return list?.length ? h('div', { class: 'warning' }, h('strong', {}, 'Warnings'), h('ul', {}, list.map((w) => h('li', {}, w)))) : null;
}

export async function jobView(id) {
  let job = await api('GET', `/v1/jobs/${encodeURIComponent(id)}`);
  let timer = null;
  let stopped = false;
  const head = h('div', { class: 'job-head' });
  const status = h('div', { class: 'card status-card', 'aria-live': 'polite' });
  const body = h('div', { class: 'job-body' });
  const node = h('div', {}, head, status, body);

  // The job's name and tags, and an editor for them (PATCH /v1/jobs/{id}).
  function renderHead() {
    const edit = h('button', { type: 'button', class: 'link', id: 'edit-labels', onclick: () => editLabels() }, 'Rename or retag');
    head.replaceChildren(
      h('p', { class: 'crumbs' }, h('a', { href: '#/jobs' }, 'Jobs'), ' / ', h('span', { class: 'mono' }, job.id.slice(0, 8))),
      h('h1', {}, job.name || KIND_NAMES[job.kind] || job.kind),
      h('p', { class: 'muted' }, `${job.name ? `${KIND_NAMES[job.kind] || job.kind} · ` : ''}Job ${job.id} · created ${when(job.created_at)} · `, edit),
      ...[tagList(job.tags)].filter(Boolean));
  }

  function editLabels() {
    const name = h('input', { id: 'label-name', type: 'text', maxlength: 200, value: job.name || '', autocomplete: 'off', placeholder: 'no name' });
    const tags = h('input', { id: 'label-tags', type: 'text', value: (job.tags || []).join(' '), autocomplete: 'off', spellcheck: 'false', placeholder: 'die:4711 roughing' });
    const slot = h('div', { 'aria-live': 'polite' });
    const field = (id, label, control, hint) => h('div', { class: 'field' }, h('label', { for: id }, label), control, h('small', { class: 'hint' }, hint));
    const form = h('form', { class: 'card labels-editor', id: 'labels-editor', onsubmit: async (event) => {
      event.preventDefault();
      slot.replaceChildren();
      form.querySelectorAll('.field-error').forEach((e) => e.remove());
      try {
        job = await api('PATCH', `/v1/jobs/${job.id}`, { name: name.value.trim() || null, tags: parseTags(tags.value) });
        renderHead();
      } catch (err) {
        slot.append(problemBox(err, 'The name or tags were refused'));
        for (const e of err.problem?.errors || []) {
          const input = e.field === 'name' ? name : e.field.startsWith('tags') ? tags : null;
          input?.setAttribute('aria-invalid', 'true');
          input?.closest('.field').append(h('small', { class: 'field-error' }, e.reason));
        }
      }
    } },
    h('div', { class: 'grid' },
      field('label-name', 'Name', name, 'Up to 200 characters; empty for none.'),
      field('label-tags', 'Tags', tags, 'Separated by spaces or commas: letters, digits and - _ . : / (up to 20).')),
    slot,
    h('div', { class: 'actions' }, h('button', { type: 'submit', class: 'primary', id: 'save-labels' }, 'Save'),
      h('button', { type: 'button', onclick: () => renderHead() }, 'Cancel')));
    head.querySelector('#labels-editor')?.remove();
    head.append(form);
    name.focus();
  }
  renderHead();

  function renderStatus() {
    const running = job.status === 'queued' || job.status === 'running';
    const pct = Math.round((job.progress || 0) * 100);
    const cancel = h('button', { type: 'button', class: 'danger', disabled: job.cancel_requested, onclick: async () => {
      cancel.disabled = true;
      try { job = await api('DELETE', `/v1/jobs/${job.id}`); renderStatus(); } catch (err) { status.append(problemBox(err, 'Could not cancel')); }
    } }, job.cancel_requested ? 'Cancelling…' : 'Cancel job');
    status.replaceChildren(...[
      h('div', { class: 'status-line' }, badge(job.status),
        h('span', {}, running
          ? `${pct} %${job.started_at ? ` · running for ${duration(job.started_at)} · ${remaining(job.progress, job.started_at) || 'estimating the time left'}` : ' · waiting for a worker'}`
          : `finished ${when(job.finished_at)} · ran ${duration(job.started_at, job.finished_at)}`),
        running ? cancel : h('span', { class: 'actions tight' },
          job.status === 'succeeded' && job.kind === 'feeds' ? h('a', { class: 'button', href: `#/new?cost=${job.id}` }, 'Cost this program') : null,
          h('a', { class: 'button', href: `#/new?from=${job.id}` }, 'Edit as a new job'))),
      running ? h('progress', { max: 100, value: pct, 'aria-label': 'progress' }, `${pct} %`) : null,
      job.status === 'failed' && job.error ? problemBox({ problem: job.error }, 'The job failed') : null,
      job.status === 'cancelled' ? h('p', { class: 'muted' }, 'The job was cancelled before it finished.') : null,
    ].filter(Boolean));
  }

  // The input is served apart from the job (it may be large): read when opened.
  function inputPanel(job) {
    const pre = h('pre', { class: 'code' }, 'Loading…');
    const panel = h('details', { class: 'card raw' }, h('summary', {}, 'Input (JSON)'), pre);
    let loaded = false;
    panel.addEventListener('toggle', async () => {
      if (!panel.open || loaded) return;
      loaded = true;
      try {
        pre.textContent = pretty(await api('GET', job.links.input));
      } catch (err) {
        loaded = false;
        pre.textContent = `Could not read the input: ${err.message || err}`;
      }
    });
    return panel;
  }

  function renderResult() {
    const r = job.result || {};
    const parts = [];
    program = programPanel(job);
    parts.push(h('section', { class: 'card' }, h('h2', {}, 'Result'), ...(SUMMARIES[job.kind]?.(r) || [h('p', { class: 'muted' }, 'See the raw result below.')]), warnings(r.warnings)));
    parts.push(savingsPanel(job.kind, r));
    parts.push(drawingPanel(job, program));
    parts.push(view3dPanel(job));
    parts.push(program?.node);
    parts.push(h('details', { class: 'card raw' }, h('summary', {}, 'Raw result (JSON)'), h('pre', { class: 'code' }, pretty(job.result))));
    parts.push(inputPanel(job));
    body.replaceChildren(...parts.filter(Boolean));
  }

  async function poll() {
    if (stopped) return;
    try {
      job = await api('GET', `/v1/jobs/${job.id}`);
    } catch (err) {
      if (stopped) return;
      status.replaceChildren(problemBox(err, 'Lost contact with the service; trying again every few seconds'));
      timer = setTimeout(poll, 5 * POLL_MS);
      return;
    }
    if (stopped) return;
    renderStatus();
    if (job.status === 'succeeded') renderResult();
    else if (job.status === 'queued' || job.status === 'running') timer = setTimeout(poll, POLL_MS);
  }

  renderStatus();
  if (job.status === 'succeeded') renderResult();
  else if (job.status === 'queued' || job.status === 'running') timer = setTimeout(poll, POLL_MS);
  return { node, title: job.name || `${job.kind} ${job.id.slice(0, 8)}`, cleanup: () => { stopped = true; clearTimeout(timer); } };
}
