// Opens ramap's report.html files in Debian's Chromium (headless, software WebGL) through
// playwright-core and checks what a person would see: no console error, a WebGL context, one
// frustum drawn per registered image of every model, a mapper toggled off and on, an orbit that
// moves the camera, and a screenshot that is not blank.
//
//   node report_test.mjs REPORT.html[=SCREENSHOT.png] ...
//
// Exit 0 when every report passes, 1 on a failure, 77 (skipped) when Chromium or playwright-core
// is missing. Prints one line per check.
import { existsSync } from 'node:fs';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import path from 'node:path';

const SKIP = 77;
const chromiumPath = process.env.RAMAP_CHROMIUM || '/usr/bin/chromium';
if (!existsSync(chromiumPath)) {
  console.log(`report_test: skipped: no Chromium at ${chromiumPath} (scripts/install-deps.sh installs Debian's chromium)`);
  process.exit(SKIP);
}
let chromium;
try {
  const require = createRequire(import.meta.url);
  ({ chromium } = require('playwright-core'));
} catch (error) {
  console.log('report_test: skipped: playwright-core is not installed (scripts/install-deps.sh runs npm ci in tests/browser)');
  process.exit(SKIP);
}

const reports = process.argv.slice(2).map((argument) => {
  const [report, screenshot] = argument.split('=');
  return { report: path.resolve(report), screenshot: screenshot ? path.resolve(screenshot) : null };
});
if (reports.length === 0) {
  console.error('usage: node report_test.mjs REPORT.html[=SCREENSHOT.png] ...');
  process.exit(2);
}

let failures = 0;
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures += 1;
}

const browser = await chromium.launch({
  executablePath: chromiumPath,
  headless: true,
  // Software WebGL (SwiftShader through ANGLE): CI machines have no GPU. The network flags keep
  // Chromium from calling out of a machine that has no network.
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
});
try {
  for (const { report, screenshot } of reports) {
    console.log(`report_test: ${report}`);
    check(existsSync(report), 'the report exists');
    if (!existsSync(report)) continue;
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
    const problems = [];
    page.on('console', (message) => { if (message.type() === 'error') problems.push(message.text()); });
    page.on('pageerror', (error) => problems.push(String(error)));
    const requests = [];
    page.on('request', (request) => { if (!request.url().startsWith('file:') && !request.url().startsWith('data:')) requests.push(request.url()); });

    const started = Date.now();
    await page.goto(pathToFileURL(report).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.ramapReport && window.ramapReport.ready, null, { timeout: 30000 });
    const seconds = (Date.now() - started) / 1000;
    console.log(`     opened and drawn in ${seconds.toFixed(2)} s`);

    const state = await page.evaluate(() => window.ramapReport.state());
    check(state.webgl === 'webgl2' || state.webgl === 'webgl', `a WebGL context (${state.webgl})`);
    check(state.layers.filter((layer) => !layer.reference).length > 0, 'at least one model in the view');
    // The frusta in the drawn geometry against the registered images as the mapper's summary or
    // the comparison's table counts them (not the page's own arrays).
    for (const layer of state.layers) {
      check(layer.frusta === layer.expected,
        `${layer.name}: ${layer.frusta} frusta drawn for ${layer.expected} registered images`);
    }
    const lit = await page.evaluate(() => window.ramapReport.litPixels());
    check(lit > 2000, `the view draws something (${lit} pixels off the background)`);

    // Toggle the last model off and on again through its checkbox, as a person would.
    const models = state.layers.filter((layer) => !layer.reference);
    const toggled = models[models.length - 1].name;
    const box = page.locator(`#view-controls input[data-model="${toggled}"]`);
    const wasChecked = await box.isChecked();
    await box.click();
    let after = await page.evaluate(() => window.ramapReport.state());
    check(after.layers.find((layer) => layer.name === toggled).visible === !wasChecked, `${toggled} toggled by its checkbox`);
    await box.click();
    after = await page.evaluate(() => window.ramapReport.state());
    check(after.layers.find((layer) => layer.name === toggled).visible === wasChecked, `${toggled} toggled back`);

    // Orbit: drag across the canvas.
    const canvas = page.locator('#view canvas');
    await canvas.scrollIntoViewIfNeeded();
    const frame = await canvas.boundingBox();
    await page.mouse.move(frame.x + frame.width / 2, frame.y + frame.height / 2);
    await page.mouse.down();
    await page.mouse.move(frame.x + frame.width / 2 + 160, frame.y + frame.height / 2 + 40, { steps: 8 });
    await page.mouse.up();
    const orbited = await page.evaluate(() => window.ramapReport.state());
    const moved = Math.hypot(...orbited.camera.map((c, k) => c - state.camera[k]));
    check(moved > 0, 'dragging orbits the camera');
    const litAfter = await page.evaluate(() => window.ramapReport.litPixels());
    check(litAfter > 2000, `the orbited view draws something (${litAfter} pixels)`);

    const svgCount = await page.locator('#plots svg').count();
    check(svgCount > 0, `${svgCount} plots drawn as SVG`);

    if (screenshot) {
      await page.mouse.move(frame.x + frame.width / 2, frame.y + frame.height / 2);
      await page.mouse.down();
      await page.mouse.move(frame.x + frame.width / 2 - 160, frame.y + frame.height / 2 - 40, { steps: 8 });
      await page.mouse.up();
      await page.screenshot({ path: screenshot, fullPage: true });
      console.log(`     screenshot: ${screenshot}`);
    }
    check(requests.length === 0, `no network request (${requests.join(', ') || 'none'})`);
    check(problems.length === 0, `no console error${problems.length ? ': ' + problems.join(' | ') : ''}`);
    await page.close();
  }
} finally {
  await browser.close();
}
console.log(`report_test: ${failures === 0 ? 'passed' : failures + ' checks failed'}`);
process.exit(failures === 0 ? 0 : 1);
