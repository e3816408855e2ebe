// The cutting levels of a path in the 3-D view and the depth control over them: a path
// with few levels is shown one level at a time (the layer slider of view3d.js), a path
// with many (a 3-D program has hundreds or thousands) down to a depth chosen on a slider
// over its z range that steps through its actual levels. Every function here is at most
// O(n log n) in the path's vertices, whatever the number of levels.
import { h } from './ui.js';
import { coordinate, lengthUnit } from './units.js';

/** Up to this many distinct cutting levels are offered one by one; more, by depth. */
export const MAX_LEVELS = 400;
/** Levels closer than this are one, mm. */
export const LEVEL_EPS_MM = 1e-3;
/** Levels one Page Up or Page Down moves the depth slider by. */
const PAGE_LEVELS = 10;

/** The distinct cutting levels of the path (z of its feed vertices that engage the material, α > 0), top first. */
export function cuttingLevels(trace) {
  const { v } = trace;
  const zs = new Float64Array(trace.count);
  let n = 0;
  for (let i = 0; i < trace.count; i++) {
    if (v.run[i] < 0 || v.z[i] == null || !(v.alpha[i] > 0)) continue;
    zs[n++] = v.z[i];
  }
  const sorted = zs.subarray(0, n).sort().reverse();
  const levels = [];
  for (const z of sorted) if (!levels.length || levels.at(-1) - z >= LEVEL_EPS_MM) levels.push(z);
  return levels;
}

/** The index of the level nearest `z` in `levels` (top first), by binary search. */
export function nearestLevel(levels, z) {
  let lo = 0;
  let hi = levels.length;
  // The first level at or below z.
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (levels[mid] > z) lo = mid + 1;
    else hi = mid;
  }
  if (lo === 0) return 0;
  if (lo === levels.length) return levels.length - 1;
  return levels[lo - 1] - z < z - levels[lo] ? lo - 1 : lo;
}

/** The vertices of the trace for which `keep(z)` holds of their z, in path order. */
function vertices(trace, keep) {
  const { z } = trace.v;
  const kept = [];
  for (let i = 0; i < trace.count; i++) if (z[i] != null && keep(z[i])) kept.push(i);
  return kept;
}

/** The vertices at the level `level` (mm), in path order. */
export function atLevel(trace, level) {
  return vertices(trace, (z) => Math.abs(z - level) < LEVEL_EPS_MM);
}

/** The vertices down to the level `level` (mm), those below it left out, in path order. */
export function downTo(trace, level) {
  return vertices(trace, (z) => z > level - LEVEL_EPS_MM);
}

/** What the depth slider at level `index` shows, as text in the display unit. */
function depthLabel(levels, index) {
  const z = `z ${coordinate(levels[index])} ${lengthUnit()}`;
  if (index === levels.length - 1) return `all ${levels.length} levels, down to ${z}`;
  return `down to ${z} (level ${index + 1} of ${levels.length})`;
}

/** The level index a key moves the depth slider to from `index`, or null for another key. */
function keyTarget(key, index, last) {
  const moves = { ArrowRight: 1, ArrowUp: 1, ArrowLeft: -1, ArrowDown: -1, PageUp: PAGE_LEVELS, PageDown: -PAGE_LEVELS, Home: -last, End: last };
  return key in moves ? Math.min(last, Math.max(0, index + moves[key])) : null;
}

/**
 * The depth slider over the z range of `levels` (top first, at least two), from the top
 * level (left) to the lowest (right, the whole path), at level `index`: dragging it snaps
 * to the nearest actual level, a key steps one level (ten with Page Up and Down), and
 * `onChange(index)` is told the level chosen.
 */
export function depthControl(levels, index, onChange) {
  const top = levels[0];
  const last = levels.length - 1;
  const label = h('span', { id: 'depth3d-label' }, depthLabel(levels, index));
  let current = index;
  const choose = (k) => {
    input.value = String(top - levels[k]);
    if (k === current) return;
    current = k;
    label.textContent = depthLabel(levels, k);
    input.setAttribute('aria-valuetext', label.textContent);
    onChange(k);
  };
  const input = h('input', {
    type: 'range', id: 'depth3d', min: 0, max: top - levels[last], step: 'any', value: top - levels[index],
    'aria-valuetext': depthLabel(levels, index),
    oninput: (e) => choose(nearestLevel(levels, top - Number(e.target.value))),
    onkeydown: (e) => {
      const k = keyTarget(e.key, current, last);
      if (k == null) return;
      e.preventDefault();
      choose(k);
    },
  });
  return h('div', { class: 'field depth3d' }, h('label', { for: 'depth3d' }, 'Depth: ', label), input);
}
