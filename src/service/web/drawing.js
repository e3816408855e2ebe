// The drawing of a finished job (GET /v1/jobs/{id}/views, then drawing.svg with the chosen
// path, colour quantity, layer and layers of detail) with zoom and pan, and its charts.
import { h, api, problemBox, svgNode } from './ui.js';
import { zoomable, readoutLine, frameOf } from './zoom.js';
import { loadTrace, nearest, atDistance, describe, markLines } from './trace.js';
import { units, MM_PER_INCH, coordinate, lengthUnit } from './units.js';

const QUANTITIES = {
  alpha: 'Engagement angle α (°)',
  force: 'Cutting force (N)',
  feed: 'Feed (mm/min)',
  wear: 'Tool wear (% of a tool per m)',
};
const PATHS = { input: 'Input path', base: 'Base path (before trochoids)', planned: 'Planned path', optimised: 'Optimised path', program: 'Planned program', baseline: 'Ball-end baseline', stair_step: 'Stair-step roughing' };
const pathLabel = (name) => PATHS[name] || name.charAt(0).toUpperCase() + name.slice(1).replace(/_/g, ' ');
/** Layers of detail: query parameter, label, shown at first, the job kinds that have them. */
const TOGGLES = [
  ['regions', 'Critical regions', true, null],
  ['trochoids', 'Trochoids', true, ['trochoids', 'plan']],
  ['medial', 'Medial axis', true, ['trochoids', 'plan']],
  ['rapids', 'Rapids', false, null],
];

// Width of each drawing of the before-and-after strip, px.
const COMPARE_WIDTH_PX = 700;
/** Bounds of the charts' width parameter, px (as the API checks them). */
const CHART_MIN_PX = 200;
const CHART_MAX_PX = 4000;
// A chart is drawn again when its width changes by more than this share, after the
// window has been still for this long.
const CHART_REDRAW_RATIO = 0.2;
const CHART_REDRAW_DELAY_MS = 250;

async function loadSvg(href, target) {
  try {
    const svg = svgNode(await api('GET', href, undefined, { text: true }));
    svg.removeAttribute('height');
    svg.setAttribute('width', '100%');
    target.replaceChildren(svg);
    return svg;
  } catch (err) {
    target.replaceChildren(problemBox(err, 'Could not draw this'));
    return null;
  }
}

/** A layer's name with its heights in the display unit (the API's names are in mm). */
function layerName(l) {
  const head = (l.name || `layer ${l.index + 1}`).split(' (z')[0];
  return units() === 'inch' || !l.name ? `${head} (z ${coordinate(l.z_top)} → ${coordinate(l.z_bottom)} ${lengthUnit()})` : l.name;
}

/** Pointer travel below which a press on the drawing is a click, not a pan, px. */
const CLICK_SLOP_PX = 4;

/**
 * Links the drawing with the program panel: a click on a critical region (its band or
 * its label) shows its NC lines; lines selected in the program mark the regions on them.
 */
function linkToProgram(canvas, program, pathName, linked) {
  if (!program) return;
  let press = null;
  canvas.addEventListener('pointerdown', (event) => {
    const mark = event.target.closest?.('.region, .region-label');
    press = mark ? { mark, x: event.clientX, y: event.clientY } : null;
  }, { capture: true });
  canvas.addEventListener('pointerup', (event) => {
    if (!press || Math.hypot(event.clientX - press.x, event.clientY - press.y) > CLICK_SLOP_PX) return;
    const [from, to] = (press.mark.getAttribute('data-lines') || '').split('-').map(Number);
    press = null;
    if (Number.isFinite(from)) program.show(program.partFor(pathName()), from, Number.isFinite(to) ? to : from);
  });
  program.onSelect((selection) => {
    linked.selection = selection;
    markSelection(canvas, program, pathName(), linked);
  });
}

/** Marks the regions on the selected NC lines and their moves (from the path's trace). */
function markSelection(canvas, program, pathName, linked) {
  const svg = canvas.querySelector('svg');
  const selection = linked.selection;
  if (!svg || !program) return;
  const same = selection && program.partFor(pathName) === selection.part;
  for (const mark of svg.querySelectorAll('.region, .region-label')) {
    const [from, to] = (mark.getAttribute('data-lines') || '').split('-').map(Number);
    mark.classList.toggle('linked', Boolean(same && from <= selection.to && to >= selection.from));
  }
  const trace = linked.trace?.path === pathName ? linked.trace : null;
  markLines(svg, frameOf(svg), trace, same ? selection.from : null, same ? selection.to : null);
}

export function drawingPanel(job, program) {
  const section = h('section', { class: 'card drawing-card' }, h('h2', {}, 'Drawing'));
  const chartsSection = h('section', { class: 'card charts-card' }, h('h2', {}, 'Charts'));
  const wrap = h('div', {}, section, chartsSection);
  if (!job.links?.views) {
    section.append(h('p', { class: 'muted' }, 'This job has nothing to draw.'));
    chartsSection.remove();
    return wrap;
  }
  const body = h('div', {}, h('p', { class: 'muted' }, 'Loading the drawing…'));
  section.append(body);
  // What the drawing and the charts share: the drawn path's trace and the selected lines.
  const linked = { trace: null, selection: null, path: null };
  api('GET', job.links.views).then((views) => {
    renderDrawing(views, body, job.kind, program, linked);
    renderCharts(views, chartsSection, program, linked);
  }).catch((err) => {
    body.replaceChildren(problemBox(err, 'No drawing'));
    chartsSection.remove();
  });
  return wrap;
}

/** What a job changes, by kind: the quantity both sides of its before-and-after strip are coloured by. */
const CHANGED = { feeds: 'feed', trochoids: 'alpha', plan: 'feed' };

// Before and after side by side (the first and the last path, e.g. the base path with
// its overloads and the planned one with its trochoids), as images: the job at a glance.
// Both are coloured by what the job changes (a feeds job the feed, the others α), on one
// scale for both, so that a colour is the same value on either side.
function compareStrip(views, paths, kind) {
  if (paths.length < 2) return [];
  const [first, last] = [paths[0], paths.at(-1)];
  const wanted = CHANGED[kind] || 'alpha';
  const common = [wanted, 'alpha', 'feed'].find((q) => first.quantities.includes(q) && last.quantities.includes(q));
  const [before, after] = kind === 'plan' ? ['Baseline', 'Plan'] : ['Before', 'After'];
  const figure = (path, caption) => {
    const q = new URLSearchParams({ path: path.name, width: String(COMPARE_WIDTH_PX), rapids: 'false' });
    if (common) q.set('color', common);
    const src = `${views.drawing}?${q}`;
    return h('figure', { class: 'compare-item' },
      h('a', { href: src, target: '_blank', rel: 'noopener' },
        h('img', { src, alt: `${caption}: ${pathLabel(path.name)}`, loading: 'lazy' })),
      h('figcaption', {}, h('strong', {}, caption), ` · ${pathLabel(path.name)}`));
  };
  return [h('div', { class: 'compare', dataset: { color: common || '' } }, figure(first, before), figure(last, after)),
    common ? h('p', { class: 'hint' }, `Both coloured by ${QUANTITIES[common] || common}, on one scale.`) : null];
}

function renderDrawing(views, body, kind, program, linked) {
  const paths = views.paths || [];
  const toggles = TOGGLES.filter(([, , , kinds]) => !kinds || kinds.includes(kind));
  const state = { path: paths.at(-1)?.name, color: null, layer: '', window: null, toggles: Object.fromEntries(toggles.map(([k, , v]) => [k, v])) };
  const info = readoutLine();
  const canvas = h('div', { class: 'drawing-canvas', id: 'drawing' });
  const controls = h('div', { class: 'drawing-controls' });
  const openLink = h('a', { target: '_blank', rel: 'noopener' }, 'Open the SVG');
  let zoom = () => {};
  let request = 0;
  linkToProgram(canvas, program, () => state.path, linked);
  // The trace of the path shown: read under the pointer, and marks the selected lines.
  const traceOf = (path) => {
    linked.path = path;
    if (linked.trace?.path === path) return;
    loadTrace(views.drawing, path).then((trace) => {
      if (linked.path !== path) return;
      linked.trace = trace;
      markSelection(canvas, program, state.path, linked);
    }).catch(() => { linked.trace = null; });
  };
  const probe = (x, y, radiusMm) => {
    const trace = linked.trace?.path === state.path ? linked.trace : null;
    const i = trace ? nearest(trace, x, y, radiusMm) : -1;
    return i < 0 ? null : describe(trace, i);
  };

  const url = () => {
    const q = new URLSearchParams();
    if (state.path) q.set('path', state.path);
    if (state.color) q.set('color', state.color);
    if (state.layer !== '') q.set('layer', state.layer);
    for (const [k, v] of Object.entries(state.toggles)) q.set(k, String(v));
    q.set('width', String(Math.max(320, Math.min(2400, Math.round(canvas.clientWidth || 900)))));
    if (state.window) for (const k of ['x_min', 'y_min', 'x_max', 'y_max']) q.set(k, String(state.window[k]));
    // The frame's coordinates, the scale bar and the feed legend in the display unit.
    if (units() === 'inch') q.set('units', 'inch');
    return `${views.drawing}?${q}`;
  };
  let drawnWidth = 0;
  async function draw() {
    const mine = ++request;
    drawnWidth = canvas.clientWidth;
    canvas.classList.add('loading');
    const href = url();
    openLink.href = href;
    const svg = await loadSvg(href, h('div'));
    if (mine !== request) return;
    canvas.classList.remove('loading');
    if (svg) {
      canvas.replaceChildren(svg);
      zoom = zoomable(svg, canvas, { window: state.window, info, probe, detail: views.detail_mm, redraw: (window) => { state.window = window; draw(); } });
      markSelection(canvas, program, state.path, linked);
      traceOf(state.path);
    } else {
      canvas.replaceChildren(problemBox({ message: 'The drawing could not be loaded.' }));
    }
  }
  function renderControls() {
    const current = paths.find((p) => p.name === state.path) || paths[0] || { quantities: [] };
    if (!current.quantities.includes(state.color)) state.color = current.quantities[0] || null;
    const select = (id, label, options, value, set) => h('div', { class: 'field' }, h('label', { for: id }, label),
      h('select', { id, onchange: (e) => { set(e.target.value); renderControls(); draw(); } },
        options.map(([v, text]) => h('option', { value: v, selected: String(v) === String(value) }, text))));
    controls.replaceChildren(...[
      paths.length > 1 ? select('draw-path', 'Path', paths.map((p) => [p.name, pathLabel(p.name)]), state.path, (v) => { state.path = v; }) : null,
      current.quantities.length ? select('draw-color', 'Colour by', current.quantities.map((q) => [q, QUANTITIES[q] || q]), state.color, (v) => { state.color = v; }) : null,
      (views.layers || []).length > 1 ? select('draw-layer', 'Layer', [['', 'All layers'], ...views.layers.map((l) => [l.index, layerName(l)])], state.layer, (v) => { state.layer = v; }) : null,
      h('fieldset', { class: 'toggles' }, h('legend', {}, 'Show'), toggles.map(([key, label]) => h('label', {},
        h('input', { type: 'checkbox', checked: state.toggles[key], onchange: (e) => { state.toggles[key] = e.target.checked; draw(); } }), ` ${label}`))),
      h('div', { class: 'zoom', role: 'group', 'aria-label': 'zoom' },
        h('button', { type: 'button', title: 'Zoom in', 'aria-label': 'Zoom in', onclick: () => zoom('in') }, '+'),
        h('button', { type: 'button', title: 'Zoom out', 'aria-label': 'Zoom out', onclick: () => zoom('out') }, '−'),
        h('button', { type: 'button', title: 'Show the whole drawing', onclick: () => zoom('fit') }, 'Fit')),
    ].filter(Boolean));
  }
  renderControls();
  body.replaceChildren(...compareStrip(views, paths, kind).filter(Boolean), controls, canvas, info, h('p', { class: 'hint' }, 'Scroll to zoom, drag to pan: the drawing is drawn again for what is in view. ', openLink));
  requestAnimationFrame(draw);
  // Drawn at the width it is shown at, so its text keeps its size: drawn again when the
  // window makes it much wider or narrower (a phone turned, a window resized).
  if (typeof ResizeObserver === 'function') {
    let pending = null;
    const observer = new ResizeObserver(() => {
      if (!canvas.isConnected) {
        if (drawnWidth) observer.disconnect();
        return;
      }
      clearTimeout(pending);
      pending = setTimeout(() => {
        if (drawnWidth && Math.abs(canvas.clientWidth - drawnWidth) > CHART_REDRAW_RATIO * drawnWidth) draw();
      }, CHART_REDRAW_DELAY_MS);
    });
    observer.observe(canvas);
  }
}

/** The path distance (mm) under a click on a line chart, from its x axis's scale; null off the plot. */
function chartDistance(svg, event) {
  const axis = svg.querySelector('.x-axis[data-x-min]');
  const vb = svg.viewBox.baseVal;
  if (!axis || !vb?.width) return null;
  const n = (k) => Number(axis.getAttribute(`data-${k}`));
  const r = svg.getBoundingClientRect();
  const x = vb.x + ((event.clientX - r.left) / r.width) * vb.width;
  if (x < n('left') || x > n('right')) return null;
  const s = n('x-min') + ((x - n('left')) / (n('right') - n('left'))) * (n('x-max') - n('x-min'));
  return svg.dataset.units === 'inch' ? s * MM_PER_INCH : s;
}

/** A click on a chart of path distance shows the NC line there (of the path drawn). */
function linkChart(target, program, linked) {
  if (!program) return;
  target.addEventListener('click', (event) => {
    const svg = target.querySelector('svg');
    const s = svg ? chartDistance(svg, event) : null;
    const trace = linked.trace;
    if (s == null || !trace) return;
    const i = atDistance(trace, s);
    if (i < 0) return;
    const line = trace.v.line[i];
    target.dataset.line = String(line);
    program.show(program.partFor(trace.path), line, line);
  });
  target.title = 'Click a point of the chart to show its NC line';
}

function renderCharts(views, section, program, linked) {
  const charts = views.charts || [];
  if (!charts.length) {
    section.remove();
    return;
  }
  const grid = h('div', { class: 'charts' });
  const targets = charts.map((chart) => {
    const target = h('div', { class: 'chart-canvas' }, h('p', { class: 'muted' }, 'Loading…'));
    grid.append(h('figure', { class: 'chart', dataset: { chart: chart.id } }, h('figcaption', {}, chart.title || chart.id), target));
    linkChart(target, program, linked);
    return [chart, target];
  });
  section.append(grid);
  // Each chart is drawn at the width it is shown at, so its text keeps its size; when
  // the window makes it much wider or narrower, it is drawn again.
  const drawnAt = new Map();
  const load = (chart, target) => {
    const width = Math.max(CHART_MIN_PX, Math.min(CHART_MAX_PX, Math.round(target.clientWidth || 800)));
    const before = drawnAt.get(target);
    if (before && Math.abs(width - before) < CHART_REDRAW_RATIO * before) return;
    drawnAt.set(target, width);
    const url = new URL(chart.href, location.origin);
    url.searchParams.set('width', String(width));
    url.searchParams.set('height', String(Math.max(240, Math.min(420, Math.round(width * 0.5)))));
    // Path distances and feeds in the page's display unit.
    const unit = units();
    if (unit === 'inch') url.searchParams.set('units', unit);
    loadSvg(`${url.pathname}${url.search}`, target).then((svg) => { if (svg) svg.dataset.units = unit; });
  };
  requestAnimationFrame(() => targets.forEach(([chart, target]) => load(chart, target)));
  if (typeof ResizeObserver === 'function') {
    let pending = null;
    const observer = new ResizeObserver(() => {
      if (!grid.isConnected) {
        observer.disconnect();
        return;
      }
      clearTimeout(pending);
      pending = setTimeout(() => targets.forEach(([chart, target]) => load(chart, target)), CHART_REDRAW_DELAY_MS);
    });
    observer.observe(grid);
  }
}
