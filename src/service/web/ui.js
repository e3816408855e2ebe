// Small helpers shared by the views: element builder, API calls, problem display, number
// formatting. No framework: views build DOM with h() and replace the main element's content.
import { storedKey, askForKey, authorizeDownload } from './key.js';

export { askForKey };

/** A link that downloads the text at `href` as `filename`, with the stored key if any. */
export function downloadLink(href, filename, attrs, label) {
  return authorizeDownload(h('a', { ...attrs, href, download: filename }, label), (path) => api('GET', path, undefined, { text: true }));
}

/** Builds an element: h('a', {href: '#/jobs', class: 'x', onclick: fn}, 'text', child, [more]). */
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key.startsWith('on') && typeof value === 'function') el.addEventListener(key.slice(2), value);
    else if (key === 'class') el.className = value;
    else if (key === 'dataset') Object.assign(el.dataset, value);
    else if (key === 'value' && 'value' in el) el.value = value;
    else if (key === 'checked' || key === 'selected' || key === 'disabled') el[key] = Boolean(value);
    else el.setAttribute(key, value === true ? '' : String(value));
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const child of children.flat(Infinity)) {
    if (child === null || child === undefined || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
}

/** An error answered by the API as application/problem+json (or anything not 2xx). */
export class ApiProblem extends Error {
  constructor(status, problem) {
    super(problem?.detail || `HTTP ${status}`);
    this.status = status;
    this.problem = problem || { status, title: `HTTP ${status}`, detail: `HTTP ${status}` };
  }
}

/** Most times a request asks for a key before it gives up with the 401. */
const KEY_ATTEMPTS = 3;

/**
 * Calls the API with the stored key (key.js), asking for one when the service answers
 * 401. Resolves to the parsed JSON (or text, or null for 204); rejects with an ApiProblem
 * for a 4xx/5xx answer and for network failures.
 */
export async function api(method, path, body, { contentType = 'application/json', text = false } = {}) {
  const init = { method, headers: { accept: text ? '*/*' : 'application/json' } };
  if (body instanceof FormData) {
    // A multipart upload: the browser writes its content type with the boundary.
    init.body = body;
  } else if (body !== undefined) {
    init.headers['content-type'] = contentType;
    init.body = typeof body === 'string' ? body : JSON.stringify(body);
  }
  let response;
  for (let attempt = 0; ; attempt++) {
    const key = storedKey();
    if (key) init.headers.authorization = `Bearer ${key}`;
    else delete init.headers.authorization;
    try {
      response = await fetch(path, init);
    } catch (err) {
      throw new ApiProblem(0, { status: 0, title: 'Network error', detail: `The service did not answer (${err.message}). Is it running?` });
    }
    if (response.status !== 401 || attempt >= KEY_ATTEMPTS) break;
    const problem = await response.clone().json().catch(() => null);
    const entered = await askForKey(problem?.detail);
    if (!entered) break;
  }
  const type = response.headers.get('content-type') || '';
  if (!response.ok) {
    let problem = null;
    if (type.includes('json')) problem = await response.json().catch(() => null);
    else problem = { status: response.status, title: response.statusText, detail: (await response.text()).slice(0, 500) };
    throw new ApiProblem(response.status, problem);
  }
  if (response.status === 204) return null;
  if (text || !type.includes('json')) return response.text();
  return response.json();
}

/** A readable box for a problem: title, detail and the refused fields. */
export function problemBox(err, heading) {
  const problem = err?.problem || { title: 'Error', detail: String(err?.message || err) };
  const status = problem.status ? ` (${problem.status})` : '';
  const errors = Array.isArray(problem.errors) ? problem.errors : [];
  // A validation problem's detail repeats its first error: show the list only.
  const repeats = errors.length && String(problem.detail || '').startsWith(`${errors[0].field}: `);
  return h('div', { class: 'problem', role: 'alert' },
    h('strong', {}, heading || `${problem.title || 'Error'}${status}`),
    problem.detail && !repeats ? h('p', {}, problem.detail) : null,
    errors.length
      ? h('ul', {}, problem.errors.map((e) => h('li', {}, h('code', {}, e.field), ': ', e.reason)))
      : null);
}

/** JSON with two-space indents, arrays of plain values (points, vertices) on one line. */
export function pretty(value) {
  return JSON.stringify(value, null, 2)
    .replace(/"(?:[^"\\]|\\.)*"|\[\s*([^[\]{}"]*?)\s*\]/g,
      (match, inner) => (inner === undefined ? match : `[${inner.split(/,\s*/).join(', ')}]`));
}

/** Formats a number with at most `digits` decimals (trailing zeros dropped) and a unit. */
export function num(value, digits = 1, unit = '') {
  if (value === null || value === undefined || Number.isNaN(value)) return '–';
  if (typeof value !== 'number') return String(value);
  const text = value.toLocaleString('en-US', { maximumFractionDigits: digits, minimumFractionDigits: 0 });
  return unit ? `${text} ${unit}` : text;
}

/** Minutes as "1 h 02 min", "3.4 min" or "12 s". */
export function minutes(value) {
  if (value === null || value === undefined) return '–';
  if (value < 1) return `${num(value * 60, 1)} s`;
  if (value < 60) return `${num(value, 2)} min`;
  const hours = Math.floor(value / 60);
  return `${hours} h ${String(Math.round(value - hours * 60)).padStart(2, '0')} min`;
}

/** A local date-time from an RFC 3339 timestamp. */
export function when(stamp) {
  if (!stamp) return '–';
  const d = new Date(stamp);
  return Number.isNaN(d.getTime()) ? stamp : d.toLocaleString(undefined, { dateStyle: 'short', timeStyle: 'medium' });
}

/** Duration between two timestamps, readable. */
export function duration(from, to) {
  if (!from) return '–';
  const ms = (to ? new Date(to) : new Date()) - new Date(from);
  if (!(ms >= 0)) return '–';
  if (ms < 1000) return '< 1 s';
  return ms < 60000 ? `${num(ms / 1000, 1)} s` : minutes(ms / 60000);
}

/** Key figures as a definition list: [[label, value, hint?], …]. */
export function figures(rows) {
  return h('dl', { class: 'figures' }, rows.filter(Boolean).map(([label, value, hint]) =>
    h('div', { class: hint ? `figure ${hint}` : 'figure' }, h('dt', {}, label), h('dd', {}, value))));
}

/**
 * A table: columns [[heading, row => cell]], optional row click. Wrapped for small screens.
 * With `limit`, longer tables show their first rows and a button to show the rest.
 */
export function table(columns, rows, { onRow, rowLink, empty = 'Nothing to show.', limit } = {}) {
  if (!rows.length) return h('p', { class: 'muted' }, empty);
  if (limit && rows.length > limit) {
    const wrap = h('div', {}, table(columns, rows.slice(0, limit), { onRow, rowLink }));
    const more = h('button', { type: 'button', class: 'link more', onclick: () => {
      wrap.replaceChildren(table(columns, rows, { onRow, rowLink }));
    } }, `Show all ${rows.length} rows`);
    wrap.append(h('p', { class: 'hint' }, `The first ${limit} of ${rows.length}. `, more));
    return wrap;
  }
  const head = h('thead', {}, h('tr', {}, columns.map(([heading]) => h('th', { scope: 'col' }, heading))));
  const body = h('tbody', {}, rows.map((row) => {
    const tr = h('tr', {}, columns.map(([, cell]) => h('td', {}, cell(row))));
    if (rowLink) {
      tr.classList.add('clickable');
      tr.addEventListener('click', (event) => {
        if (!event.target.closest('a, button, input, select')) location.hash = rowLink(row);
      });
    } else if (onRow) {
      tr.classList.add('clickable');
      tr.addEventListener('click', (event) => {
        if (!event.target.closest('a, button, input, select')) onRow(row);
      });
    }
    return tr;
  }));
  return h('div', { class: 'table-wrap' }, h('table', {}, head, body));
}

/** A status badge. */
export function badge(status) {
  return h('span', { class: `badge badge-${status}` }, status);
}

/** The endpoint that creates a job of each kind. */
export const ENDPOINTS = {
  analysis: '/v1/analysis',
  trochoids: '/v1/trochoids',
  feeds: '/v1/feeds',
  costing: '/v1/costing',
  plan: '/v1/plans',
  conditions: '/v1/conditions',
};

/** Human names of job kinds. */
export const KIND_NAMES = {
  analysis: 'Path analysis',
  trochoids: 'Trochoid insertion',
  feeds: 'Feed optimisation',
  costing: 'Costing',
  plan: 'Cavity plan',
  conditions: 'Cutting conditions',
};

/** Parses an SVG document fetched from the service and returns a safe, importable node. */
export function svgNode(text) {
  const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
  const root = doc.documentElement;
  if (!root || root.nodeName.toLowerCase() !== 'svg' || doc.querySelector('parsererror')) {
    throw new Error('the answer is not an SVG image');
  }
  root.querySelectorAll('script, foreignObject').forEach((n) => n.remove());
  for (const el of [root, ...root.querySelectorAll('*')]) {
    for (const attr of [...el.attributes]) {
      if (attr.name.startsWith('on') || (/href$/.test(attr.name) && /^\s*javascript:/i.test(attr.value))) {
        el.removeAttribute(attr.name);
      }
    }
  }
  return document.importNode(root, true);
}

let openapiDocument = null;

/** The service's OpenAPI document (loaded once): request schemas, examples, descriptions. */
export function openapi() {
  if (!openapiDocument) {
    openapiDocument = api('GET', '/openapi.json').catch((err) => {
      openapiDocument = null;
      throw err;
    });
  }
  return openapiDocument;
}

/** Resolves a `$ref` (or a nullable `oneOf` of one) to its schema. */
export function resolveSchema(doc, schema) {
  let s = schema || {};
  for (let i = 0; i < 5; i += 1) {
    if (s.$ref) s = doc.components.schemas[s.$ref.split('/').pop()] || {};
    else if (Array.isArray(s.oneOf)) s = s.oneOf.find((o) => o.type !== 'null') || {};
    else break;
  }
  return s;
}

/** A job's tags as links to the jobs list filtered by each. */
export function tagList(tags) {
  if (!tags?.length) return null;
  return h('ul', { class: 'tags', 'aria-label': 'tags' }, tags.map((t) => h('li', {},
    h('a', { class: 'tag', href: `#/jobs?tag=${encodeURIComponent(t)}`, title: `Jobs tagged ${t}` }, t))));
}

/** Tags typed in one box, separated by commas or spaces. */
export const parseTags = (text) => [...new Set(String(text || '').split(/[\s,]+/).filter(Boolean))];
