// The "New job" form: operation, source (built-in example, pasted text, uploaded file),
// tool and material from the database, the operation's key options, and the exact JSON
// request, editable. Submits to the operation's endpoint and opens the job.
import { h, api, problemBox, pretty, parseTags, ENDPOINTS, KIND_NAMES, openapi } from './ui.js';

const OPERATIONS = [
  ['trochoids', 'Trochoids', 'Insert trochoid cycles where a pocket’s roughing path overloads the tool'],
  ['analysis', 'Analysis', 'Where a tool path overloads the tool (engagement angle α above the limit)'],
  ['feeds', 'Feeds', 'Set every block’s feed for a constant cutting force; writes the NC program'],
  ['costing', 'Costing', 'Machining time, tool-life consumption and cost of a program'],
  ['plan', 'Plan', 'Plan a whole cavity: tool choice, layers, trochoids, feeds, cost'],
];

/** Path jobs take a program and a stock box; pocket jobs a contour (or DXF) and depths. */
const POCKET_KINDS = new Set(['trochoids', 'plan']);
/** The kinds whose program file is sent as a file (multipart/form-data: the `program`
 * part and the rest of the request as the `request` part); pasted text goes as JSON. */
const UPLOAD_KINDS = new Set(['analysis', 'feeds', 'costing']);
const REQUEST_SCHEMAS = {
  analysis: 'AnalysisRequest', trochoids: 'TrochoidsRequest', feeds: 'FeedsRequest',
  costing: 'CostingRequest', plan: 'PlanRequest',
};

const num = (key, label, unit, placeholder, extra = {}) => ({ key, label, unit, placeholder, type: 'number', ...extra });
const DEPTHS = [
  num('z_top', 'Top of the material', 'mm', '', { value: '0', required: true }),
  num('z_bottom', 'Bottom of the pocket', 'mm', '', { value: '-10', required: true }),
];
const FIELDS = {
  analysis: [
    num('alpha_limit_deg', 'Engagement limit α', '°', '40'),
    num('spindle_rpm', 'Spindle speed (if no S word)', 'min⁻¹', 'database'),
    num('series_points', 'Chart points', 'points', '0', { value: '400', step: '1', min: '0' }),
    num('sample_spacing_mm', 'Sample spacing', 'mm', 'min(0.05, D/100)'),
  ],
  trochoids: [
    ...DEPTHS,
    num('alpha_limit_deg', 'Engagement limit α', '°', '40'),
    num('allowance_mm', 'Allowance on walls', 'mm', '0'),
    num('pitch_mm', 'Largest trochoid pitch', 'mm', 'r(1 − cos α limit)'),
    num('zcut_ad_mm', 'Z-cut depth per pass', 'mm', '2.5'),
    { key: 'direction', label: 'Direction', type: 'select', options: [['', 'climb (default)'], ['conventional', 'conventional']] },
  ],
  feeds: [
    { key: 'strategy', label: 'Strategy', type: 'select', options: [['constant_force', 'constant force'], ['cutting_point', 'constant feed at the cutting point'], ['both', 'both']], value: 'constant_force' },
    num('target_force_n', 'Target force', 'N', 'tool’s β0'),
    num('min_feed_mm_min', 'Minimum feed', 'mm/min', 'database'),
    num('max_feed_mm_min', 'Maximum feed', 'mm/min', '2 × standard'),
    num('max_feed_change_per_mm', 'Feed change limit', 'mm/min per mm', '1000'),
    { key: 'output.dialect', label: 'NC dialect', type: 'select', options: [['', 'Fanuc (default)'], ['linux_cnc', 'LinuxCNC']] },
  ],
  costing: [
    num('tool_price', 'Tool price', 'cost-rate currency', 'tool’s price'),
    num('spindle_rpm', 'Spindle speed (if no S word)', 'min⁻¹', 'database'),
  ],
  plan: [
    ...DEPTHS.map((f) => (f.key === 'z_bottom' ? { ...f, value: '-20' } : f)),
    num('target_consumption', 'Share of one tool’s life to use', '0–1', '0.9'),
    num('alpha_limit_deg', 'Engagement limit α', '°', '40'),
    num('allowance_mm', 'Allowance on walls', 'mm', '0'),
    { key: 'baseline', label: 'Compare with the ball-end baseline', type: 'checkbox', value: true },
  ],
};
const BOX = ['x_min', 'x_max', 'y_min', 'y_max', 'z_min', 'z_max'];

const getPath = (obj, path) => path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
function setPath(obj, path, value) {
  const keys = path.split('.');
  let o = obj;
  for (const k of keys.slice(0, -1)) o = o[k] && typeof o[k] === 'object' ? o[k] : (o[k] = {});
  if (value === undefined) delete o[keys.at(-1)];
  else o[keys.at(-1)] = value;
}

/** Rough extent of a G-code program's cutting moves (absolute coordinates). */
export function programExtent(gcode) {
  let motion = 0; const pos = { X: 0, Y: 0, Z: 0 }; const ext = {};
  for (const raw of gcode.split(/\r?\n/)) {
    const line = raw.replace(/\(.*?\)|;.*$/g, '').toUpperCase();
    for (const [, g] of line.matchAll(/G0*([0-3])(?![0-9.])/g)) motion = Number(g);
    let moved = false;
    for (const [, axis, value] of line.matchAll(/([XYZ])\s*([-+]?\d*\.?\d+)/g)) { pos[axis] = Number(value); moved = true; }
    if (moved && motion > 0) {
      for (const a of 'XYZ') {
        ext[`${a}min`] = Math.min(ext[`${a}min`] ?? Infinity, pos[a]);
        ext[`${a}max`] = Math.max(ext[`${a}max`] ?? -Infinity, pos[a]);
      }
    }
  }
  if (ext.Xmin === undefined) return null;
  return { x_min: ext.Xmin, x_max: ext.Xmax, y_min: ext.Ymin, y_max: ext.Ymax, z_min: ext.Zmin, z_max: Math.max(0, ext.Zmin < 0 ? 0 : ext.Zmax) };
}

const looksLikeDxf = (text) => /(^|\n)\s*SECTION\s*\r?\n/.test(text) && /ENTITIES/.test(text);

export async function newJobView(params) {
  const [examples, tools, materials, doc] = await Promise.all([
    api('GET', '/v1/examples').then((r) => r.items),
    api('GET', '/v1/tools?limit=500').then((r) => r.items),
    api('GET', '/v1/materials?limit=500').then((r) => r.items),
    openapi(),
  ]);
  const allowed = (kind) => new Set(Object.keys(doc.components.schemas[REQUEST_SCHEMAS[kind]]?.properties || {}));
  const state = {
    kind: 'trochoids', source: 'example', exampleId: null, text: '', fileName: '', file: null,
    toolId: '', materialId: materials[0] ? String(materials[0].id) : '', planType: 'square', diameters: new Set(),
    name: '', tags: '', values: {}, box: { x_min: '0', x_max: '100', y_min: '0', y_max: '50', z_min: '-10', z_max: '0' }, jsonEdited: false,
  };
  const exampleFor = (kind) => examples.filter((e) => POCKET_KINDS.has(e.kind) === POCKET_KINDS.has(kind))
    .sort((a, b) => (b.kind === kind) - (a.kind === kind));
  const toolOf = (type, d) => tools.find((t) => t.tool_type === type && Math.abs(t.diameter_mm - d) < 1e-6);
  const defaultTool = toolOf('square', 10) || tools[0];
  state.toolId = defaultTool ? String(defaultTool.id) : '';

  function resetValues() {
    state.values = {};
    for (const f of FIELDS[state.kind]) state.values[f.key] = f.value ?? '';
  }

  /** Fills the form from an example's input. */
  function applyExample(example) {
    state.exampleId = example?.id || null;
    resetValues();
    if (!example) return;
    const input = example.input;
    for (const f of FIELDS[state.kind]) {
      const v = getPath(input, f.key);
      if (v !== undefined) state.values[f.key] = f.type === 'checkbox' ? Boolean(v) : String(v);
    }
    if (input.stock?.box) for (const k of BOX) state.box[k] = String(input.stock.box[k]);
    const tool = input.tool_id ? tools.find((t) => t.id === input.tool_id) : toolOf(input.tool_type || 'square', input.diameter_mm ?? 10);
    if (tool) state.toolId = String(tool.id);
    if (input.tool_type && state.kind === 'plan') state.planType = input.tool_type;
    state.diameters = new Set((input.diameters_mm || []).map(Number));
  }

  function setKind(kind) {
    state.kind = kind;
    const list = exampleFor(kind);
    if (state.source === 'example') applyExample(list.find((e) => e.id === state.exampleId) || list[0]);
    else resetValues();
  }

  /** `true` when the job is sent as a file upload (a program file of a kind that takes one). */
  const uploading = () => state.source === 'file' && Boolean(state.file) && UPLOAD_KINDS.has(state.kind);

  /** The request the form describes. */
  function buildRequest() {
    const keep = allowed(state.kind);
    const example = examples.find((e) => e.id === state.exampleId);
    const request = {};
    if (state.source === 'example' && example) {
      for (const [k, v] of Object.entries(structuredClone(example.input))) if (keep.has(k)) request[k] = v;
    } else if (uploading()) {
      // The program goes as the file part; the request part is the rest.
      delete request.program;
    } else if (state.text.trim()) {
      if (POCKET_KINDS.has(state.kind)) request.dxf = state.text;
      else request.program = { gcode: state.text };
    }
    for (const k of ['tool_id', 'tool_type', 'diameter_mm', 'material', 'diameters_mm']) delete request[k];
    if (state.kind === 'plan') {
      request.tool_type = state.planType;
      if (state.diameters.size) request.diameters_mm = [...state.diameters].sort((a, b) => a - b);
    } else if (state.toolId) request.tool_id = Number(state.toolId);
    if (state.materialId) request.material_id = Number(state.materialId);
    for (const f of FIELDS[state.kind]) {
      const raw = state.values[f.key];
      let value;
      if (f.type === 'checkbox') value = Boolean(raw);
      else if (raw === '' || raw === undefined) value = undefined;
      else if (f.type === 'number') value = Number(raw);
      else value = raw;
      setPath(request, f.key, value);
    }
    if (request.output && !Object.keys(request.output).length) delete request.output;
    if (state.name.trim()) request.name = state.name.trim();
    const tags = parseTags(state.tags);
    if (tags.length) request.tags = tags;
    if (!POCKET_KINDS.has(state.kind)) {
      const box = Object.fromEntries(BOX.map((k) => [k, state.box[k] === '' ? null : Number(state.box[k])]));
      request.stock = { ...(request.stock || {}), box };
      delete request.stock.contour; delete request.stock.dxf;
    }
    return request;
  }

  // ----- rendering -----
  const root = h('form', { class: 'new-job', novalidate: true });
  const problemSlot = h('div', { class: 'problem-slot', 'aria-live': 'polite' });
  const jsonArea = h('textarea', { id: 'json-input', class: 'code', rows: 16, spellcheck: 'false', 'aria-describedby': 'json-note' });
  const jsonNote = h('p', { id: 'json-note', class: 'hint' });
  const endpointLine = h('code', { class: 'endpoint' });
  const details = h('details', { class: 'card advanced' },
    h('summary', {}, 'Advanced: the JSON request that will be sent'),
    h('p', {}, endpointLine), jsonArea, jsonNote);
  const sections = h('div');
  const submit = h('button', { type: 'submit', class: 'primary', id: 'submit-job' }, 'Run');

  function refreshJson() {
    endpointLine.textContent = uploading()
      ? `POST ${ENDPOINTS[state.kind]}  (multipart/form-data: program = ${state.fileName}, request = the JSON below)`
      : `POST ${ENDPOINTS[state.kind]}  (content-type: application/json)`;
    submit.textContent = `Run ${KIND_NAMES[state.kind].toLowerCase()}`;
    jsonNote.replaceChildren();
    if (state.jsonEdited) {
      jsonNote.append('You edited the JSON: it is sent as it is and the form above no longer changes it. ',
        h('button', { type: 'button', class: 'link', onclick: () => { state.jsonEdited = false; refreshJson(); } }, 'Discard my edits and use the form'));
      return;
    }
    jsonArea.value = pretty(buildRequest());
    jsonNote.textContent = 'Edit it to send fields the form does not show (see the API docs for every field).';
  }
  jsonArea.addEventListener('input', () => {
    if (!state.jsonEdited) { state.jsonEdited = true; refreshJson(); }
  });

  const field = (id, label, control, { unit, hint } = {}) => h('div', { class: 'field' },
    h('label', { for: id }, label, unit ? h('span', { class: 'unit' }, ` (${unit})`) : null), control,
    hint ? h('small', { class: 'hint' }, hint) : null);
  const onChange = (fn) => (event) => { fn(event.target); refreshJson(); };

  function operationSection() {
    return h('fieldset', { class: 'card' }, h('legend', {}, 'Operation'),
      h('div', { class: 'segmented', role: 'radiogroup' }, OPERATIONS.map(([kind, label, title]) => h('label', { title },
        h('input', { type: 'radio', name: 'kind', value: kind, checked: state.kind === kind,
          onchange: () => { setKind(kind); render(); } }), h('span', {}, label)))),
      h('p', { class: 'hint' }, OPERATIONS.find(([k]) => k === state.kind)[2], '.'));
  }

  function sourceSection() {
    const list = exampleFor(state.kind);
    const pocket = POCKET_KINDS.has(state.kind);
    const what = pocket ? 'the pocket as DXF text (LINE, ARC, CIRCLE, LWPOLYLINE; the outermost loop is the pocket)' : 'the tool path as G-code (ISO/Fanuc or LinuxCNC)';
    const radios = h('div', { class: 'segmented', role: 'radiogroup' }, [['example', 'Built-in example'], ['text', 'Paste text'], ['file', 'Upload file']]
      .map(([value, label]) => h('label', {}, h('input', { type: 'radio', name: 'source', value, checked: state.source === value,
        onchange: () => { state.source = value; if (value === 'example') applyExample(list[0]); render(); } }), h('span', {}, label))));
    const body = [];
    if (state.source === 'example') {
      const current = list.find((e) => e.id === state.exampleId);
      body.push(field('example', 'Example', h('select', { id: 'example', onchange: (e) => { applyExample(examples.find((x) => x.id === e.target.value)); render(); } },
        list.map((e) => h('option', { value: e.id, selected: e.id === state.exampleId }, e.kind === state.kind ? e.title : `${e.title} (as ${/^[aeiou]/.test(e.kind) ? 'an' : 'a'} ${e.kind} job’s input)`)))),
      current ? h('p', { class: 'hint' }, current.description) : h('p', { class: 'hint' }, 'No example for this operation.'));
    } else {
      if (state.source === 'file') {
        body.push(field('file', `File with ${pocket ? 'the pocket (DXF)' : 'the NC program'}`, h('input', { id: 'file', type: 'file', dataset: { field: pocket ? 'dxf' : 'program' },
          accept: pocket ? '.dxf,.txt' : '.nc,.ngc,.tap,.gcode,.cnc,.txt,.iso,.eia',
          onchange: async (e) => {
            const file = e.target.files[0];
            if (!file) return;
            state.text = await file.text();
            state.fileName = file.name;
            state.file = file;
            render();
          } }), { hint: state.fileName
          ? `${state.fileName}: ${state.text.split('\n').length} lines${UPLOAD_KINDS.has(state.kind) ? ', sent as a file (multipart upload).' : '. You can edit it below.'}`
          : UPLOAD_KINDS.has(state.kind) ? 'Sent as a file (multipart upload), as it is.' : 'Read in the browser as text and sent in the request.' }));
        if (uploading()) {
          return h('fieldset', { class: 'card' }, h('legend', {}, 'Source'), radios, body,
            h('pre', { class: 'code file-preview', 'aria-label': 'the file’s first lines' }, state.text.split('\n').slice(0, 8).join('\n')));
        }
      }
      const area = h('textarea', { id: 'source-text', class: 'code', rows: 10, spellcheck: 'false', dataset: { field: pocket ? 'dxf' : 'program' },
        placeholder: pocket ? '0\nSECTION\n2\nENTITIES\n…' : 'G21 G90 G17\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\n…', value: state.text,
        oninput: onChange((t) => { state.text = t.value; }) });
      body.push(field('source-text', pocket ? 'Pocket (DXF text)' : 'Tool path (G-code)', area, { hint: `Paste ${what}.` }));
      if (pocket && state.text && !looksLikeDxf(state.text)) body.push(h('p', { class: 'warning' }, 'This does not look like DXF text: a pocket job needs the pocket contour as DXF.'));
    }
    return h('fieldset', { class: 'card' }, h('legend', {}, 'Source'), radios, body);
  }

  function toolSection() {
    const materialSelect = h('select', { id: 'material', dataset: { field: 'material_id' }, onchange: onChange((t) => { state.materialId = t.value; }) },
      materials.map((m) => h('option', { value: m.id, selected: String(m.id) === state.materialId }, `${m.name}${m.hardness_hrc ? ` (HRC ${m.hardness_hrc})` : ''}`)));
    const items = [field('material', 'Material', materialSelect)];
    if (state.kind === 'plan') {
      const types = [...new Set(tools.map((t) => t.tool_type))].filter((t) => t !== 'ball');
      items.push(field('plan-type', 'End-mill type', h('select', { id: 'plan-type', dataset: { field: 'tool_type' }, onchange: (e) => { state.planType = e.target.value; state.diameters.clear(); render(); } },
        types.map((t) => h('option', { value: t, selected: t === state.planType }, t)))));
      const ds = [...new Set(tools.filter((t) => t.tool_type === state.planType).map((t) => t.diameter_mm))].sort((a, b) => a - b);
      items.push(h('fieldset', { class: 'field checks', dataset: { field: 'diameters_mm' } }, h('legend', {}, 'Candidate diameters (mm; none ticked: every one)'),
        ds.map((d) => h('label', {}, h('input', { type: 'checkbox', value: d, checked: state.diameters.has(d),
          onchange: onChange((t) => { if (t.checked) state.diameters.add(d); else state.diameters.delete(d); }) }), ` ${d}`))));
    } else {
      const groups = {};
      for (const t of tools) (groups[t.tool_type] ||= []).push(t);
      items.push(field('tool', 'End mill', h('select', { id: 'tool', dataset: { field: 'tool_id' }, onchange: onChange((t) => { state.toolId = t.value; }) },
        Object.entries(groups).map(([type, list]) => h('optgroup', { label: type }, list.map((t) => h('option', { value: t.id, selected: String(t.id) === state.toolId },
          `${t.name} · ${t.flutes} flutes${t.source === 'user' ? ' · shop' : ''}`)))))));
    }
    return h('fieldset', { class: 'card' }, h('legend', {}, 'Tool and material'), h('div', { class: 'grid' }, items));
  }

  function optionsSection() {
    const controls = FIELDS[state.kind].map((f) => {
      const id = `opt-${f.key.replace(/\./g, '-')}`;
      const value = state.values[f.key];
      if (f.type === 'checkbox') {
        return h('div', { class: 'field check' }, h('label', {}, h('input', { id, type: 'checkbox', checked: value, dataset: { field: f.key },
          onchange: onChange((t) => { state.values[f.key] = t.checked; }) }), ` ${f.label}`));
      }
      const control = f.type === 'select'
        ? h('select', { id, dataset: { field: f.key }, onchange: onChange((t) => { state.values[f.key] = t.value; }) },
          f.options.map(([v, label]) => h('option', { value: v, selected: v === (value ?? '') }, label)))
        : h('input', { id, type: 'number', step: f.step || 'any', min: f.min, inputmode: 'decimal', required: f.required,
          placeholder: f.placeholder || '', value: value ?? '', dataset: { field: f.key },
          oninput: onChange((t) => { state.values[f.key] = t.value; }) });
      return field(id, f.label, control, { unit: f.unit });
    });
    const out = [h('fieldset', { class: 'card' }, h('legend', {}, 'Options'), h('p', { class: 'hint' }, 'Leave a field empty for the default shown in grey (from the database or the model).'), h('div', { class: 'grid options' }, controls))];
    if (!POCKET_KINDS.has(state.kind)) {
      const inputs = BOX.map((k) => field(`box-${k}`, k.replace('_', ' '), h('input', { id: `box-${k}`, type: 'number', step: 'any', inputmode: 'decimal', required: true, value: state.box[k], dataset: { field: `stock.box.${k}` },
        oninput: onChange((t) => { state.box[k] = t.value; }) }), { unit: 'mm' }));
      const boxMessage = h('small', { class: 'hint', 'aria-live': 'polite' });
      const guess = state.source === 'example' ? null : h('button', { type: 'button',
        onclick: () => {
          const e = programExtent(uploading() ? state.text : buildRequest().program?.gcode || '');
          if (!e) { boxMessage.textContent = ' Paste or upload a program with cutting moves (G1, G2, G3) first.'; return; }
          for (const k of BOX) state.box[k] = String(e[k]);
          render();
        } }, 'Fit box to the program’s cutting moves');
      out.push(h('fieldset', { class: 'card' }, h('legend', {}, 'Stock box'), h('p', { class: 'hint' }, 'The block of material the layer cuts, in program coordinates.',
        state.source === 'example' && buildRequest().stock?.open ? ' The example also has regions already open (see the JSON).' : ''), h('div', { class: 'grid box' }, inputs), guess, boxMessage));
    }
    return out;
  }

  // What to call the job and its tags: shown in the job and the list, and searched there.
  function labelsSection() {
    return h('fieldset', { class: 'card' }, h('legend', {}, 'Job'), h('div', { class: 'grid' },
      field('job-name', 'Name', h('input', { id: 'job-name', type: 'text', maxlength: 200, value: state.name, placeholder: 'e.g. Die 4711, cavity A, roughing',
        autocomplete: 'off', dataset: { field: 'name' }, oninput: onChange((t) => { state.name = t.value; }) }), { hint: 'Optional; up to 200 characters.' }),
      field('job-tags', 'Tags', h('input', { id: 'job-tags', type: 'text', value: state.tags, placeholder: 'die:4711 roughing',
        autocomplete: 'off', spellcheck: 'false', dataset: { field: 'tags' }, oninput: onChange((t) => { state.tags = t.value; }) }),
      { hint: 'Optional; separated by spaces or commas: letters, digits and - _ . : / (up to 20).' })));
  }

  function render() {
    // Re-rendering replaces the controls: keep the keyboard focus where it was.
    const active = document.activeElement;
    let selector = null;
    if (active && root.contains(active)) {
      if (active.id) selector = `#${CSS.escape(active.id)}`;
      else if (active.name) selector = `[name="${CSS.escape(active.name)}"][value="${CSS.escape(active.value)}"]`;
    }
    sections.replaceChildren(operationSection(), labelsSection(), sourceSection(), toolSection(), ...optionsSection());
    refreshJson();
    if (selector) root.querySelector(selector)?.focus();
  }

  function markFields(errors) {
    root.querySelectorAll('[aria-invalid]').forEach((el) => el.removeAttribute('aria-invalid'));
    root.querySelectorAll('.field-error').forEach((el) => el.remove());
    for (const e of errors || []) {
      const target = [...root.querySelectorAll('[data-field]')]
        .filter((el) => e.field === el.dataset.field || e.field.startsWith(`${el.dataset.field}.`) || e.field.startsWith(`${el.dataset.field}[`))
        .sort((a, b) => b.dataset.field.length - a.dataset.field.length)[0];
      if (!target) continue;
      target.setAttribute('aria-invalid', 'true');
      (target.closest('.field') || target).append(h('small', { class: 'field-error' }, e.reason));
    }
  }

  root.addEventListener('submit', async (event) => {
    event.preventDefault();
    problemSlot.replaceChildren();
    markFields([]);
    let body;
    try {
      body = state.jsonEdited ? JSON.parse(jsonArea.value) : buildRequest();
    } catch (err) {
      details.open = true;
      problemSlot.append(problemBox({ message: `The JSON request is not valid JSON: ${err.message}` }, 'Cannot send the request'));
      return;
    }
    submit.disabled = true;
    submit.textContent = 'Submitting…';
    try {
      let sent = body;
      if (uploading()) {
        sent = new FormData();
        sent.append('program', state.file, state.fileName);
        sent.append('request', new Blob([JSON.stringify(body)], { type: 'application/json' }));
      }
      const job = await api('POST', ENDPOINTS[state.kind], sent);
      location.hash = `#/jobs/${job.id}`;
    } catch (err) {
      problemSlot.append(problemBox(err, 'The service refused the job'));
      markFields(err.problem?.errors);
      problemSlot.scrollIntoView({ block: 'nearest', behavior: 'smooth' });
    } finally {
      submit.disabled = false;
      refreshJson();
    }
  });

  // Start from an example, a previous job's input, or the default operation.
  const fromExample = examples.find((e) => e.id === params.get('example'));
  if (fromExample) state.kind = fromExample.kind;
  setKind(state.kind);
  if (fromExample) applyExample(fromExample);
  render();
  // A previous job's input to edit, or a costing of a finished job's NC program.
  const source = params.get('from') || params.get('cost');
  if (source) {
    const job = await api('GET', `/v1/jobs/${encodeURIComponent(source)}`);
    const original = await api('GET', job.links.input);
    let kind = job.kind;
    let input = original;
    if (params.get('cost')) {
      kind = 'costing';
      const keep = allowed('costing');
      input = Object.fromEntries(Object.entries(original).filter(([k]) => keep.has(k) && k !== 'program'));
      input = { job_id: job.id, ...input };
    }
    if (REQUEST_SCHEMAS[kind]) {
      setKind(kind);
      render();
      state.jsonEdited = true;
      jsonArea.value = pretty(input);
      details.open = true;
      refreshJson();
      problemSlot.append(h('p', { class: 'hint' }, params.get('cost')
        ? `Costs the NC program of job ${job.id.slice(0, 8)} in the same stock, with the same tool. Edit the JSON below or run it as it is.`
        : `The input of job ${job.id.slice(0, 8)}: edit the JSON below and run it again.`));
    }
  }

  root.append(h('h1', {}, 'New job'), sections, details, problemSlot, h('div', { class: 'actions' }, submit));
  return { node: root, title: 'New job' };
}
