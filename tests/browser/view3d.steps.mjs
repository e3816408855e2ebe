// The 3-D view (issue 32 item 5), driven by page.test.mjs: a finished analysis job's stock
// and path drawn with WebGL (headless chromium draws it with SwiftShader, see ARGS there),
// the time slider moving the tool, the quantity switched, inches in the read-out; desktop
// and phone screenshots.

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
    const colours = new Set();
    for (let k = 0; k < data.length; k += 4) {
      if (Math.abs(data[k] - r0) + Math.abs(data[k + 1] - g0) + Math.abs(data[k + 2] - b0) > 12) differ++;
      if (k % 64 === 0) colours.add((data[k] >> 4) * 256 + (data[k + 1] >> 4) * 16 + (data[k + 2] >> 4));
    }
    return { share: differ / (data.length / 4), colours: colours.size, width: canvas.width, height: canvas.height };
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

  await step('the time slider moves the tool along the path, and play runs it', async () => {
    const at = () => page.$eval('#view3d', (c) => ({ tool: c.dataset.tool, vertex: Number(c.dataset.vertex) }));
    const end = await at();
    const slider = page.locator('#time3d');
    const max = Number(await slider.getAttribute('max'));
    check(max > 3 && end.vertex === max, `the path is not shown whole at first: ${JSON.stringify(end)} of ${max}`);
    // (A range input is set as a user's drag sets it: its value, then an input event.)
    await slider.evaluate((input, value) => { input.value = String(value); input.dispatchEvent(new Event('input', { bubbles: true })); }, Math.round(max / 3));
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
}
