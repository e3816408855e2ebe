// The page as a CAM engineer's workbench (issue 33), driven by page.test.mjs: the drawing
// in inches, a deep zoom, a program file sent as a multipart upload, and a job renamed
// and retagged; desktop and phone screenshots.

/** The drawing's frame in mm, and its text's size on the screen, px (once it is drawn). */
async function frameOf(page) {
  await page.waitForSelector('#drawing svg .frame', { state: 'attached', timeout: 30_000 });
  await page.waitForFunction(() => !document.querySelector('#drawing.loading'));
  return page.$eval('#drawing svg', (svg) => {
    const f = svg.querySelector('.frame');
    const n = (k) => Number(f.getAttribute(`data-${k}`));
    const px = svg.getBoundingClientRect().width / svg.viewBox.baseVal.width;
    const fonts = [...svg.querySelectorAll('.legend-caption, .subtitle, .axis-label')].map((t) => (Number(t.getAttribute('font-size')) * px).toFixed(1));
    return { width: n('x-max') - n('x-min'), windowed: f.dataset.windowed, fonts: [...new Set(fonts)].sort().join(' ') };
  });
}

/** On the trochoids job's page: its drawing in inches, then zoomed in as far as it goes. */
export async function drawingSteps({ page, step, check, shot, BASE, jobId }) {
  await step('in inches, the drawing’s frame, scale bar and labels read in inches (the API stays in mm)', async () => {
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('#drawing svg .frame-axes', { state: 'attached', timeout: 30_000 });
    check(await page.$eval('#drawing svg .frame-axes', (g) => g.dataset.unit) === 'mm', 'the frame is not in mm at first');
    await page.selectOption('#units', 'inch');
    await page.waitForSelector('#drawing svg .frame-axes[data-unit="in"]', { state: 'attached', timeout: 30_000 });
    const bar = await page.$eval('#drawing svg .scale-bar', (g) => ({ unit: g.dataset.unit, mm: Number(g.dataset.lengthMm), length: Number(g.dataset.length), text: g.textContent.trim() }));
    check(bar.unit === 'in' && / in$/.test(bar.text), `the scale bar is not in inches: ${JSON.stringify(bar)}`);
    check(Math.abs(bar.length * 25.4 - bar.mm) < 1e-6 * bar.mm, `the scale bar's inches are not its mm: ${JSON.stringify(bar)}`);
    const labels = await page.$$eval('#drawing svg .axis-x .axis-label', (t) => t.map((e) => e.textContent));
    check(labels.length >= 2 && labels.filter((t) => / in$/.test(t)).length === 1, `the frame's x labels do not name inches once: ${labels}`);
    // The frame keeps mm (what the page maps with), and the API's drawing without units too.
    const mm = await page.evaluate(async (id) => (await fetch(`/v1/jobs/${id}/drawing.svg`)).text(), jobId);
    check(mm.includes('data-unit="mm"') && / mm<\/text>/.test(mm), 'the drawing without units is not in mm');
    const subtitle = await page.$eval('#drawing svg .subtitle', (t) => t.textContent);
    check(!/ mm\b/.test(subtitle), `the subtitle shows mm: ${subtitle}`);
    await shot(page, 'desktop-drawing-inch');
    await page.setViewportSize({ width: 390, height: 844 });
    await page.waitForSelector('#drawing svg .frame-axes[data-unit="in"]', { state: 'attached' });
    await page.locator('#drawing').scrollIntoViewIfNeeded();
    await shot(page, 'phone-drawing-inch');
    await page.setViewportSize({ width: 1280, height: 800 });
    await page.selectOption('#units', 'mm');
    await page.waitForSelector('#drawing svg .frame-axes[data-unit="mm"]', { state: 'attached', timeout: 30_000 });
  });

  await step('zoom goes deeper than 1/2000 of the drawing, to the detail its data keeps, with the text at its size', async () => {
    // The page as it is after the units changed back: drawn anew, whole.
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.reload();
    await page.waitForSelector('#drawing svg .frame[data-windowed="false"]', { state: 'attached', timeout: 30_000 });
    const whole = await frameOf(page);
    const views = await page.evaluate(async (id) => (await fetch(`/v1/jobs/${id}/views`)).json(), jobId);
    check(views.detail_mm > 0 && views.detail_mm < whole.width / 2000, `the views give no detail finer than 1/2000: ${views.detail_mm} of ${whole.width} mm`);
    let last = whole;
    for (let i = 0; i < 40; i++) {
      for (let k = 0; k < 4; k++) await page.click('button[aria-label="Zoom in"]');
      await page.waitForSelector('#drawing svg .frame[data-windowed="true"]', { state: 'attached', timeout: 30_000 });
      await page.waitForFunction((w) => {
        const f = document.querySelector('#drawing svg .frame');
        return !document.querySelector('#drawing.loading') && f && Number(f.dataset.xMax) - Number(f.dataset.xMin) < w * 0.999;
      }, last.width, { timeout: 5_000 }).catch(() => {});
      const now = await frameOf(page);
      if (now.width >= last.width * 0.999) break;
      last = now;
    }
    check(last.width < whole.width / 2000, `the zoom stopped at ${last.width} mm of ${whole.width} mm`);
    check(last.width >= 4 * views.detail_mm * 0.99, `the zoom went past the data's detail: ${last.width} mm for ${views.detail_mm} mm`);
    check(last.fonts === whole.fonts, `the text changed size when zoomed: ${whole.fonts} → ${last.fonts}`);
    const ticks = await page.$$eval('#drawing svg .axis-label', (t) => t.length);
    check(ticks >= 2, 'the deep view has no coordinates on its frame');
    await shot(page, 'desktop-drawing-deep-zoom');
    await page.click('button:has-text("Fit")');
    await page.waitForSelector('#drawing svg .frame[data-windowed="false"]', { state: 'attached' });
  });
}

/** A program file sent as a multipart upload from the form, and a job renamed and retagged. */
export async function uploadSteps({ page, step, check, shot, BASE, consoleErrors }) {
  let jobId;
  await step('a program file is sent as a multipart upload (program and request parts)', async () => {
    await page.goto(`${BASE}/#/new`);
    await page.waitForSelector('#submit-job');
    await page.check('input[name="kind"][value="analysis"]', { force: true });
    await page.check('input[name="source"][value="file"]', { force: true });
    const gcode = 'G21 G90 G17\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\nG1 X50 F2000\nG0 Z5\nM30\n';
    await page.setInputFiles('#file', { name: 'slot.nc', mimeType: 'text/plain', buffer: Buffer.from(gcode) });
    await page.waitForSelector('.file-preview');
    check(await page.locator('#source-text').count() === 0, 'an uploaded file is still pasted into the form');
    check((await page.locator('.endpoint').textContent()).includes('multipart/form-data'), 'the request line does not say multipart');
    const json = JSON.parse(await page.inputValue('#json-input'));
    check(!json.program?.gcode, `the request part holds the program: ${JSON.stringify(json).slice(0, 200)}`);
    await page.fill('#box-x_min', '0');
    await page.fill('#box-x_max', '100');
    await page.fill('#box-y_min', '0');
    await page.fill('#box-y_max', '40');
    await page.fill('#box-z_min', '-10');
    await page.fill('#box-z_max', '0');
    await shot(page, 'desktop-upload');
    const sent = page.waitForRequest((r) => r.method() === 'POST' && r.url().endsWith('/v1/analysis'));
    await page.click('#submit-job');
    const request = await sent;
    const type = request.headers()['content-type'] || '';
    check(type.startsWith('multipart/form-data; boundary='), `the upload was sent as ${type}`);
    // The body as the browser sent it (when the browser hands it over: a file part may be
    // left out of it); the job's input below shows the service read both parts.
    const body = request.postDataBuffer()?.toString() || '';
    if (body) check(/name="program"; filename="slot.nc"/.test(body) && /name="request"/.test(body), `the parts are not program and request: ${body.slice(0, 300)}`);
    await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
    jobId = page.url().split('/').pop();
    await page.waitForSelector('.badge-succeeded, .badge-failed', { timeout: 60_000 });
    const input = await page.evaluate(async (id) => (await fetch(`/v1/jobs/${id}/input`)).json(), jobId);
    check(input.program?.gcode === gcode, 'the job did not read the file as its program');
    check(input.stock?.box?.x_max === 100 && input.tool_id > 0, `the job did not read the request part: ${JSON.stringify(input).slice(0, 300)}`);
    await page.setViewportSize({ width: 390, height: 844 });
    await page.goto(`${BASE}/#/new`);
    await page.waitForSelector('#submit-job');
    await page.check('input[name="kind"][value="analysis"]', { force: true });
    await page.check('input[name="source"][value="file"]', { force: true });
    await page.setInputFiles('#file', { name: 'slot.nc', mimeType: 'text/plain', buffer: Buffer.from(gcode) });
    await page.waitForSelector('.file-preview');
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    check(width <= 390, `the upload form scrolls sideways on a phone (${width} px wide)`);
    await shot(page, 'phone-upload');
    await page.setViewportSize({ width: 1280, height: 800 });
  });

  await step('a job is renamed and retagged on its page; a bad tag is refused at its field', async () => {
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('#edit-labels');
    await page.click('#edit-labels');
    await page.fill('#label-name', 'Slot, checked');
    await page.fill('#label-tags', 'die:4711 bad#tag');
    const errorsBefore = consoleErrors.length;
    await page.click('#save-labels');
    await page.waitForSelector('#label-tags[aria-invalid="true"]');
    // The browser logs the 422 the editor showed: expected, not an error of the page.
    consoleErrors.splice(errorsBefore, consoleErrors.length - errorsBefore,
      ...consoleErrors.slice(errorsBefore).filter((e) => !e.includes('422')));
    const reason = await page.locator('#label-tags').locator('xpath=..').locator('.field-error').innerText();
    check(/letters, digits/.test(reason), `the tag's fault does not say what a tag may hold: ${reason}`);
    check((await page.evaluate(async (id) => (await fetch(`/v1/jobs/${id}`)).json(), jobId)).name === null, 'a refused patch changed the job');
    await shot(page, 'desktop-relabel-refused');
    await page.fill('#label-tags', 'die:4711, checked');
    await page.click('#save-labels');
    await page.waitForFunction(() => document.querySelector('.job-head h1')?.textContent === 'Slot, checked');
    const tags = await page.$$eval('.job-head .tags .tag', (t) => t.map((e) => e.textContent));
    check(tags.join(' ') === 'die:4711 checked', `the job shows tags ${tags}`);
    const job = await page.evaluate(async (id) => (await fetch(`/v1/jobs/${id}`)).json(), jobId);
    check(job.name === 'Slot, checked' && job.tags.join(' ') === 'die:4711 checked', `the job was not relabelled: ${job.name} ${job.tags}`);
    await shot(page, 'desktop-relabelled');
    await page.setViewportSize({ width: 390, height: 844 });
    await page.click('#edit-labels');
    await page.waitForSelector('#labels-editor');
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    check(width <= 390, `the editor scrolls sideways on a phone (${width} px wide)`);
    await shot(page, 'phone-relabel');
    await page.setViewportSize({ width: 1280, height: 800 });
  });
  return jobId;
}
