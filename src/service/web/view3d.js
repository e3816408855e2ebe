// The 3-D view of a finished job: the stock it left (GET /v1/jobs/{id}/stock) as a
// shaded mesh and its path (the trace) in 3-D, coloured by the drawing's quantities and
// colour scales, with orbit, pan and zoom, a layer slider (or, for a path of many cutting
// levels, a depth slider) and a time slider that plays the path with the tool, drawn in its
// shape, where it is.
import { h, api, num, problemBox } from './ui.js';
import { loadTrace, describe } from './trace.js';
import { createScene, hasWebGL } from './scene3d.js';
import { cuttingLevels, atLevel, downTo, depthControl, MAX_LEVELS } from './levels3d.js';
import { toolOf } from './tool3d.js';
import { units, MM_PER_INCH, coordinate, length, lengthUnit } from './units.js';

/** The whole path plays in this many seconds. */
const PLAY_SECONDS = 20;
/** Values within this of the α limit count as at it (as the drawing's). */
const LIMIT_TOLERANCE = 1e-6;
/** The tool's diameter when the result names none, as a share of the scene's size. */
const TOOL_SHARE = 0.02;
/** Heights above the tool's tip, as shares of its diameter, at which its radius is told to tests. */
const PROFILE_HEIGHTS = [0, 0.05, 0.25, 0.5];
const NAMES = { alpha: 'Engagement angle α', force: 'Cutting force', feed: 'Feed', wear: 'Tool wear' };

/** The bin of `value` on `scale` (the drawing's rule, see the trace's `scales`). */
export function binOf(scale, value) {
  const bins = scale.colors.length;
  const fraction = (v, lo, hi) => {
    const span = hi - lo;
    if (!Number.isFinite(v) || span <= Number.EPSILON * Math.max(Math.abs(hi), 1)) return 0;
    return Math.min(1, Math.max(0, (v - lo) / span));
  };
  const bin = (f, n) => Math.min(n - 1, Math.floor(f * n));
  if (scale.limit == null) return bin(fraction(value, scale.min, scale.max), bins);
  if (value <= scale.limit + LIMIT_TOLERANCE) return bin(fraction(value, scale.min, Math.max(scale.limit, scale.min)), scale.cool_bins);
  return scale.cool_bins + bin(fraction(value, scale.limit, Math.max(scale.max, scale.limit)), bins - scale.cool_bins);
}

/** A value of quantity `q` as text in the display unit. */
function valueText(q, value) {
  if (q === 'feed') return units() === 'inch' ? num(value / MM_PER_INCH, 1) : num(value, 0);
  return num(value, q === 'wear' ? 3 : q === 'alpha' ? 1 : 0);
}

function caption(q, scale) {
  if (q === 'feed') return `feed, ${units() === 'inch' ? 'in/min' : 'mm/min'}`;
  return scale.caption;
}

/** The legend of `scale`: its bins, min, limit and max. */
function legend(q, scale, colors) {
  if (!scale) return h('div', { class: 'legend3d' });
  const share = (bin) => `${(100 * bin) / scale.colors.length}%`;
  const ticks = [[0, valueText(q, scale.min)], [scale.colors.length, `${scale.top_clipped ? '≥ ' : ''}${valueText(q, scale.max)}`]];
  if (scale.limit != null) ticks.splice(1, 0, [scale.cool_bins, `${valueText(q, scale.limit)} limit`]);
  return h('div', { class: 'legend3d', id: 'legend3d', dataset: { quantity: q } },
    h('div', { class: 'legend3d-caption' }, caption(q, scale)),
    h('div', { class: 'legend3d-ramp' }, scale.colors.map((c) => h('span', { style: `background:${c}` }))),
    h('div', { class: 'legend3d-ticks' }, ticks.map(([bin, text]) => h('span', { style: `left:${share(bin)}` }, text))),
    h('div', { class: 'legend3d-keys' },
      h('span', {}, h('i', { class: 'key-line', style: `background:${colors.no_value}` }), ' no value (air)'),
      h('span', {}, h('i', { class: 'key-dash', style: `border-color:${colors.rapid}` }), ' rapid')));
}

export function view3d(job, views) {
  const node = h('div', { class: 'view3d' });
  if (!hasWebGL()) {
    node.append(problemBox({ message: 'This browser cannot draw WebGL, which the 3-D view needs.' }));
    return node;
  }
  const paths = views.paths || [];
  const state = { path: paths.at(-1)?.name, color: null, layer: 0, depth: 0, n: 0, playing: false };
  const controls = h('div', { class: 'drawing-controls view3d-controls' });
  const canvas = h('div', { class: 'view3d-canvas', id: 'view3d' });
  const status = h('p', { class: 'hint', 'aria-live': 'polite' });
  const readout = h('div', { class: 'readout', id: 'view3d-readout' });
  // The layer (or depth) slider, drawn once per path, and the time slider, drawn again with
  // each path drawn: a drag on the first goes on while the path is drawn again.
  const levelSlot = h('div', { class: 'view3d-slot' });
  const timeSlot = h('div', { class: 'view3d-slot' });
  const sliders = h('div', { class: 'view3d-sliders' }, levelSlot, timeSlot);
  let legendSlot = h('div');
  node.append(controls, canvas, legendSlot, sliders, readout, status,
    h('p', { class: 'hint' }, 'Drag to orbit, right-drag or shift-drag to pan, scroll or pinch to zoom. Rapids are dashed.'));
  let view = null;
  let trace = null;
  let order = [];
  let levels = [];
  let timer = 0;
  let pending = 0;
  let stock = null;

  const stockPromise = api('GET', `/v1/jobs/${encodeURIComponent(job.id)}/stock`).catch((err) => {
    if (err.status === 404) return null;
    throw err;
  });

  function colorOf(i) {
    const scale = trace.scales?.[state.color];
    const value = trace.v[state.color]?.[i];
    return scale && value != null ? scale.colors[binOf(scale, value)] : trace.colors.no_value;
  }

  /** Whether the path is shown down to a depth: it has too many cutting levels to show one by one. */
  const byDepth = () => levels.length > MAX_LEVELS;

  /** The vertices drawn: down to the depth chosen, or the layer's (or cutting level's) chosen; all when none is. */
  function filter() {
    const { v } = trace;
    const all = () => [...Array(trace.count).keys()];
    if (byDepth()) return state.depth < levels.length - 1 ? downTo(trace, levels[state.depth]) : all();
    if (!state.layer) return all();
    if ((views.layers || []).length > 1) return all().filter((i) => v.layer[i] === state.layer - 1);
    return atLevel(trace, levels[state.layer - 1]);
  }

  function layerLabel() {
    if (!state.layer) return 'All layers';
    const layer = (views.layers || []).length > 1 ? views.layers[state.layer - 1] : null;
    if (layer) return `${(layer.name || `layer ${state.layer}`).split(' (z')[0]} (z ${coordinate(layer.z_top)} → ${coordinate(layer.z_bottom)} ${lengthUnit()})`;
    return `Level ${state.layer} of ${levels.length}: z ${coordinate(levels[state.layer - 1])} ${lengthUnit()}`;
  }

  function showTime() {
    if (!order.length) return;
    const i = order[state.n];
    const { v } = trace;
    view.showUpTo(state.n, v.x[i], v.y[i], v.z[i]);
    const at = view.toolPosition();
    canvas.dataset.tool = at ? at.map((c) => c.toFixed(3)).join(',') : '';
    canvas.dataset.vertex = String(state.n);
    readout.textContent = `Tool at ${describe(trace, i)}`;
    const time = sliders.querySelector('#time3d');
    if (time) time.value = String(state.n);
    const label = sliders.querySelector('#time3d-label');
    if (label) label.textContent = v.s[i] != null ? `${length(v.s[i], 1)} along the path` : `vertex ${state.n + 1} of ${order.length}`;
  }

  /** Draws the path again at the next frame: a dragged slider draws once a frame, at its last value. */
  function drawSoon() {
    cancelAnimationFrame(pending);
    pending = requestAnimationFrame(drawPath);
  }

  /** The layer slider (one layer or cutting level at a time), the depth slider for many levels, or none. */
  function renderLevels() {
    if (byDepth()) {
      levelSlot.replaceChildren(depthControl(levels, state.depth, (k) => { state.depth = k; drawSoon(); }));
      return;
    }
    const layerCount = (views.layers || []).length > 1 ? views.layers.length : levels.length > 1 ? levels.length : 0;
    levelSlot.replaceChildren(...(layerCount ? [h('div', { class: 'field' }, h('label', { for: 'layer3d' }, 'Layer: ', h('span', { id: 'layer3d-label' }, layerLabel())),
      h('input', { type: 'range', id: 'layer3d', min: 0, max: layerCount, step: 1, value: state.layer, oninput: (e) => {
        state.layer = Number(e.target.value);
        levelSlot.querySelector('#layer3d-label').textContent = layerLabel();
        drawSoon();
      } }))] : []));
  }

  /** The time slider and Play, over the vertices drawn. */
  function renderSliders() {
    const play = h('button', { type: 'button', id: 'play3d', 'aria-pressed': String(state.playing), onclick: () => (state.playing ? stop() : start()) }, state.playing ? 'Pause' : 'Play');
    timeSlot.replaceChildren(h('div', { class: 'field time3d' }, h('label', { for: 'time3d' }, 'Time: ', h('span', { id: 'time3d-label' })),
      h('div', { class: 'time3d-row' }, play,
        h('input', { type: 'range', id: 'time3d', min: 0, max: Math.max(0, order.length - 1), step: 1, value: state.n, oninput: (e) => {
          stop();
          state.n = Number(e.target.value);
          showTime();
        } }))));
  }

  /** Draws the vertices the layer or depth chosen shows, with their legend and the time slider over them. */
  function drawPath() {
    cancelAnimationFrame(pending);
    stop();
    order = filter();
    state.n = Math.max(0, order.length - 1);
    view.setPath(trace, order, colorOf, trace.colors.rapid);
    canvas.dataset.drawn = String(order.length);
    canvas.dataset.depth = byDepth() ? levels[state.depth].toFixed(3) : '';
    const scale = trace.scales?.[state.color];
    const next = legend(state.color, scale, trace.colors);
    legendSlot.replaceWith(next);
    legendSlot = next;
    renderSliders();
    showTime();
  }

  function start() {
    if (!order.length) return;
    if (state.n >= order.length - 1) state.n = 0;
    state.playing = true;
    renderSliders();
    const { v } = trace;
    const s0 = v.s[order[0]]; const s1 = v.s[order.at(-1)];
    const bySpan = s0 != null && s1 != null && s1 > s0;
    let last = performance.now();
    let at = bySpan ? v.s[order[state.n]] ?? s0 : state.n;
    const step = (now) => {
      if (!state.playing) return;
      const dt = (now - last) / 1000;
      last = now;
      at += (dt / PLAY_SECONDS) * (bySpan ? s1 - s0 : order.length);
      if (bySpan) { while (state.n < order.length - 1 && (v.s[order[state.n + 1]] ?? at) <= at) state.n++; } else state.n = Math.min(order.length - 1, Math.floor(at));
      showTime();
      if (state.n >= order.length - 1) { stop(); return; }
      timer = requestAnimationFrame(step);
    };
    timer = requestAnimationFrame(step);
  }

  function stop() {
    cancelAnimationFrame(timer);
    if (!state.playing) return;
    state.playing = false;
    renderSliders();
    showTime();
  }

  function renderControls() {
    const current = paths.find((p) => p.name === state.path) || paths[0] || { quantities: [] };
    if (!current.quantities.includes(state.color)) state.color = current.quantities[0] || null;
    const select = (id, label, options, value, set) => h('div', { class: 'field' }, h('label', { for: id }, label),
      h('select', { id, onchange: (e) => set(e.target.value) },
        options.map(([v, text]) => h('option', { value: v, selected: String(v) === String(value) }, text))));
    controls.replaceChildren(...[
      paths.length > 1 ? select('path3d', 'Path', paths.map((p) => [p.name, p.name.charAt(0).toUpperCase() + p.name.slice(1).replace(/_/g, ' ')]), state.path, (v) => { state.path = v; load(); }) : null,
      current.quantities.length ? select('color3d', 'Colour by', current.quantities.map((q) => [q, NAMES[q] || q]), state.color, (v) => { state.color = v; drawPath(); }) : null,
      h('div', { class: 'zoom' }, h('button', { type: 'button', id: 'fit3d', onclick: () => view.fit() }, 'Fit')),
    ].filter(Boolean));
  }

  async function load() {
    renderControls();
    status.textContent = 'Loading the path…';
    try {
      trace = await loadTrace(views.drawing, state.path);
      levels = (views.layers || []).length > 1 ? [] : cuttingLevels(trace);
      canvas.dataset.levels = String(levels.length);
      state.layer = 0;
      state.depth = Math.max(0, levels.length - 1);
      showTool();
      renderLevels();
      drawPath();
      status.textContent = '';
    } catch (err) {
      status.replaceChildren(problemBox(err, 'Could not load the path'));
    }
  }

  /** The end mill of the path shown, as the result names it; else a cylinder sized to the stock. */
  function toolSpec() {
    const diameter = stock ? stock.grid.cell_mm * stock.grid.columns * TOOL_SHARE : 1;
    return toolOf(job, state.path) ?? { shape: null, diameter_mm: diameter, corner_radius_mm: 0 };
  }

  /** Draws the path's end mill and tells tests its shape and its radius near its tip (`[height, radius]`, mm). */
  function showTool() {
    const tool = toolSpec();
    view.setTool(tool);
    canvas.dataset.toolShape = tool.shape ?? 'unnamed';
    canvas.dataset.toolProfile = JSON.stringify(PROFILE_HEIGHTS.map((share) => {
      const height = share * tool.diameter_mm;
      return [height, Number(view.toolRadiusAt(height).toFixed(3))];
    }));
  }

  stockPromise.then((kept) => {
    stock = kept;
    view = createScene(canvas, { stock, tool: toolSpec() });
    view.resize();
    canvas.dataset.stock = stock ? `${stock.grid.columns}x${stock.grid.rows}` : 'none';
    if (!stock) status.textContent = 'This job kept no stock (analysis, costing, side-milling feeds, trochoids and plan jobs keep theirs): the path alone.';
    load();
    const observer = new ResizeObserver(() => {
      if (!canvas.isConnected) { observer.disconnect(); stop(); view.dispose(); return; }
      view.resize();
    });
    observer.observe(canvas);
  }).catch((err) => node.replaceChildren(problemBox(err, 'Could not load the stock')));
  return node;
}
