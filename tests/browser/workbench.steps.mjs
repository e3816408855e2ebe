// The page as a CAM engineer's workbench (issue 33), driven by page.test.mjs: jobs with a
// name and tags, searched and filtered in the list; desktop and phone screenshots.

/** A job submitted from the form with a name and tags, found again by them in the list. */
export async function labelSteps({ page, step, check, shot, BASE, consoleErrors }) {
  let namedId;
  await step('a job gets a name and tags on submit, and shows them', async () => {
    await page.goto(`${BASE}/#/new`);
    await page.waitForSelector('#submit-job');
    await page.check('input[name="kind"][value="analysis"]', { force: true });
    await page.check('input[name="source"][value="example"]', { force: true });
    await page.fill('#job-name', 'Die 4711 — cavity A analysis');
    await page.fill('#job-tags', 'die:4711, analysis  cavity-A');
    const json = JSON.parse(await page.inputValue('#json-input'));
    check(json.name === 'Die 4711 — cavity A analysis' && JSON.stringify(json.tags) === '["die:4711","analysis","cavity-A"]',
      `the request has no name and tags: ${JSON.stringify({ name: json.name, tags: json.tags })}`);
    await page.click('#submit-job');
    await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
    namedId = page.url().split('/').pop();
    await page.waitForSelector('.job-head h1');
    check((await page.locator('.job-head h1').innerText()) === 'Die 4711 — cavity A analysis', 'the job page is not headed by its name');
    const tags = await page.$$eval('.job-head .tags .tag', (t) => t.map((e) => e.textContent));
    check(tags.join(' ') === 'die:4711 analysis cavity-A', `the job page shows tags ${tags}`);
    await page.waitForSelector('.badge-succeeded, .badge-failed', { timeout: 60_000 });
  });

  await step('a bad tag is refused at its field, with the other faults of the form', async () => {
    await page.goto(`${BASE}/#/new`);
    await page.waitForSelector('#submit-job');
    await page.check('input[name="kind"][value="analysis"]', { force: true });
    await page.fill('#job-tags', 'good bad#tag');
    const errorsBefore = consoleErrors.length;
    await page.click('#submit-job');
    await page.waitForSelector('#job-tags[aria-invalid="true"]');
    const reason = await page.locator('#job-tags').locator('xpath=..').locator('.field-error').innerText();
    check(/letters, digits/.test(reason), `the tag's fault does not say what a tag may hold: ${reason}`);
    // The browser logs the 422 the form showed: expected, not an error of the page.
    consoleErrors.splice(errorsBefore, consoleErrors.length - errorsBefore,
      ...consoleErrors.slice(errorsBefore).filter((e) => !e.includes('422')));
  });

  await step('the jobs list finds jobs by a part of their name and by their tags', async () => {
    await page.goto(`${BASE}/#/jobs`);
    await page.waitForSelector('#filter-name');
    await page.fill('#filter-name', 'CAVITY a');
    await page.click('#filter-apply');
    await page.waitForFunction(() => location.hash.includes('name='));
    await page.waitForSelector(`#jobs a[href="#/jobs/${namedId}"]`);
    const rows = await page.locator('#jobs tbody tr').count();
    check(rows === 1, `the name search lists ${rows} jobs, not the one named so`);
    await shot(page, 'desktop-jobs-search');
    // A tag in the list filters by it; the filter shows, and removing it lists all again.
    await page.goto(`${BASE}/#/jobs`);
    await page.waitForSelector(`#jobs a[href="#/jobs/${namedId}"]`);
    const all = await page.locator('#jobs tbody tr').count();
    await page.click('#jobs tbody .tag:has-text("die:4711")');
    await page.waitForSelector('.active-tags .tag');
    await page.waitForFunction(() => document.querySelectorAll('#jobs tbody tr').length === 1);
    check(all > 1, `the list without filters has ${all} jobs`);
    await page.fill('#filter-tag', 'die:4711 nothing-has-this');
    await page.click('#filter-apply');
    await page.waitForSelector('#jobs .empty, #jobs td.empty, #jobs p.muted');
    await page.setViewportSize({ width: 390, height: 844 });
    await page.goto(`${BASE}/#/jobs?tag=die:4711`);
    await page.waitForSelector(`#jobs a[href="#/jobs/${namedId}"]`);
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    check(width <= 390, `the jobs list scrolls sideways on a phone (${width} px wide)`);
    await shot(page, 'phone-jobs-search');
    await page.setViewportSize({ width: 1280, height: 800 });
  });
}

/** On a trochoids job's page: the read-out, a chart point's line, and the moves of selected lines. */
export async function linkSteps({ page, step, check, shot, BASE, jobId }) {
  await step('the hover read-out gives x, y, z, the line, α and feed of the path under the pointer', async () => {
    await page.goto(`${BASE}/#/jobs/${jobId}`);
    await page.waitForSelector('#drawing svg path', { state: 'attached', timeout: 30_000 });
    await page.locator('#drawing svg').scrollIntoViewIfNeeded();
    // A vertex of the drawn path, in screen px, from the trace the page reads.
    const at = await page.evaluate(async (id) => {
      const { frameOf } = await import('/zoom.js');
      const svg = document.querySelector('#drawing svg');
      const frame = frameOf(svg);
      const trace = await (await fetch(`/v1/jobs/${id}/trace`)).json();
      const run = trace.runs.find((r) => !r.rapid && r.values.alpha?.some((v) => v != null) && r.points.length > 3);
      const k = run.values.alpha.findIndex((v, i) => v != null && i > 0);
      const [x, y] = run.points[k];
      const r = svg.getBoundingClientRect();
      const f = r.width / svg.viewBox.baseVal.width;
      return { x: r.left + (frame.left + (x - frame.xMin) * frame.scale - svg.viewBox.baseVal.x) * f,
        y: r.top + (frame.top + (frame.yMax - y) * frame.scale - svg.viewBox.baseVal.y) * f, line: run.lines[k] };
    }, jobId);
    // The page reads the trace once the drawing is in: point again until it has.
    let text = '';
    for (let i = 0; i < 40 && !/line \d+/.test(text); i++) {
      await page.mouse.move(at.x + (i % 2), at.y);
      text = await page.locator('#drawing-readout').innerText();
      if (!/line \d+/.test(text)) await page.waitForTimeout(250);
    }
    check(/^X -?[\d.,]+ {2}Y -?[\d.,]+ {2}Z -?[\d.,]+ mm · line \d+ · α [\d.]+° · feed [\d,]+ mm\/min/.test(text), `the read-out lacks z, line, α or feed: ${text}`);
  });

  await step('a click on a chart point shows its NC line; selected lines mark their moves in the drawing', async () => {
    await page.waitForSelector('.chart svg .x-axis[data-x-min]', { state: 'attached', timeout: 30_000 });
    const chart = page.locator('.chart-canvas').first();
    await chart.scrollIntoViewIfNeeded();
    const box = await chart.locator('svg').boundingBox();
    await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await page.waitForFunction(() => document.querySelector('.chart-canvas[data-line]'));
    const line = await chart.getAttribute('data-line');
    await page.waitForSelector(`#program .nc-row.selected[data-line="${line}"]`);
    await page.waitForSelector('#drawing svg .selected-moves path', { state: 'attached' });
    const d = await page.$eval('#drawing svg .selected-moves path', (p) => p.getAttribute('d'));
    check(/^M[\d.-]+,[\d.-]+L/.test(d), `no moves marked for line ${line}: ${d}`);
    await shot(page, 'desktop-job-linked');
    await page.setViewportSize({ width: 390, height: 844 });
    await page.waitForSelector('#drawing svg .selected-moves', { state: 'attached' });
    await shot(page, 'phone-job-linked');
    await page.setViewportSize({ width: 1280, height: 800 });
    // The charts' path distances in the display unit.
    await page.selectOption('#units', 'inch');
    await page.waitForFunction(() => [...document.querySelectorAll('.chart svg .axis-label')].some((t) => /, in$/.test(t.textContent)), undefined, { timeout: 30_000 });
    await page.selectOption('#units', 'mm');
    await page.waitForFunction(() => [...document.querySelectorAll('.chart svg .axis-label')].some((t) => /, mm$/.test(t.textContent)), undefined, { timeout: 30_000 });
  });
}
