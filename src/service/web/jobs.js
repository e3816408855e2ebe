// Past jobs, newest first: filter by kind and status, page through, open one. Refreshes
// itself while a listed job is still queued or running.
import { h, api, downloadLink, num, when, duration, table, badge, tagList, parseTags, KIND_NAMES } from './ui.js';

const PAGE = 20;
const STATUSES = ['queued', 'running', 'succeeded', 'failed', 'cancelled'];

export async function jobsView(params) {
  const kind = params.get('kind') || '';
  const status = params.get('status') || '';
  const name = params.get('name') || '';
  const tags = params.getAll('tag');
  const offset = Math.max(0, Number(params.get('offset')) || 0);
  const link = (changes) => {
    const next = { kind, status, name, offset: String(offset), tag: tags, ...changes };
    const q = new URLSearchParams();
    for (const [k, v] of Object.entries(next)) for (const one of [v].flat()) if (one && one !== '0') q.append(k, one);
    return `#/jobs${q.toString() ? `?${q}` : ''}`;
  };
  const query = new URLSearchParams({ limit: String(PAGE), offset: String(offset) });
  if (kind) query.set('kind', kind);
  if (status) query.set('status', status);
  if (name) query.set('name', name);
  for (const t of tags) query.append('tag', t);
  const page = await api('GET', `/v1/jobs?${query}`);

  const filter = (id, label, value, options, key) => h('div', { class: 'field' }, h('label', { for: id }, label),
    h('select', { id, onchange: (e) => { location.hash = link({ [key]: e.target.value, offset: '0' }); } },
      h('option', { value: '' }, 'all'), options.map((o) => h('option', { value: o, selected: o === value }, KIND_NAMES[o] && key === 'kind' ? KIND_NAMES[o] : o))));

  // Name search and tag filter: typed, then applied with Enter or the button.
  const nameBox = h('input', { id: 'filter-name', type: 'search', value: name, placeholder: 'part of a name', autocomplete: 'off' });
  const tagBox = h('input', { id: 'filter-tag', type: 'text', value: tags.join(' '), placeholder: 'die:4711 roughing', autocomplete: 'off', spellcheck: 'false' });
  const search = h('form', { class: 'search', role: 'search', onsubmit: (e) => {
    e.preventDefault();
    location.hash = link({ name: nameBox.value.trim(), tag: parseTags(tagBox.value), offset: '0' });
  } },
  h('div', { class: 'field' }, h('label', { for: 'filter-name' }, 'Name'), nameBox),
  h('div', { class: 'field' }, h('label', { for: 'filter-tag' }, 'Tags (all of them)'), tagBox),
  h('button', { type: 'submit', id: 'filter-apply' }, 'Search'));

  const rows = table([
    ['Created', (j) => h('a', { href: `#/jobs/${j.id}` }, when(j.created_at))],
    ['Name', (j) => (j.name ? h('a', { href: `#/jobs/${j.id}`, class: 'job-name' }, j.name) : h('span', { class: 'muted' }, '–'))],
    ['Tags', (j) => tagList(j.tags) || ''],
    ['Kind', (j) => KIND_NAMES[j.kind] || j.kind],
    ['Status', (j) => badge(j.status)],
    ['Progress', (j) => `${num((j.progress || 0) * 100, 0)} %`],
    ['Ran', (j) => duration(j.started_at, j.finished_at)],
    ['Job', (j) => h('span', { class: 'mono' }, j.id.slice(0, 8))],
    ['Program', (j) => (j.links?.program ? downloadLink(j.links.program, `dieplan-${j.kind}-${j.id.slice(0, 8)}.nc`, {}, 'NC') : '')],
  ], page.items, { rowLink: (j) => `#/jobs/${j.id}`, empty: kind || status || name || tags.length ? 'No job matches these filters.' : 'No jobs yet: start one under “New job”.' });

  const last = Math.min(offset + page.items.length, page.total);
  const pageLink = (label, to, enabled) => (enabled ? h('a', { class: 'button', href: link({ offset: String(to) }) }, label) : h('span', { class: 'button disabled', 'aria-disabled': 'true' }, label));
  const pager = h('nav', { class: 'pager', 'aria-label': 'pages' },
    pageLink('← Newer', Math.max(0, offset - PAGE), offset > 0),
    h('span', {}, page.total ? `${offset + 1}–${last} of ${page.total}` : '0 jobs'),
    pageLink('Older →', offset + PAGE, last < page.total));

  const node = h('div', { id: 'jobs' },
    h('div', { class: 'title-row' }, h('h1', {}, 'Jobs'), h('a', { class: 'button primary', href: '#/new' }, 'New job')),
    h('div', { class: 'card filters' },
      search,
      filter('filter-kind', 'Kind', kind, Object.keys(KIND_NAMES), 'kind'),
      filter('filter-status', 'Status', status, STATUSES, 'status'),
      tags.length ? h('p', { class: 'active-tags' }, 'Tagged ', tags.map((t) => h('a', { class: 'tag removable', href: link({ tag: tags.filter((x) => x !== t), offset: '0' }), title: `Show jobs without the ${t} filter` }, t, ' ×'))) : null),
    rows, pager);

  let timer = null;
  if (page.items.some((j) => j.status === 'queued' || j.status === 'running')) {
    timer = setTimeout(() => window.dispatchEvent(new Event('dieplan:refresh')), 2000);
  }
  return { node, title: 'Jobs', cleanup: () => clearTimeout(timer) };
}
