// Drives the dieplan web page in headless chromium (Debian's, via playwright-core):
// new job from the built-in trochoids example, its progress, result, NC program, the jobs
// list, the database, the drawing with its charts, and the key prompt once the service has
// keys; desktop and phone screenshots.
//
//   node tests/browser/page.test.mjs http://127.0.0.1:8080
//
// Exits non-zero with the failed step's message. tests/browser/run.sh starts the service.
import { chromium } from 'playwright-core';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { labelSteps, linkSteps } from './workbench.steps.mjs';
import { drawingSteps, uploadSteps } from './workbench3.steps.mjs';
import { view3dSteps } from './view3d.steps.mjs';

const BASE = (process.argv[2] || process.env.DIEPLAN || 'http://127.0.0.1:8080').replace(/\/$/, '');
const SHOTS = resolve(process.env.SCREENSHOT_DIR || 'target/browser-screenshots');
const JOB_TIMEOUT_MS = 120_000;
// WebGL without a GPU for the 3-D view: ANGLE on SwiftShader, Chromium's CPU renderer,
// asked for by name (Chromium 148 still falls back to it, but is deprecating the fallback).
const ARGS = ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', '--disable-dev-shm-usage'];

const consoleErrors = [];
const shots = [];
let current = 'starting';

function check(condition, message) {
  if (!condition) throw new Error(message);
}

async function step(name, fn) {
  current = name;
  const t0 = Date.now();
  await fn();
  console.log(`ok: ${name} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
}

async function shot(page, name) {
  const path = join(SHOTS, `${name}.png`);
  await page.screenshot({ path, fullPage: true });
  shots.push(path);
}

rmSync(SHOTS, { recursive: true, force: true });
mkdirSync(SHOTS, { recursive: true });
const profile = mkdtempSync(join(tmpdir(), 'dieplan-chromium-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ARGS,
  viewport: { width: 1280, height: 800 },
  acceptDownloads: true,
});
let failed = false;
try {
  const page = context.pages()[0] || await context.newPage();
  page.setDefaultTimeout(15_000);
  page.on('console', (msg) => { if (msg.type() === 'error') consoleErrors.push(`${msg.text()} (${msg.location().url || 'page'})`); });
  page.on('pageerror', (err) => consoleErrors.push(`uncaught: ${err.message}`));
  let jobId;
  let feedsJobId;

  await step('the page loads at / with its form filled from the API', async () => {
    const response = await page.goto(`${BASE}/`);
    check(response.ok(), `GET / answered ${response.status()}`);
    check((response.headers()['content-type'] || '').startsWith('text/html'), 'GET / is not text/html');
    await page.waitForSelector('#submit-job');
    await page.waitForSelector('#tool option', { state: 'attached' });
    check((await page.locator('h1').innerText()) === 'New job', 'the start page is not "New job"');
  });

  await step('pick the built-in trochoids example', async () => {
    await page.check('input[name="kind"][value="trochoids"]', { force: true });
    await page.check('input[name="source"][value="example"]', { force: true });
    await page.selectOption('#example', 'pocket-slot-trochoids');
    const json = JSON.parse(await page.inputValue('#json-input'));
    check(Array.isArray(json.contour?.outer) && json.z_bottom === -10, `the JSON request is not the example's: ${JSON.stringify(json).slice(0, 200)}`);
    check(Number.isInteger(json.tool_id), 'the request names no tool_id');
    await shot(page, 'desktop-new-job');
  });

  await step('submit and wait for the job to succeed', async () => {
    await page.click('#submit-job');
    await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
    jobId = page.url().split('/').pop();
    await page.waitForSelector('.badge-succeeded, .badge-failed, .badge-cancelled', { timeout: JOB_TIMEOUT_MS });
    const status = await page.locator('.status-card .badge').innerText();
    check(status === 'succeeded', `the job ended ${status}: ${await page.locator('.status-card').innerText()}`);
  });

  await step('the result shows its key figures and the verification passed', async () => {
    await page.waitForSelector('.figures');
    const text = await page.locator('.job-body').innerText();
    check(/Verification\s*passed/i.test(text), `no passed verification in the summary: ${text.slice(0, 400)}`);
  });

  await step('the trochoids job shows what the change saves, before → after', async () => {
    await page.waitForSelector('#savings .saving');
    const cards = await page.$$eval('#savings .saving', (els) => els.map((e) => ({
      id: e.dataset.figure, before: e.querySelector('.before')?.textContent, after: e.querySelector('.after')?.textContent,
      change: e.querySelector('.saving-change')?.textContent || '' })));
    const ids = cards.map((c) => c.id);
    for (const id of ['nominal-time', 'kinematic-time', 'length', 'rapid-length', 'air-cut', 'tool-use', 'cost', 'max-alpha']) {
      check(ids.includes(id), `no "${id}" card: ${JSON.stringify(cards)}`);
    }
    // Air cut, tool use and cost before and after, from the simulations of both paths.
    for (const id of ['air-cut', 'tool-use', 'cost']) {
      const c = cards.find((x) => x.id === id);
      check(c.before !== '–' && c.after !== '–', `the "${id}" card has no figures: ${JSON.stringify(c)}`);
    }
    const job = await page.evaluate(async (id) => (await (await fetch(`/v1/jobs/${id}`)).json()).result, jobId);
    check(job.figures?.before?.kinematic_time_min > 0 && job.figures?.after?.kinematic_time_min > 0, `the result has no figures: ${JSON.stringify(job.figures)}`);
    const alpha = cards.find((c) => c.id === 'max-alpha');
    check(alpha.before.startsWith('180') && /^−/.test(alpha.change), `max α does not drop from 180°: ${JSON.stringify(alpha)}`);
    await shot(page, 'desktop-job-savings');
    // Display units: inch on the page; the API stays in mm.
    await page.selectOption('#units', 'inch');
    await page.waitForFunction(() => / in$/.test(document.querySelector('#savings [data-figure="length"] .after')?.textContent || ''));
    const mm = cards.find((c) => c.id === 'length').after;
    const inch = await page.locator('#savings [data-figure="length"] .after').innerText();
    const value = (t) => Number(t.replace(/[^\d.]/g, ''));
    check(Math.abs(value(inch) * 25.4 - value(mm)) < 0.01 * value(mm), `${mm} is not ${inch}`);
    await page.selectOption('#units', 'mm');
    await page.waitForFunction(() => / mm$/.test(document.querySelector('#savings [data-figure="length"] .after')?.textContent || ''));
  });

  await step('a running job’s time left is estimated from its progress and elapsed time', async () => {
    const texts = await page.evaluate(async () => {
      const { remaining } = await import('/savings.js');
      const start = new Date(Date.now() - 30_000).toISOString();
      return [remaining(0.25, start), remaining(0.5, new Date(Date.now() - 600_000).toISOString()), remaining(0.001, start), remaining(0.5, null)];
    });
    check(texts[0] === 'about 1.5 min left', `25 % after 30 s should leave about 90 s: ${texts[0]}`);
    check(texts[1] === 'about 10 min left', `50 % after 10 min should leave about 10 min: ${texts[1]}`);
    check(texts[2] === null && texts[3] === null, `too little progress or no start gives no estimate: ${texts}`);
  });

  await step('the NC program link downloads G-code', async () => {
    const link = page.locator('#download-program');
    check(await link.count() === 1, 'no "Download NC program" link');
    check((await link.getAttribute('download'))?.endsWith('.nc'), 'the program link has no download attribute');
    const href = await link.getAttribute('href');
    const text = await page.evaluate(async (url) => (await fetch(url)).text(), href);
    check(/\bG0?1\b/.test(text), `the program at ${href} is not G-code: ${text.slice(0, 200)}`);
  });

  await step('the jobs list shows the job', async () => {
    await page.click('nav.main-nav a[data-nav="jobs"]');
    await page.waitForSelector(`#jobs a[href="#/jobs/${jobId}"]`);
    await shot(page, 'desktop-jobs');
  });

  await step('the database tab shows the tools table', async () => {
    await page.click('nav.main-nav a[data-nav="db"]');
    await page.waitForSelector('#database table tbody tr');
    const rows = await page.locator('#database tbody tr').count();
    check(rows >= 10, `only ${rows} tool rows`);
    check((await page.locator('.tabs a[aria-current="page"]').innerText()) === 'Tools', 'the Tools tab is not the current one');
    await shot(page, 'desktop-database');
  });

  await step('edit a tool row: the change is saved and the row becomes the shop’s', async () => {
    await page.locator('#database tbody tr').first().click();
    await page.waitForSelector('dialog.editor[open] #row-price');
    const price = Number(await page.inputValue('#row-price')) + 1;
    await page.fill('#row-price', String(price));
    await shot(page, 'desktop-database-editor');
    await page.click('dialog.editor button[type="submit"]');
    await page.waitForSelector('dialog.editor[open]', { state: 'detached' })
      .catch(async () => { throw new Error(`the editor stayed open: ${await page.locator('dialog.editor').innerText()}`); });
    await page.waitForSelector('#database tbody tr:first-child .source-user');
    const row = await page.evaluate(async () => (await (await fetch('/v1/tools?limit=1')).json()).items[0]);
    check(row.price === price && row.source === 'user' && row.edited === true, `the PATCH did not stick: ${JSON.stringify(row)}`);
  });

  await step('phone layout (390 × 844)', async () => {
    await page.setViewportSize({ width: 390, height: 844 });
    await page.goto(`${BASE}/#/new`);
    await page.waitForSelector('#submit-job');
    await shot(page, 'phone-new-job');
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    check(width <= 390, `the new-job page scrolls sideways on a phone (${width} px wide)`);
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('.figures');
    await page.waitForSelector('#drawing svg path', { state: 'attached', timeout: 30_000 });
    const jobWidth = await page.evaluate(() => document.documentElement.scrollWidth);
    check(jobWidth <= 390, `the job page scrolls sideways on a phone (${jobWidth} px wide)`);
    await shot(page, 'phone-job');
    await page.setViewportSize({ width: 1280, height: 800 });
  });

  await step('the drawing shows the path with its legend', async () => {
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('.drawing-card');
    const links = await page.evaluate(async (id) => (await (await fetch(`/v1/jobs/${id}`)).json()).links, jobId);
    check(links.views, `the job has no views link (links: ${JSON.stringify(links)}): the drawing endpoints are missing`);
    await page.waitForSelector('#drawing svg path', { state: 'attached', timeout: 30_000 });
    check(await page.locator('#drawing svg').isVisible(), 'the drawing SVG is not visible');
    // The legend's elements: class "legend" or "legend-…" (caption, entries, ramp).
    check(await page.locator('#drawing svg [class|="legend"]').count() > 0, 'the drawing has no legend');
    // Zoom in narrows the view box at once, then the drawing is drawn again for the
    // window in view: a larger scale, with its labels and legend at their usual size.
    // The drawing is drawn for the width it is shown at (again, after the phone's).
    await page.waitForFunction(() => {
      const svg = document.querySelector('#drawing svg');
      const shown = svg?.getBoundingClientRect().width || 0;
      return svg && !document.querySelector('#drawing.loading') && Math.abs(svg.viewBox.baseVal.width - shown) < 0.2 * shown;
    });
    const viewBox = () => page.$eval('#drawing svg', (svg) => svg.viewBox.baseVal.width);
    const frame = () => page.$eval('#drawing svg .frame', (f) => ({ scale: Number(f.dataset.scale), windowed: f.dataset.windowed }));
    // The size of the text on the screen, px.
    const fonts = () => page.$$eval('#drawing svg .legend-caption, #drawing svg .subtitle', (t) => t.map((e) => {
      const svg = e.ownerSVGElement;
      return (Number(e.getAttribute('font-size')) * svg.getBoundingClientRect().width / svg.viewBox.baseVal.width).toFixed(1);
    }).join(' '));
    const whole = await viewBox();
    const homeFrame = await frame();
    const fontsBefore = await fonts();
    await page.click('button[aria-label="Zoom in"]');
    check(await viewBox() < whole, 'Zoom in did not zoom');
    await page.waitForSelector('#drawing svg .frame[data-windowed="true"]', { state: 'attached' });
    const zoomed = await frame();
    check(zoomed.scale > 1.4 * homeFrame.scale, `the zoomed drawing is not drawn at a larger scale: ${homeFrame.scale} → ${zoomed.scale}`);
    check(await fonts() === fontsBefore, `the text changed size when zoomed: ${fontsBefore} → ${await fonts()}`);
    check(Math.abs((await viewBox()) - whole) < 1e-6 * whole, 'the zoomed drawing is not shown whole');
    // The hover read-out gives the position (and what is under the pointer).
    const box = await page.locator('#drawing svg').boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 3);
    check(/^X -?[\d.,]+ {2}Y -?[\d.,]+( {2}Z -?[\d.,]+)? mm/.test(await page.locator('#drawing-readout').innerText()), `no read-out: ${await page.locator('#drawing-readout').innerText()}`);
    await shot(page, 'desktop-drawing-zoomed');
    await page.click('button:has-text("Fit")');
    await page.waitForSelector('#drawing svg .frame[data-windowed="false"]', { state: 'attached' });
    check(Math.abs((await frame()).scale - homeFrame.scale) < 1e-6 * homeFrame.scale, 'Fit did not show the whole drawing again');
    // A trochoids job has the base path (before) and the planned one: the before-and-after
    // strip shows both, and choosing the other path redraws the drawing with it.
    check(await page.locator('.compare img').count() === 2, 'no before-and-after strip');
    check(await page.locator('#draw-path').count() === 1, 'no path choice for a job with two paths');
    const subtitle = () => page.evaluate(() => document.querySelector('#drawing svg .subtitle')?.textContent || '');
    const before = await subtitle();
    const other = await page.$eval('#draw-path', (s) => [...s.options].find((o) => !o.selected)?.value);
    await page.selectOption('#draw-path', other);
    await page.waitForFunction((t) => (document.querySelector('#drawing svg .subtitle')?.textContent || '') !== t, before);
    check((await subtitle()).startsWith(other), `the drawing is not of the ${other} path: ${await subtitle()}`);
    check(await page.locator('#drawing svg path').count() > 0, `the ${other} path draws nothing`);
  });

  await step('a feeds job: its before-and-after strip is coloured by feed on one scale, and it shows what it saves', async () => {
    const made = await page.evaluate(async () => {
      const examples = (await (await fetch('/v1/examples')).json()).items;
      const feeds = examples.find((e) => e.kind === 'feeds');
      const r = await fetch('/v1/jobs', { method: 'POST', headers: { 'content-type': 'application/json', prefer: 'wait=60' },
        body: JSON.stringify({ kind: 'feeds', input: feeds.input }) });
      return r.json();
    });
    check(made.status === 'succeeded', `the feeds example ended ${made.status}`);
    feedsJobId = made.id;
    await page.goto(`${BASE}/#/jobs/${feedsJobId}`);
    await page.waitForSelector('#savings .saving');
    await page.waitForSelector('.compare img');
    check(await page.$eval('.compare', (e) => e.dataset.color) === 'feed', 'the feeds strip is not coloured by feed');
    const srcs = await page.$$eval('.compare img', (imgs) => imgs.map((i) => i.getAttribute('src')));
    check(srcs.every((src) => src.includes('color=feed')), `the strip's drawings are not coloured by feed: ${srcs}`);
    // The two drawings differ (the feeds changed) and share the legend's range.
    const svgs = await page.evaluate(async (list) => Promise.all(list.map(async (u) => (await fetch(u)).text())), srcs);
    check(svgs[0] !== svgs[1], 'the before and after drawings are identical');
    const range = (svg) => [...svg.matchAll(/<text[^>]*class="legend-(min|max)"[^>]*>([^<]+)</g)].map((m) => m[2]).join(' – ');
    check(range(svgs[0]) && range(svgs[0]) === range(svgs[1]), `the two legends differ: ${range(svgs[0])} vs ${range(svgs[1])}`);
    check(svgs[0].includes('data-quantity="feed"') && svgs[0].includes('#'), 'no feed legend');
    const ids = await page.$$eval('#savings .saving', (els) => els.map((e) => e.dataset.figure));
    for (const id of ['nominal-time', 'kinematic-time', 'length', 'air-cut', 'tool-use', 'cost']) {
      check(ids.includes(id), `the feeds job has no "${id}" card: ${ids}`);
    }
    // The changed lines, before and after.
    await page.selectOption('#program-part', 'diff');
    await page.waitForSelector('#program .nc-diff');
    const diff = await page.$$eval('#program .nc-diff', (rows) => rows.slice(0, 3).map((r) => r.innerText));
    check(diff.length > 0 && diff.every((t) => /F/.test(t)), `the changed lines show no feeds: ${diff}`);
    await shot(page, 'desktop-feeds-job');
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('#drawing svg path', { state: 'attached', timeout: 30_000 });
  });

  await step('the program view: the NC text with line numbers, the base program, and links both ways with the drawing', async () => {
    await page.waitForSelector('#program .nc-row');
    const options = await page.$$eval('#program-part option', (o) => o.map((x) => x.value));
    check(options.includes('main') && options.includes('base'), `a trochoids job shows its program and its base program: ${options}`);
    const first = await page.$eval('#program .nc-row', (r) => ({ line: r.dataset.line, ln: r.querySelector('.nc-ln').textContent }));
    check(first.line === '1' && first.ln === '1', `the first row is not line 1: ${JSON.stringify(first)}`);
    // The base program is downloadable and is G-code.
    const base = page.locator('#download-base');
    check(await base.count() === 1, 'no download of the base program');
    const text = await page.evaluate(async (url) => (await fetch(url)).text(), await base.getAttribute('href'));
    check(/\bG0?1\b/.test(text), `the base program is not G-code: ${text.slice(0, 200)}`);
    // An overload's NC lines in the table lead to them in the program.
    const link = page.locator('button.line-link[data-part="main"]').first();
    check(await link.count() === 1, 'the overloads table has no links to NC lines');
    const from = await link.getAttribute('data-from');
    await link.click();
    await page.waitForSelector(`#program .nc-row.selected[data-line="${from}"]`);
    check((await page.locator('#program .nc-status').innerText()).includes(from), 'the status does not name the selected line');
    // A critical region of the base path in the drawing leads to its lines of the base program.
    await page.selectOption('#draw-path', 'base');
    await page.waitForFunction(() => (document.querySelector('#drawing svg .subtitle')?.textContent || '').startsWith('base'));
    const label = page.locator('#drawing svg .region-label').first();
    const lines = (await label.getAttribute('data-lines')).split('-');
    await label.click();
    await page.waitForFunction(() => document.querySelector('#program-part').value === 'base');
    await page.waitForSelector(`#program .nc-row.selected[data-line="${lines[0]}"]`);
    // Selected lines mark the regions on them.
    check(await page.locator('#drawing svg .region-label.linked').count() > 0, 'the region of the selected lines is not marked');
    await shot(page, 'desktop-job-program');
  });

  await step('the program view stays small and quick for a program of 200 000 lines', async () => {
    const made = await page.evaluate(async () => {
      const { virtualList } = await import('/program-view.js');
      const n = 200_000;
      const list = virtualList(n, (i) => { const d = document.createElement('div'); d.className = 'nc-row'; d.dataset.line = String(i + 1); d.textContent = `N${i + 1} G1 X${i} Y0 F1000`; return d; }, { label: 'test' });
      document.body.append(list.node);
      const t0 = performance.now();
      list.draw(true);
      list.reveal(149_999);
      const ms = performance.now() - t0;
      const rows = list.node.querySelectorAll('.nc-row').length;
      const shown = Boolean(list.node.querySelector('[data-line="150000"]'));
      const height = list.node.scrollHeight;
      list.node.remove();
      return { ms, rows, shown, height };
    });
    check(made.shown, 'line 150000 is not shown after revealing it');
    check(made.rows < 100, `${made.rows} rows in the DOM for 200 000 lines`);
    check(made.height >= 200_000 * 20, `the list is not as tall as its lines: ${made.height}`);
    check(made.ms < 100, `revealing a line took ${made.ms} ms`);
  });

  await step('the charts are drawn', async () => {
    const views = await page.evaluate(async (id) => (await (await fetch(`/v1/jobs/${id}/views`)).json()), jobId);
    check(views.charts.length > 0, 'a trochoids job has an α chart');
    await page.waitForFunction((n) => document.querySelectorAll('.chart svg').length === n, views.charts.length, { timeout: 30_000 });
    await shot(page, 'desktop-job');
  });

  await linkSteps({ page, step, check, shot, BASE, jobId });
  await drawingSteps({ page, step, check, shot, BASE, jobId });
  await labelSteps({ page, step, check, shot, BASE, consoleErrors });
  await uploadSteps({ page, step, check, shot, BASE, consoleErrors });

  await view3dSteps({ page, step, check, shot, BASE });

  await step('once the service has keys, the page asks for one and keeps it', async () => {
    const made = await page.evaluate(async () => {
      const r = await fetch('/v1/keys', { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ role: 'admin', name: 'browser test' }) });
      return r.json();
    });
    check(String(made.key || '').startsWith('dpk_'), `no key made: ${JSON.stringify(made)}`);
    const errorsBefore = consoleErrors.length;
    await page.goto(`${BASE}/#/jobs`);
    await page.waitForSelector('dialog.key-dialog[open]');
    await shot(page, 'desktop-key');
    await page.fill('#api-key-input', made.key);
    await page.click('dialog.key-dialog button[type="submit"]');
    await page.waitForSelector(`#jobs a[href="#/jobs/${jobId}"]`);
    check(await page.evaluate(() => localStorage.getItem('dieplan.apiKey')) === made.key, 'the key is not kept');
    // The browser logs the 401 that made the page ask: expected, not an error of the page.
    consoleErrors.splice(errorsBefore, consoleErrors.length - errorsBefore,
      ...consoleErrors.slice(errorsBefore).filter((e) => !e.includes('401')));
    await page.reload();
    await page.waitForSelector(`#jobs a[href="#/jobs/${jobId}"]`);
    check(await page.locator('dialog.key-dialog').count() === 0, 'the page asked again for a kept key');
  });

  check(consoleErrors.length === 0, `console errors:\n  ${consoleErrors.join('\n  ')}`);
  console.log('ok: no console errors');
} catch (err) {
  failed = true;
  console.error(`FAILED at "${current}": ${err.message}`);
  if (consoleErrors.length) console.error(`console errors:\n  ${consoleErrors.join('\n  ')}`);
  try {
    const page = context.pages()[0];
    if (page) await shot(page, 'failure');
  } catch { /* the browser is gone */ }
} finally {
  await context.close();
  rmSync(profile, { recursive: true, force: true });
}
console.log(`screenshots:\n  ${shots.join('\n  ')}`);
process.exit(failed ? 1 : 0);
