// The drawn path vertex by vertex (GET /v1/jobs/{id}/trace): where each vertex is (x, y,
// z, NC line, path distance) and its values. The drawing reads it under the pointer,
// marks the moves of the NC lines selected in the program, and a chart's path distance
// finds its line in it.
import { api, num } from './ui.js';
import { coordinate, lengthUnit, feed as feedText } from './units.js';

/** How near the pointer a vertex must be to be read, px on the screen. */
export const PROBE_RADIUS_PX = 14;
const SVG_NS = 'http://www.w3.org/2000/svg';

/** Loads the trace of `path` of a job whose drawing is at `drawingHref`; flattened per vertex. */
export async function loadTrace(drawingHref, path) {
  const href = `${drawingHref.replace(/drawing\.svg$/, 'trace')}${path ? `?path=${encodeURIComponent(path)}` : ''}`;
  const trace = await api('GET', href);
  const v = { x: [], y: [], z: [], line: [], s: [], alpha: [], feed: [], force: [], wear: [], run: [], layer: [] };
  trace.runs.forEach((run, r) => {
    run.points.forEach(([x, y], i) => {
      v.x.push(x); v.y.push(y); v.z.push(run.z[i] ?? null); v.line.push(run.lines[i] ?? null); v.s.push(run.s_mm[i] ?? null);
      for (const q of ['alpha', 'feed', 'force', 'wear']) v[q].push(run.values[q]?.[i] ?? null);
      v.run.push(run.rapid ? -1 - r : r);
      v.layer.push(run.layer ?? null);
    });
  });
  // The drawing's colour scales and its colours of rapids and of vertices without a value.
  const colors = { rapid: trace.rapid_color, no_value: trace.no_value_color };
  return { path: trace.path, v, count: v.x.length, scales: trace.scales || {}, colors };
}

/** The vertex nearest (x, y) mm within `radius` mm, or -1. */
export function nearest(trace, x, y, radius) {
  let best = -1;
  let bestD = radius * radius;
  const { v } = trace;
  for (let i = 0; i < trace.count; i++) {
    const dx = v.x[i] - x; const dy = v.y[i] - y;
    const d = dx * dx + dy * dy;
    if (d <= bestD) { bestD = d; best = i; }
  }
  return best;
}

/** The feed vertex whose path distance is nearest `s` mm, or -1. */
export function atDistance(trace, s) {
  let best = -1;
  let bestD = Infinity;
  const { v } = trace;
  for (let i = 0; i < trace.count; i++) {
    if (v.s[i] == null || v.line[i] == null || v.run[i] < 0) continue;
    const d = Math.abs(v.s[i] - s);
    if (d < bestD) { bestD = d; best = i; }
  }
  return best;
}

/** What is known at vertex `i`, as text: x, y, z, line, α, feed, force. */
export function describe(trace, i) {
  const { v } = trace;
  const parts = [`X ${coordinate(v.x[i])}  Y ${coordinate(v.y[i])}${v.z[i] != null ? `  Z ${coordinate(v.z[i])}` : ''} ${lengthUnit()}`];
  if (v.line[i] != null) parts.push(`line ${v.line[i]}`);
  if (v.run[i] < 0) parts.push('rapid');
  if (v.alpha[i] != null) parts.push(`α ${num(v.alpha[i], 1)}°`);
  if (v.feed[i] != null) parts.push(`feed ${feedText(v.feed[i])}`);
  if (v.force[i] != null) parts.push(`force ${num(v.force[i], 0)} N`);
  return parts.join(' · ');
}

/**
 * Marks on `svg` (a drawing with its `frame`) the moves of NC lines `from`–`to`: each
 * segment whose end vertex is on one of them. Returns how many segments it marked.
 */
export function markLines(svg, frame, trace, from, to) {
  svg.querySelector('g.selected-moves')?.remove();
  if (!frame || !trace || from == null) return 0;
  const px = (i) => `${(frame.left + (trace.v.x[i] - frame.xMin) * frame.scale).toFixed(2)},${(frame.top + (frame.yMax - trace.v.y[i]) * frame.scale).toFixed(2)}`;
  const { v } = trace;
  let d = '';
  let marked = 0;
  for (let i = 1; i < trace.count; i++) {
    if (v.run[i] !== v.run[i - 1] || v.line[i] == null || v.line[i] < from || v.line[i] > to) continue;
    d += `M${px(i - 1)}L${px(i)}`;
    marked++;
  }
  if (!marked) return 0;
  const g = document.createElementNS(SVG_NS, 'g');
  g.setAttribute('class', 'selected-moves');
  g.setAttribute('data-lines', `${from}-${to}`);
  const path = document.createElementNS(SVG_NS, 'path');
  path.setAttribute('d', d);
  g.append(path);
  svg.append(g);
  return marked;
}
