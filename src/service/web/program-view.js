// The NC programs of a job, readable on the page: each program the job has (the one it
// wrote, the one it started from, a plan's baseline) with line numbers, virtualised so
// that a program of 100k lines and more scrolls smoothly (only the rows in view are in the
// DOM); a feeds job's changed lines side by side; downloads. Linked both ways with the
// drawing and the tables: `show(part, from, to)` scrolls to and selects lines, and a
// selection of lines is announced (`onSelect`) so the drawing can mark its moves.
import { h, api, downloadLink, problemBox, num } from './ui.js';

/** Height of one row, px (the CSS gives .nc-row the same height). */
const ROW_PX = 20;
/** Rows drawn above and below the visible ones. */
const OVERSCAN = 12;
/** Rows of the view's height. */
const VIEW_ROWS = 22;
/** How far ahead the diff looks for the line an edited line continues with. */
const DIFF_LOOKAHEAD = 64;

/** The programs of a job of `kind`: [part, label]; `input` is the G-code it was sent. */
function partsOf(job) {
  const r = job.result || {};
  const parts = [];
  if (job.links?.program) {
    parts.push(['main', { feeds: 'Optimised program', trochoids: 'Program with trochoids', plan: 'Planned program' }[job.kind] || 'Program']);
  }
  if (job.kind === 'trochoids' && job.links?.program) parts.push(['base', 'Base program (before)']);
  if (job.kind === 'plan' && r.baseline) parts.push(['baseline', `Baseline (${r.baseline.tool})`]);
  if (['feeds', 'analysis', 'costing'].includes(job.kind)) parts.push(['input', 'Program sent']);
  if (job.kind === 'feeds') parts.push(['diff', 'Changed lines']);
  return parts;
}

/** The file name of a downloaded part. */
const fileName = (job, part) => `dieplan-${job.kind}-${job.id.slice(0, 8)}${part === 'main' ? '' : `-${part}`}.nc`;

/**
 * Aligns the program sent (`a`) with the edited one (`b`): the editor changes only F words
 * and may split a move into several blocks, so a line of `b` whose motion (F words left
 * out) is that of the next line of `a` continues it, and lines of `b` before it are blocks
 * split off. Returns the rows that changed: [lineA|null, textA, lineB|null, textB].
 */
export function changedLines(a, b) {
  const motion = (line) => line.replace(/\bF\s*[-+]?[\d.]+/gi, '').replace(/\s+/g, ' ').trim();
  const rows = [];
  let i = 0;
  let j = 0;
  while (i < a.length || j < b.length) {
    if (i >= a.length) { rows.push([null, '', j + 1, b[j]]); j++; continue; }
    if (j >= b.length) { rows.push([i + 1, a[i], null, '']); i++; continue; }
    if (a[i] === b[j]) { i++; j++; continue; }
    const target = motion(a[i]);
    if (motion(b[j]) === target) { rows.push([i + 1, a[i], j + 1, b[j]]); i++; j++; continue; }
    let k = j + 1;
    const end = Math.min(b.length, j + DIFF_LOOKAHEAD);
    while (k < end && motion(b[k]) !== target) k++;
    if (k < end) {
      for (; j < k; j++) rows.push([null, '', j + 1, b[j]]);
    } else {
      rows.push([i + 1, a[i], j + 1, b[j]]);
      i++; j++;
    }
  }
  return rows;
}

/** A virtualised list of `count` rows of ROW_PX, drawn by `row(index)`. */
export function virtualList(count, row, { label }) {
  const rows = h('div', { class: 'nc-rows' });
  const spacer = h('div', { class: 'nc-spacer', style: `height: ${count * ROW_PX}px` }, rows);
  const view = h('div', { class: 'nc-view', tabindex: '0', role: 'region', 'aria-label': label, style: `height: ${Math.min(count, VIEW_ROWS) * ROW_PX + 2}px` }, spacer);
  let drawn = [-1, -1];
  let pending = false;
  const draw = (force = false) => {
    pending = false;
    const first = Math.max(0, Math.floor(view.scrollTop / ROW_PX) - OVERSCAN);
    const last = Math.min(count, Math.ceil((view.scrollTop + (view.clientHeight || VIEW_ROWS * ROW_PX)) / ROW_PX) + OVERSCAN);
    if (!force && first === drawn[0] && last === drawn[1]) return;
    drawn = [first, last];
    rows.style.transform = `translateY(${first * ROW_PX}px)`;
    const made = [];
    for (let i = first; i < last; i++) made.push(row(i));
    rows.replaceChildren(...made);
  };
  view.addEventListener('scroll', () => {
    if (!pending) { pending = true; requestAnimationFrame(() => draw()); }
  });
  return {
    node: view,
    draw,
    /** Scrolls row `index` into the middle of the view. */
    reveal(index) {
      view.scrollTop = Math.max(0, index * ROW_PX - (view.clientHeight || VIEW_ROWS * ROW_PX) / 2 + ROW_PX);
      draw(true);
    },
  };
}

/**
 * The program panel of a finished job. Returns { node, show(part, from, to), onSelect(fn),
 * partFor(pathName) } or null when the job has no program to show.
 */
export function programPanel(job) {
  const parts = partsOf(job);
  if (!parts.length) return null;
  const texts = new Map();
  const listeners = [];
  const state = { part: parts[0][0], selection: null };
  const body = h('div', { class: 'nc-body' }, h('p', { class: 'muted' }, 'Loading the program…'));
  const status = h('p', { class: 'hint nc-status', 'aria-live': 'polite' });
  const select = h('select', { id: 'program-part', onchange: () => load(select.value) },
    parts.map(([value, label]) => h('option', { value }, label)));
  const downloads = h('p', { class: 'actions' }, parts.filter(([p]) => p !== 'diff' && p !== 'input').map(([part, label]) => {
    const id = { main: 'download-program', baseline: 'download-baseline', base: 'download-base' }[part];
    const href = part === 'main' ? job.links.program : `${job.links.program}?part=${part}`;
    return downloadLink(href, fileName(job, part), { class: part === 'main' ? 'button primary' : 'button', id }, `Download: ${label.toLowerCase()}`);
  }));
  const node = h('section', { class: 'card program-card', id: 'program' },
    h('h2', {}, 'NC program'), downloads,
    h('div', { class: 'field inline' }, h('label', { for: 'program-part' }, 'Show'), select),
    status, body,
    h('p', { class: 'hint' }, 'Click a line to select it, shift-click to select a range: the drawing marks the overloads on those lines. Click a region in the drawing or an NC line in a table to come here.'));
  let list = null;

  async function text(part) {
    if (texts.has(part)) return texts.get(part);
    let promise;
    if (part === 'input') {
      promise = api('GET', job.links.input).then((input) => {
        const gcode = input?.program?.gcode;
        if (typeof gcode !== 'string') throw new Error('the program was sent as JSON moves, not as G-code: its moves are listed in the input below');
        return gcode;
      });
    } else {
      promise = api('GET', part === 'main' ? job.links.program : `${job.links.program}?part=${part}`, undefined, { text: true });
    }
    promise = promise.then((t) => t.replace(/\r\n?/g, '\n').replace(/\n$/, '').split('\n'));
    texts.set(part, promise);
    promise.catch(() => texts.delete(part));
    return promise;
  }

  const selected = (n) => state.selection && state.selection.part === state.part && n >= state.selection.from && n <= state.selection.to;

  function choose(n, extend) {
    const s = state.selection;
    const [from, to] = extend && s && s.part === state.part ? [Math.min(s.anchor, n), Math.max(s.anchor, n)] : [n, n];
    state.selection = { part: state.part, from, to, anchor: extend && s ? s.anchor : n };
    list?.draw(true);
    announce();
  }

  function announce() {
    const s = state.selection;
    status.textContent = s ? `Selected line${s.from === s.to ? ` ${s.from}` : `s ${s.from}–${s.to}`} of the ${select.selectedOptions[0]?.textContent.toLowerCase()}.` : '';
    for (const fn of listeners) fn(s ? { part: s.part, from: s.from, to: s.to } : null);
  }

  async function load(part) {
    state.part = part;
    select.value = part;
    body.replaceChildren(h('p', { class: 'muted' }, 'Loading the program…'));
    try {
      if (part === 'diff') return await loadDiff();
      const lines = await text(part);
      if (state.part !== part) return;
      const digits = String(lines.length).length;
      list = virtualList(lines.length, (i) => {
        const n = i + 1;
        return h('div', { class: selected(n) ? 'nc-row selected' : 'nc-row', dataset: { line: n }, onclick: (e) => choose(n, e.shiftKey) },
          h('span', { class: 'nc-ln', style: `width: ${digits + 1}ch` }, n), h('span', { class: 'nc-tx' }, lines[i]));
      }, { label: 'NC program' });
      body.replaceChildren(h('p', { class: 'hint' }, `${num(lines.length, 0)} lines`), list.node);
      list.draw(true);
      if (selected(state.selection?.from)) list.reveal(state.selection.from - 1);
    } catch (err) {
      if (state.part === part) body.replaceChildren(problemBox(err, 'This program cannot be shown'));
    }
  }

  async function loadDiff() {
    const [a, b] = await Promise.all([text('input'), text('main')]);
    if (state.part !== 'diff') return;
    const rows = changedLines(a, b);
    if (!rows.length) {
      list = null;
      body.replaceChildren(h('p', { class: 'muted' }, 'No line changed: the program keeps its feeds.'));
      return;
    }
    const cell = (n, t, side) => [h('span', { class: 'nc-ln' }, n ?? ''), h('span', { class: `nc-tx ${side}` }, t)];
    list = virtualList(rows.length, (i) => {
      const [la, ta, lb, tb] = rows[i];
      const kind = la == null ? 'added' : lb == null ? 'removed' : 'changed';
      return h('div', { class: `nc-row nc-diff ${kind}`, dataset: { before: la ?? '', after: lb ?? '' } }, cell(la, ta, 'before'), cell(lb, tb, 'after'));
    }, { label: 'changed lines' });
    const changed = rows.filter((r) => r[0] != null && r[2] != null).length;
    body.replaceChildren(
      h('p', { class: 'hint' }, `${num(changed, 0)} lines changed, ${num(rows.length - changed, 0)} blocks added (a move split where its feed changes) of ${num(a.length, 0)} → ${num(b.length, 0)} lines.`),
      h('div', { class: 'nc-diff-head' }, h('span', {}, 'Program sent'), h('span', {}, 'Optimised program')), list.node);
    list.draw(true);
  }

  load(state.part);
  return {
    node,
    /** Shows lines `from`–`to` of `part` (when the job has it), selected. */
    async show(part, from, to = from) {
      const wanted = parts.some(([p]) => p === part) ? part : state.part;
      state.selection = { part: wanted, from, to, anchor: from };
      if (wanted !== state.part || !list) await load(wanted);
      list?.reveal(from - 1);
      list?.draw(true);
      announce();
      node.scrollIntoView({ behavior: 'smooth', block: 'start' });
    },
    onSelect(fn) { listeners.push(fn); },
    /** The program a drawn path's lines refer to. */
    partFor(pathName) {
      if (job.kind === 'trochoids') return pathName === 'base' ? 'base' : 'main';
      if (job.kind === 'feeds') return pathName === 'optimised' ? 'main' : 'input';
      if (job.kind === 'plan') return pathName === 'baseline' ? 'baseline' : 'main';
      if (['analysis', 'costing'].includes(job.kind)) return 'input';
      return 'main';
    },
  };
}
