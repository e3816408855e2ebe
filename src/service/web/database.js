// The cutting-condition database: one tab per table, a paged list with each row's
// provenance, and a form (generated from the OpenAPI schema of the table's data) to edit a
// row (PATCH, JSON merge patch), add one (POST) or delete one (DELETE).
import { h, api, problemBox, num, table, openapi, resolveSchema } from './ui.js';

const PAGE = 25;
const TABLES = {
  materials: { path: '/v1/materials', title: 'Materials', columns: ['name', 'designation', 'hardness_hrc'] },
  tools: { path: '/v1/tools', title: 'Tools', columns: ['name', 'tool_type', 'diameter_mm', 'flutes', 'corner_radius_mm', 'price'] },
  'standard-conditions': { path: '/v1/conditions/standard', title: 'Standard conditions', columns: ['tool_id', 'operation', 'spindle_rpm', 'fz_mm', 'rd_mm', 'ad_mm'] },
  'force-models': { path: '/v1/force-models', title: 'Force models', columns: ['tool_id', 't0_um', 'l0_mm', 'b0', 'b1', 'b2', 'r_squared'] },
  'tool-life': { path: '/v1/tool-life', title: 'Tool life', columns: ['tool_id', 'life_m', 'force_exponent'] },
  machines: { path: '/v1/machines', title: 'Machines', columns: ['name', 'rapid_mm_min', 'max_feed_mm_min', 'max_spindle_rpm', 'tool_change_s', 'coolant'] },
  'cost-rates': { path: '/v1/cost-rates', title: 'Cost rates', columns: ['name', 'currency', 'machine_rate_per_hour', 'default_tool_price'] },
};
const READ_ONLY = new Set(['id', 'created_at', 'updated_at', 'edited']);

const heading = (key) => key.replace(/_id$/, '').replace(/_(mm|um|n|m|s|hrc)$/, (m, u) => ` (${{ um: 'µm', n: 'N', hrc: 'HRC' }[u] || u})`).replace(/_/g, ' ');
const cell = (v) => (typeof v === 'number' ? num(v, 4) : v === null || v === undefined ? '–' : typeof v === 'object' ? JSON.stringify(v) : String(v));

/** The JSON type a property takes: number, integer, string, boolean, enum, json. */
function kindOf(doc, prop) {
  const s = resolveSchema(doc, prop);
  if (Array.isArray(s.enum)) return { type: 'enum', values: s.enum.filter((v) => v !== null) };
  const types = [].concat(s.type || []).filter((t) => t !== 'null');
  const t = types[0] || 'json';
  return { type: t === 'array' || t === 'object' ? 'json' : t };
}

/** A form for one row's data; `read()` gives the values, or throws naming the bad field. */
function rowForm(doc, schema, values, refs = {}) {
  const props = schema.properties || {};
  const required = new Set(schema.required || []);
  const inputs = {};
  const fields = Object.entries(props).map(([key, prop]) => {
    const id = `row-${key}`;
    const kind = kindOf(doc, prop);
    const value = values[key];
    let control;
    if (refs[key]) {
      control = h('select', { id }, refs[key].map(([v, label]) => h('option', { value: v, selected: v === value }, `${label} (#${v})`)));
      kind.type = 'integer';
    } else if (kind.type === 'boolean') control = h('input', { id, type: 'checkbox', checked: Boolean(value) });
    else if (kind.type === 'enum') {
      control = h('select', { id }, required.has(key) ? null : h('option', { value: '' }, '—'),
        kind.values.map((v) => h('option', { value: v, selected: v === value }, v)));
    } else if (kind.type === 'json') control = h('textarea', { id, class: 'code', rows: 3, value: value === undefined ? '' : JSON.stringify(value) });
    else if (key === 'reference') control = h('textarea', { id, rows: 2, value: value ?? '' });
    else {
      control = h('input', { id, type: kind.type === 'string' ? 'text' : 'number', step: kind.type === 'integer' ? '1' : 'any',
        inputmode: kind.type === 'string' ? null : 'decimal', value: value ?? '', required: required.has(key) });
    }
    inputs[key] = { control, kind };
    const hint = (resolveSchema(doc, prop).description || prop.description || '').split('\n')[0];
    return h('div', { class: `field${kind.type === 'json' || key === 'reference' ? ' wide' : ''}` },
      h('label', { for: id }, heading(key), required.has(key) ? ' *' : ''), control, hint ? h('small', { class: 'hint' }, hint) : null);
  });
  const read = () => {
    const out = {};
    for (const [key, { control, kind }] of Object.entries(inputs)) {
      if (kind.type === 'boolean') { out[key] = control.checked; continue; }
      const raw = control.value.trim();
      if (raw === '') { out[key] = kind.type === 'string' ? '' : null; continue; }
      if (kind.type === 'number' || kind.type === 'integer') out[key] = Number(raw);
      else if (kind.type === 'json') {
        try { out[key] = JSON.parse(raw); } catch (err) { throw Object.assign(new Error(`${key}: not valid JSON (${err.message})`), { field: key }); }
      } else out[key] = raw;
    }
    return out;
  };
  return { node: h('div', { class: 'grid' }, fields), read };
}

export async function databaseView(key, params) {
  const spec = TABLES[key];
  if (!spec) {
    location.replace('#/db/tools');
    return { node: h('div') };
  }
  const offset = Math.max(0, Number(params.get('offset')) || 0);
  const [page, doc, tools, materials] = await Promise.all([
    api('GET', `${spec.path}?limit=${PAGE}&offset=${offset}`),
    openapi(),
    api('GET', '/v1/tools?limit=500').then((r) => r.items),
    api('GET', '/v1/materials?limit=500').then((r) => r.items),
  ]);
  const refs = { tool_id: tools.map((t) => [t.id, t.name]), material_id: materials.map((m) => [m.id, m.name]) };
  const toolName = (id) => tools.find((t) => t.id === id)?.name || `#${id}`;
  const dataSchema = resolveSchema(doc, doc.paths[spec.path]?.post?.requestBody?.content?.['application/json']?.schema);
  const dialog = h('dialog', { class: 'editor', 'aria-labelledby': 'editor-title' });

  function openEditor(row) {
    const isNew = !row;
    const start = isNew ? { ...(dataSchema.example || {}) } : row;
    const form = rowForm(doc, dataSchema, start, refs);
    const problemSlot = h('div', { 'aria-live': 'polite' });
    const close = () => dialog.close();
    const save = h('button', { type: 'submit', class: 'primary' }, isNew ? 'Add row' : 'Save changes');
    const del = isNew ? null : h('button', { type: 'button', class: 'danger', onclick: async () => {
      if (!window.confirm(`Delete ${spec.title.toLowerCase()} row ${row.id}${row.name ? ` (${row.name})` : ''}? This cannot be undone.`)) return;
      try {
        await api('DELETE', `${spec.path}/${row.id}`);
        close();
        window.dispatchEvent(new Event('dieplan:refresh'));
      } catch (err) { problemSlot.replaceChildren(problemBox(err, 'Not deleted')); }
    } }, 'Delete row');
    const formEl = h('form', { method: 'dialog', novalidate: true, onsubmit: async (event) => {
      event.preventDefault();
      problemSlot.replaceChildren();
      let data;
      try { data = form.read(); } catch (err) { problemSlot.replaceChildren(problemBox(err, 'Check the form')); return; }
      try {
        if (isNew) {
          for (const [k, v] of Object.entries(data)) if (v === null || v === '') delete data[k];
          await api('POST', spec.path, data);
        } else {
          const patch = {};
          for (const [k, v] of Object.entries(data)) if (JSON.stringify(v ?? null) !== JSON.stringify(row[k] ?? null)) patch[k] = v;
          if (!Object.keys(patch).length) { problemSlot.replaceChildren(h('p', { class: 'hint' }, 'Nothing changed.')); return; }
          await api('PATCH', `${spec.path}/${row.id}`, patch, { contentType: 'application/merge-patch+json' });
        }
        close();
        window.dispatchEvent(new Event('dieplan:refresh'));
      } catch (err) {
        problemSlot.replaceChildren(problemBox(err, isNew ? 'Not added' : 'Not saved'));
        for (const e of err.problem?.errors || []) document.getElementById(`row-${e.field.split(/[.[]/)[0]}`)?.setAttribute('aria-invalid', 'true');
      }
    } },
    h('div', { class: 'editor-head' }, h('h2', { id: 'editor-title' }, isNew ? `New ${spec.title.toLowerCase()} row` : `${spec.title}: row ${row.id}`),
      h('button', { type: 'button', class: 'link', onclick: close, 'aria-label': 'Close' }, '✕')),
    isNew ? h('p', { class: 'hint' }, 'Rows you add are marked source “user”. Fields marked * are required.')
      : h('p', { class: 'provenance' }, 'Source: ', h('strong', {}, row.source), row.edited ? ' (edited by the shop)' : '', row.reference ? ` — ${row.reference}` : '',
        h('br'), h('small', { class: 'hint' }, 'Saving sends only the changed fields as a JSON merge patch; unless you set the source, the row becomes the shop’s (source “user”).')),
    form.node, problemSlot, h('div', { class: 'actions' }, save, h('button', { type: 'button', onclick: close }, 'Cancel'), del));
    dialog.replaceChildren(formEl);
    dialog.showModal();
    formEl.querySelector('input, select, textarea')?.focus();
  }

  const columns = [
    ['id', (r) => h('button', { type: 'button', class: 'link', title: 'Edit this row', onclick: () => openEditor(r) }, String(r.id))],
    ...spec.columns.map((c) => [heading(c), (r) => (c === 'tool_id' ? toolName(r.tool_id) : cell(r[c]))]),
    ['source', (r) => h('span', { class: `source source-${r.source}` }, r.source, r.edited ? ' ✎' : '')],
    ['reference', (r) => h('span', { class: 'reference', title: r.reference || '' }, r.reference || '')],
  ];
  const last = Math.min(offset + page.items.length, page.total);
  const pageLink = (label, to, enabled) => (enabled ? h('a', { class: 'button', href: `#/db/${key}?offset=${to}` }, label) : h('span', { class: 'button disabled', 'aria-disabled': 'true' }, label));
  const node = h('div', { id: 'database' },
    h('div', { class: 'title-row' }, h('h1', {}, 'Cutting-condition database'),
      h('button', { type: 'button', class: 'primary', onclick: () => openEditor(null) }, `Add ${spec.title.toLowerCase()} row`)),
    h('nav', { class: 'tabs', 'aria-label': 'tables' }, Object.entries(TABLES).map(([k, t]) =>
      h('a', { href: `#/db/${k}`, 'aria-current': k === key ? 'page' : null }, t.title))),
    h('p', { class: 'hint' }, 'Every row says where its values come from: paper, extrapolated, assumed (our defaults where the papers are silent: replace them with your shop’s values), fitted or user. Click a row to edit it.'),
    table(columns, page.items, { onRow: openEditor, empty: 'This table is empty.' }),
    h('nav', { class: 'pager', 'aria-label': 'pages' },
      pageLink('← Previous', Math.max(0, offset - PAGE), offset > 0),
      h('span', {}, page.total ? `${offset + 1}–${last} of ${page.total}` : '0 rows'),
      pageLink('Next →', offset + PAGE, last < page.total)),
    dialog);
  return { node, title: spec.title, cleanup: () => dialog.open && dialog.close() };
}
