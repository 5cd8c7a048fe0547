// Opens one of dla3d's web viewer pages (PREFIX.html) in Debian's Chromium, headless, with
// every request but the page's own file refused, and prints one JSON line: the console's
// errors and warnings, the requests refused, the particle count the page shows at each step,
// and screenshots (without the control panel) at the slider's end, at a quarter and, with a
// mesh, at the end with the mesh hidden.
//   node view_page.mjs PAGE.html OUT_DIR
// Exits 0 when it could look; what it saw is for the test to judge.
import { chromium } from 'playwright-core';
import path from 'node:path';

const [page_path, out] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  // WebGL without a GPU: SwiftShader, Chromium's software renderer.
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking'],
});
try {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  const messages = [], refused = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') messages.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => messages.push(`uncaught: ${e.message}`));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:') || url.startsWith('blob:')) return route.continue();
    refused.push(url);
    return route.abort();
  });
  const started = Date.now();
  await page.goto('file://' + path.resolve(page_path));
  await page.waitForSelector('body[data-ready="true"]', { timeout: 120000 });
  const seconds_to_ready = (Date.now() - started) / 1000;
  const frames = () => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  const count = () => page.locator('#dla-count').textContent();
  const shot = (name) => page.screenshot({ path: path.join(out, name), clip: { x: 0, y: 0, width: 640, height: 400 } });
  await frames();
  const full = await count();
  await shot('full.png');
  await page.locator('#dla-show').fill('250');
  await frames();
  const quarter = await count();
  await shot('quarter.png');
  // Play replays from where the slider is: the event waited for is the count passing the
  // quarter's (a page that does not replay times out here, and the test sees the same count).
  const shown = (text) => Number(text.split(' of ')[0].replace(/,/g, ''));
  await page.locator('#dla-play').click();
  await page.waitForFunction((before) => Number(document.querySelector('#dla-count').textContent.split(' of ')[0]
    .replace(/,/g, '')) > before, shown(quarter), { timeout: 60000 }).catch(() => {});
  const playing = await count();
  let mesh_toggles = null;
  if (!(await page.locator('#dla-mesh').isDisabled())) {
    await page.locator('#dla-play').click();
    await page.locator('#dla-show').fill('1000');
    await page.locator('#dla-mesh').uncheck();
    await frames();
    await shot('no_mesh.png');
    mesh_toggles = true;
  }
  console.log('DLA3D ' + JSON.stringify({ messages, refused, seconds_to_ready, full, quarter, playing, mesh_toggles }));
} finally {
  await browser.close();
}
