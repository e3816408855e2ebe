// Zoom, pan and the hover read-out of a job's drawing. The wheel, the buttons and a drag
// move the SVG's view box at once (a preview); once the view has been still for a moment
// the drawing is asked for again for the window in view (`x_min`…`y_max`, mm), so it
// shows vector detail at any scale with its labels, strokes and legend at their usual
// size, and dense regions separate. The drawing's `frame` element says how mm map onto
// its px; the legend's ramp carries its scale, so a colour band's values can be read.
import { h } from './ui.js';
import { coordinate, lengthUnit, feed as feedText } from './units.js';
import { PROBE_RADIUS_PX } from './trace.js';

/** The view is drawn anew this long after the last zoom or pan, ms. */
const SETTLE_MS = 400;
/** Zoom bounds: out to the whole drawing; in until the window is this many times the
 * finest detail the job's drawing keeps (`detail_mm` of its views: the tolerance its paths
 * were traced to), and never below the smallest window the service draws. */
const MAX_ZOOM_OUT = 1;
const DETAIL_SPAN = 4;
const MIN_WINDOW_MM = 0.001;
/** The detail of a drawing stored before it was kept: this fraction of its extent. */
const OLD_DETAIL_FRACTION = 1 / 2000;
/** Colour bins of the drawing's ramps and where the hot part starts (palette.rs). */
const BINS = 32;
const COOL_BINS = 24;

/** The mm ↔ px mapping of a drawing, from its `frame` element. */
export function frameOf(svg) {
  const f = svg.querySelector('.frame');
  if (!f) return null;
  const n = (name) => Number(f.getAttribute(`data-${name}`));
  const frame = { xMin: n('x-min'), yMin: n('y-min'), xMax: n('x-max'), yMax: n('y-max'), scale: n('scale'), left: n('left'), top: n('top') };
  return Object.values(frame).every(Number.isFinite) && frame.scale > 0 ? frame : null;
}

const toMm = (frame, [px, py]) => [frame.xMin + (px - frame.left) / frame.scale, frame.yMax - (py - frame.top) / frame.scale];

/** The values of colour bin `bin` of the drawing's ramp: [lo, hi, quantity] or null. */
function binValues(svg, bin) {
  const ramp = svg.querySelector('.legend-ramp');
  if (!ramp || !Number.isInteger(bin)) return null;
  const min = Number(ramp.getAttribute('data-min'));
  const max = Number(ramp.getAttribute('data-max'));
  const limit = ramp.hasAttribute('data-limit') ? Number(ramp.getAttribute('data-limit')) : null;
  const span = (lo, hi, b, bins) => [lo + ((hi - lo) * b) / bins, lo + ((hi - lo) * (b + 1)) / bins];
  let range;
  if (limit === null) range = span(min, max, bin, BINS);
  else if (bin < COOL_BINS) range = span(min, Math.max(limit, min), bin, COOL_BINS);
  else range = span(limit, Math.max(max, limit), bin - COOL_BINS, BINS - COOL_BINS);
  return [...range, ramp.getAttribute('data-quantity')];
}

const UNITS = { alpha: '°', feed: 'mm/min', force: 'N', wear: '%/m' };
const NAMES = { alpha: 'α', feed: 'feed', force: 'force', wear: 'wear' };
const round = (v) => (Math.abs(v) >= 100 ? Math.round(v) : Math.round(v * 10) / 10);

/** What the pointer is over, as text: the path's vertex under it (`probe`), else the position. */
function readout(svg, frame, point, target, probe) {
  const [x, y] = toMm(frame, point);
  const vb = svg.viewBox.baseVal;
  const screenPerMm = frame.scale * (svg.getBoundingClientRect().width / (vb.width || 1));
  const probed = probe?.(x, y, PROBE_RADIUS_PX / (screenPerMm || 1));
  const parts = [probed || `X ${coordinate(x)}  Y ${coordinate(y)} ${lengthUnit()}`];
  const mark = target.closest?.('.region, .region-label');
  const feed = target.closest?.('.feed');
  if (mark) {
    const [from, to] = (mark.getAttribute('data-lines') || '').split('-');
    const alpha = mark.getAttribute('data-max-alpha') || svg.querySelector(`.region[data-lines="${from}-${to}"]`)?.getAttribute('data-max-alpha');
    parts.push(`critical region · NC lines ${from}–${to}${alpha ? ` · α up to ${alpha}°` : ''} (click: show the lines)`);
  } else if (!probed && feed?.hasAttribute('data-bin')) {
    const v = binValues(svg, Number(feed.getAttribute('data-bin')));
    if (v && v[2] === 'feed') parts.push(`feed ${feedText(v[0]).replace(/ .*$/, '')}–${feedText(v[1])}`);
    else if (v) parts.push(`${NAMES[v[2]] || v[2]} ${round(v[0])}–${round(v[1])} ${UNITS[v[2]] || ''}`);
  } else if (!probed && target.closest?.('.rapid')) {
    parts.push('rapid');
  }
  return parts.join(' · ');
}

/**
 * Makes `svg` (in `canvas`) zoomable and pannable. `redraw(window | null)` asks for the
 * drawing of a window in mm (null: the whole). Returns the buttons' action handler.
 */
export function zoomable(svg, canvas, { window: current, redraw, info, probe, detail }) {
  const vb = svg.viewBox.baseVal;
  if (!vb || !vb.width) return () => {};
  const frame = frameOf(svg);
  const home = { x: vb.x, y: vb.y, width: vb.width, height: vb.height };
  const whole = current?.whole || (frame && { width: frame.xMax - frame.xMin, height: frame.yMax - frame.yMin });
  const set = (x, y, width, height) => svg.setAttribute('viewBox', `${x} ${y} ${width} ${height}`);
  let timer = null;
  const settle = () => {
    clearTimeout(timer);
    timer = setTimeout(() => {
      if (!frame || !whole || !svg.isConnected) return;
      const f = vb.width / home.width;
      if (Math.abs(f - 1) < 1e-3 && Math.abs(vb.x - home.x) < 1e-6 && Math.abs(vb.y - home.y) < 1e-6) return;
      // The centre of the view in mm, and the window's size scaled with the view.
      const [cx, cy] = toMm(frame, [vb.x + vb.width / 2, vb.y + vb.height / 2]);
      const hx = ((frame.xMax - frame.xMin) * f) / 2;
      const hy = ((frame.yMax - frame.yMin) * f) / 2;
      if (hx * 2 >= whole.width * MAX_ZOOM_OUT && hy * 2 >= whole.height * MAX_ZOOM_OUT) redraw(null);
      else redraw({ x_min: cx - hx, y_min: cy - hy, x_max: cx + hx, y_max: cy + hy, whole });
    }, SETTLE_MS);
  };
  // The narrowest window, mm: from the data's detail, not a share of the drawing.
  const finest = Math.max(MIN_WINDOW_MM, DETAIL_SPAN * (detail > 0 ? detail : OLD_DETAIL_FRACTION * (whole?.width || 1)));
  const zoom = (factor, cx = vb.x + vb.width / 2, cy = vb.y + vb.height / 2) => {
    // The window's sides in mm per view-box unit at this drawing's scale.
    const side = frame ? Math.min(frame.xMax - frame.xMin, frame.yMax - frame.yMin) / home.width : 0;
    const depth = whole && frame ? (frame.xMax - frame.xMin) / whole.width : 1;
    const least = side > 0 ? finest / side : home.width / 2000;
    const width = Math.min(home.width * (MAX_ZOOM_OUT / depth), Math.max(least, vb.width * factor));
    const f = width / vb.width;
    set(cx - (cx - vb.x) * f, cy - (cy - vb.y) * f, vb.width * f, vb.height * f);
    settle();
  };
  const toSvg = (event) => {
    const r = svg.getBoundingClientRect();
    return [vb.x + ((event.clientX - r.left) / r.width) * vb.width, vb.y + ((event.clientY - r.top) / r.height) * vb.height];
  };
  svg.addEventListener('wheel', (event) => {
    event.preventDefault();
    zoom(event.deltaY > 0 ? 1.2 : 1 / 1.2, ...toSvg(event));
  }, { passive: false });
  let drag = null;
  svg.addEventListener('pointerdown', (event) => {
    drag = { x: event.clientX, y: event.clientY, vx: vb.x, vy: vb.y, moved: false };
    svg.setPointerCapture(event.pointerId);
    canvas.classList.add('dragging');
  });
  svg.addEventListener('pointermove', (event) => {
    if (!drag) {
      if (frame && info) info.textContent = readout(svg, frame, toSvg(event), event.target, probe);
      return;
    }
    const r = svg.getBoundingClientRect();
    drag.moved = true;
    set(drag.vx - ((event.clientX - drag.x) / r.width) * vb.width, drag.vy - ((event.clientY - drag.y) / r.height) * vb.height, vb.width, vb.height);
  });
  svg.addEventListener('pointerleave', () => { if (info && !drag) info.textContent = info.dataset.idle || ''; });
  const end = () => {
    if (drag?.moved) settle();
    drag = null;
    canvas.classList.remove('dragging');
  };
  svg.addEventListener('pointerup', end);
  svg.addEventListener('pointercancel', end);
  return (action) => {
    if (action === 'in') zoom(1 / 1.5);
    else if (action === 'out') zoom(1.5);
    else {
      clearTimeout(timer);
      set(home.x, home.y, home.width, home.height);
      if (current) redraw(null);
    }
  };
}

/** The read-out line under the drawing. */
export function readoutLine() {
  const idle = 'Point at the drawing to read x, y and the values of what is under the pointer.';
  return h('p', { class: 'hint readout', id: 'drawing-readout', 'aria-live': 'off', dataset: { idle } }, idle);
}
