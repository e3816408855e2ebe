// Past jobs, newest first: filter by kind and status, page through, open one. Refreshes
// itself while a listed job is still queued or running.
import { h, api, downloadLink, num, when, duration, table, badge, KIND_NAMES } from './ui.js';

const PAGE = 20;
const STATUSES = ['queued', 'running', 'succeeded', 'failed', 'cancelled'];

export async function jobsView(params) {
  const kind = params.get('kind') || '';
  const status = params.get('status') || '';
  const offset = Math.max(0, Number(params.get('offset')) || 0);
  const link = (changes) => {
    const q = new URLSearchParams({ kind, status, offset: String(offset), ...changes });
    for (const [k, v] of [...q]) if (!v || v === '0') q.delete(k);
    return `#/jobs${q.toString() ? `?${q}` : ''}`;
  };
  const query = new URLSearchParams({ limit: String(PAGE), offset: String(offset) });
  if (kind) query.set('kind', kind);
  if (status) query.set('status', status);
  const page = await api('GET', `/v1/jobs?${query}`);

  const filter = (id, label, value, options, key) => h('div', { class: 'field' }, h('label', { for: id }, label),
    h('select', { id, onchange: (e) => { location.hash = link({ [key]: e.target.value, offset: '0' }); } },
      h('option', { value: '' }, 'all'), options.map((o) => h('option', { value: o, selected: o === value }, KIND_NAMES[o] && key === 'kind' ? KIND_NAMES[o] : o))));

  const rows = table([
    ['Created', (j) => h('a', { href: `#/jobs/${j.id}` }, when(j.created_at))],
    ['Kind', (j) => KIND_NAMES[j.kind] || j.kind],
    ['Status', (j) => badge(j.status)],
    ['Progress', (j) => `${num((j.progress || 0) * 100, 0)} %`],
    ['Ran', (j) => duration(j.started_at, j.finished_at)],
    ['Job', (j) => h('span', { class: 'mono' }, j.id.slice(0, 8))],
    ['Program', (j) => (j.links?.program ? downloadLink(j.links.program, `dieplan-${j.kind}-${j.id.slice(0, 8)}.nc`, {}, 'NC') : '')],
  ], page.items, { rowLink: (j) => `#/jobs/${j.id}`, empty: kind || status ? 'No job matches these filters.' : 'No jobs yet: start one under “New job”.' });

  const last = Math.min(offset + page.items.length, page.total);
  const pageLink = (label, to, enabled) => (enabled ? h('a', { class: 'button', href: link({ offset: String(to) }) }, label) : h('span', { class: 'button disabled', 'aria-disabled': 'true' }, label));
  const pager = h('nav', { class: 'pager', 'aria-label': 'pages' },
    pageLink('← Newer', Math.max(0, offset - PAGE), offset > 0),
    h('span', {}, page.total ? `${offset + 1}–${last} of ${page.total}` : '0 jobs'),
    pageLink('Older →', offset + PAGE, last < page.total));

  const node = h('div', { id: 'jobs' },
    h('div', { class: 'title-row' }, h('h1', {}, 'Jobs'), h('a', { class: 'button primary', href: '#/new' }, 'New job')),
    h('div', { class: 'card filters' },
      filter('filter-kind', 'Kind', kind, Object.keys(KIND_NAMES), 'kind'),
      filter('filter-status', 'Status', status, STATUSES, 'status')),
    rows, pager);

  let timer = null;
  if (page.items.some((j) => j.status === 'queued' || j.status === 'running')) {
    timer = setTimeout(() => window.dispatchEvent(new Event('dieplan:refresh')), 2000);
  }
  return { node, title: 'Jobs', cleanup: () => clearTimeout(timer) };
}
