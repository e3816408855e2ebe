// The 3-D view (issue 32 item 5), driven by page.test.mjs: a finished analysis job's stock
// and path drawn with WebGL (headless chromium draws it with SwiftShader, see ARGS there),
// the time slider moving the tool, the quantity switched, inches in the read-out; desktop
// and phone screenshots. Then a path of more cutting levels than are offered one by one,
// shown down to a depth, and the tool drawn in its shape (flat, ball).

/** Passes of the many-levels program, each its own cutting level. */
const MANY_LEVELS = 450;
/** The depth of each of its passes, mm. */
const PASS_DEPTH_MM = 0.01;

/** A slot cut in MANY_LEVELS passes of PASS_DEPTH_MM, to and fro along x, as G-code. */
function manyLevelsProgram() {
  const lines = ['G21 G90 G17', 'G0 Z5', 'G0 X5 Y20', 'S4800 M3', 'G1 Z0 F600'];
  for (let k = 1; k <= MANY_LEVELS; k++) lines.push(`G1 Z${(-k * PASS_DEPTH_MM).toFixed(3)} F600`, `G1 X${k % 2 ? 55 : 5} F2000`);
  return [...lines, 'G0 Z5', 'M30'].join('\n');
}

/** Sets a range input as a user's drag sets it: its value, then an input event. */
async function slide(locator, value) {
  await locator.evaluate((input, v) => { input.value = String(v); input.dispatchEvent(new Event('input', { bubbles: true })); }, value);
}

/** The 3-D view's data for tests: what it draws and the tool (shape, `[height, radius]` near its tip). */
async function drawn(page) {
  return page.$eval('#view3d', (c) => ({ levels: Number(c.dataset.levels), drawn: Number(c.dataset.drawn), depth: c.dataset.depth,
    shape: c.dataset.toolShape, profile: JSON.parse(c.dataset.toolProfile || '[]') }));
}

/** The share of the 3-D canvas's pixels that differ from its background, and their colours. */
async function canvasPixels(page) {
  return page.$eval('#view3d canvas', (canvas) => {
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(canvas, 0, 0);
    const data = ctx.getImageData(0, 0, copy.width, copy.height).data;
    const [r0, g0, b0] = data;
    let differ = 0;
    let digest = 2166136261;
    const colours = new Set();
    for (let k = 0; k < data.length; k += 4) {
      if (Math.abs(data[k] - r0) + Math.abs(data[k + 1] - g0) + Math.abs(data[k + 2] - b0) > 12) differ++;
      if (k % 64 === 0) colours.add((data[k] >> 4) * 256 + (data[k + 1] >> 4) * 16 + (data[k + 2] >> 4));
      digest = Math.imul(digest ^ (data[k] | (data[k + 1] << 8) | (data[k + 2] << 16)), 16777619) >>> 0;
    }
    return { share: differ / (data.length / 4), colours: colours.size, digest, width: canvas.width, height: canvas.height };
  });
}

export async function view3dSteps({ page, step, check, shot, BASE }) {
  let id;
  await step('a finished analysis job opens in 3-D: its stock and its path drawn with WebGL', async () => {
    id = await page.evaluate(async () => {
      const examples = (await (await fetch('/v1/examples')).json()).items;
      const slot = examples.find((e) => e.id === 'slot-analysis');
      const answer = await fetch('/v1/analysis', { method: 'POST', headers: { 'content-type': 'application/json', prefer: 'wait=60' }, body: JSON.stringify(slot.input) });
      const job = await answer.json();
      if (job.status !== 'succeeded') throw new Error(`the analysis is ${job.status}`);
      return job.id;
    });
    await page.goto(`${BASE}/#/jobs/${id}`);
    await page.click('#open-3d');
    await page.waitForSelector('#view3d[data-stock] canvas', { timeout: 30_000 });
    await page.waitForFunction(() => document.querySelector('#view3d')?.dataset.tool, null, { timeout: 30_000 });
    const stock = await page.$eval('#view3d', (c) => c.dataset.stock);
    check(/^\d+x\d+$/.test(stock), `the analysis job's stock was not drawn: ${stock}`);
    const webgl = await page.evaluate(() => Boolean(document.createElement('canvas').getContext('webgl2')));
    check(webgl, 'chromium has no WebGL');
    const pixels = await canvasPixels(page);
    check(pixels.share > 0.05 && pixels.colours > 8, `the 3-D canvas is (nearly) blank: ${JSON.stringify(pixels)}`);
    check(await page.locator('#legend3d .legend3d-ramp span').count() === 32, 'the legend has not the 32 colours of the drawing');
    const caption = await page.locator('#legend3d').innerText();
    check(/engagement α/.test(caption) && /limit/.test(caption), `the legend is not α's with its limit: ${caption}`);
    await page.locator('#view3d-card').scrollIntoViewIfNeeded();
    await shot(page, 'desktop-3d');
  });

  await step('the analysis\'s square end mill is drawn flat at its tip; a path of few levels keeps no depth slider', async () => {
    const view = await drawn(page);
    check(view.shape === 'square', `the tool is not the square end mill the result names: ${JSON.stringify(view)}`);
    check(view.profile.length > 0 && view.profile.every(([, radius]) => Math.abs(radius - 5) < 1e-3), `the 10 mm square end mill is not flat at its tip: ${JSON.stringify(view.profile)}`);
    check(view.levels <= 400 && await page.locator('#depth3d').count() === 0, `a path of ${view.levels} levels got a depth slider`);
  });

  await step('the time slider moves the tool along the path, and play runs it', async () => {
    const at = () => page.$eval('#view3d', (c) => ({ tool: c.dataset.tool, vertex: Number(c.dataset.vertex) }));
    const end = await at();
    const slider = page.locator('#time3d');
    const max = Number(await slider.getAttribute('max'));
    check(max > 3 && end.vertex === max, `the path is not shown whole at first: ${JSON.stringify(end)} of ${max}`);
    await slide(slider, Math.round(max / 3));
    const third = await at();
    check(third.vertex === Math.round(max / 3) && third.tool !== end.tool, `the tool did not move: ${JSON.stringify([end, third])}`);
    const readout = await page.locator('#view3d-readout').innerText();
    check(/^Tool at X .* mm/.test(readout), `the read-out does not give the tool's position: ${readout}`);
    const partial = await canvasPixels(page);
    check(partial.share > 0.05, 'the canvas went blank');
    await page.click('#play3d');
    await page.waitForFunction((v) => Number(document.querySelector('#view3d').dataset.vertex) > v, third.vertex, { timeout: 10_000 });
    await page.click('#play3d');
    check(await page.locator('#play3d').innerText() === 'Play', 'pause did not stop it');
  });

  await step('switching the quantity recolours the path with its own legend; inches in the read-out', async () => {
    const options = await page.$$eval('#color3d option', (o) => o.map((e) => e.value));
    check(options.includes('feed') && options.includes('force'), `the 3-D view cannot colour by feed and force: ${options}`);
    const before = await canvasPixels(page);
    await page.selectOption('#color3d', 'force');
    await page.waitForSelector('#legend3d[data-quantity="force"]');
    const caption = await page.locator('#legend3d').innerText();
    check(/force/.test(caption) && !/limit/.test(caption), `the legend is not the force's: ${caption}`);
    const after = await canvasPixels(page);
    check(after.share > 0.05, `the canvas is blank coloured by force: ${JSON.stringify([before, after])}`);
    await page.selectOption('#units', 'inch');
    await page.waitForFunction(() => / in\b/.test(document.querySelector('#view3d-readout')?.textContent || ''), null, { timeout: 30_000 });
    await page.selectOption('#units', 'mm');
    await page.waitForFunction(() => / mm\b/.test(document.querySelector('#view3d-readout')?.textContent || ''), null, { timeout: 30_000 });
  });

  await step('the 3-D view on a phone (390 × 844)', async () => {
    await page.setViewportSize({ width: 390, height: 844 });
    await page.waitForFunction(() => {
      const c = document.querySelector('#view3d canvas');
      return c && c.getBoundingClientRect().width <= 390;
    });
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    check(width <= 390, `the 3-D view scrolls sideways on a phone (${width} px wide)`);
    await page.locator('#view3d-card').scrollIntoViewIfNeeded();
    await shot(page, 'phone-3d');
    await page.setViewportSize({ width: 1280, height: 800 });
  });

  await step('a path of more than 400 cutting levels gets a depth slider, and moving it hides the deeper path', async () => {
    id = await page.evaluate(async (gcode) => {
      const request = { program: { gcode }, tool_type: 'ball', diameter_mm: 10,
        stock: { box: { x_min: 0, y_min: 0, z_min: -5, x_max: 60, y_max: 40, z_max: 0 } } };
      const answer = await fetch('/v1/analysis', { method: 'POST', headers: { 'content-type': 'application/json', prefer: 'wait=60' }, body: JSON.stringify(request) });
      const job = await answer.json();
      if (job.status !== 'succeeded') throw new Error(`the analysis is ${job.status}: ${JSON.stringify(job.error)}`);
      return job.id;
    }, manyLevelsProgram());
    await page.goto(`${BASE}/#/jobs/${id}`);
    await page.click('#open-3d');
    await page.waitForFunction(() => document.querySelector('#view3d')?.dataset.tool, null, { timeout: 30_000 });
    const whole = await drawn(page);
    check(whole.levels > 400 && whole.levels <= MANY_LEVELS + 2, `the path has not its ${MANY_LEVELS} levels: ${JSON.stringify(whole)}`);
    check(await page.locator('#layer3d').count() === 0, 'a path of many levels is offered one level at a time');
    const depth = page.locator('#depth3d');
    check(await depth.count() === 1, 'the path of many levels has no depth slider');
    check(/^all \d+ levels, down to z -4\.5 mm$/.test(await page.locator('#depth3d-label').innerText()), `the depth slider does not start at the whole path: ${await page.locator('#depth3d-label').innerText()}`);
    const before = await canvasPixels(page);
    await slide(depth, Number(await depth.getAttribute('max')) / 2);
    await page.waitForFunction((d) => document.querySelector('#view3d').dataset.depth !== d, whole.depth);
    const half = await drawn(page);
    const label = await page.locator('#depth3d-label').innerText();
    check(/^down to z -?[\d.]+ mm \(level \d+ of \d+\)$/.test(label), `the depth read-out is not a z in mm and a level: ${label}`);
    // What the page draws is the trace's vertices down to the chosen level, no deeper.
    const expected = await page.evaluate(async ([job, level]) => {
      const trace = await (await fetch(`/v1/jobs/${job}/trace`)).json();
      return trace.runs.flatMap((run) => run.z).filter((z) => z != null && z > level - 1e-3).length;
    }, [id, Number(half.depth)]);
    check(half.drawn === expected && half.drawn < whole.drawn && Number(half.depth) > -3.5 && Number(half.depth) < -1,
      `halfway down, the view draws ${half.drawn} of ${whole.drawn} vertices down to z ${half.depth}, not the trace's ${expected}`);
    const time = Number(await page.locator('#time3d').getAttribute('max'));
    check(time === half.drawn - 1, `the time slider does not play the path shown: ${time} of ${half.drawn}`);
    const after = await canvasPixels(page);
    // (The deeper path lies over the slot's floor: hiding it changes pixels, not how many
    // differ from the background.)
    check(after.share > 0.05 && after.digest !== before.digest, `hiding the deeper path changed nothing on the canvas: ${JSON.stringify([before, after])}`);
    await depth.focus();
    await page.keyboard.press('ArrowRight');
    await page.waitForFunction((d) => document.querySelector('#view3d').dataset.depth !== d, half.depth);
    const deeper = await drawn(page);
    check(Math.abs(Number(half.depth) - Number(deeper.depth) - 0.01) < 1e-6, `a key does not step to the next level down: ${half.depth} → ${deeper.depth}`);
    await page.locator('#view3d-card').scrollIntoViewIfNeeded();
    await shot(page, 'desktop-3d-depth');
    await page.selectOption('#units', 'inch');
    await page.waitForFunction(() => / in$/.test(document.querySelector('#depth3d-label')?.textContent || ''), null, { timeout: 30_000 });
    await page.selectOption('#units', 'mm');
    await page.waitForFunction(() => / mm$/.test(document.querySelector('#depth3d-label')?.textContent || ''), null, { timeout: 30_000 });
  });

  await step('a ball end mill job\'s tool is drawn round at its tip', async () => {
    const view = await drawn(page);
    check(view.shape === 'ball', `the tool is not the ball end mill the result names: ${JSON.stringify(view)}`);
    const radius = (height) => view.profile.find(([h]) => Math.abs(h - height) < 1e-9)?.[1];
    // A ball of R5: a point at its tip, under √(5² − 4.5²) = 2.18 mm half a millimetre up, its full radius at R.
    check(radius(0) < 1e-3 && radius(0.5) > 1 && radius(0.5) <= 2.18 && Math.abs(radius(5) - 5) < 1e-3,
      `the ball end mill is not round at its tip: ${JSON.stringify(view.profile)}`);
    await slide(page.locator('#time3d'), Math.round(Number(await page.locator('#time3d').getAttribute('max')) / 2));
    await page.locator('#view3d-card').scrollIntoViewIfNeeded();
    await shot(page, 'desktop-3d-ball-end-mill');
  });
}
