// Drives the growth studio (dla3d studio) in Debian's Chromium, headless, as a user would: load
// the bust, paint a patch of seeds, grow PARTICLES, stop part way, go on, finish, and download
// the files; then paint an Eden mask on its grid and grow with it. Every request off the studio's own address is refused. Prints one JSON line: the
// console's errors, the requests refused, every particle count the page showed, the count when
// stopped, the final count, the command the page shows and the files saved in OUT_DIR (with
// screenshots of the view before growth and at the end).
//   node studio_page.mjs ADDRESS OUT_DIR PARTICLES
// Exits 0 when it could look; what it saw is for the test to judge.
import { chromium } from 'playwright-core';
import path from 'node:path';

const [address, out, particles] = process.argv.slice(2);
const origin = new URL(address).origin;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking'],
});
try {
  const context = await browser.newContext({ viewport: { width: 1000, height: 600 }, acceptDownloads: true });
  const page = await context.newPage();
  const messages = [], refused = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') messages.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => messages.push(`uncaught: ${e.message}`));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith(origin) || url.startsWith('data:') || url.startsWith('blob:')) return route.continue();
    refused.push(url);
    return route.abort();
  });
  const minutes = 120000;
  await page.goto(address);
  await page.waitForSelector('body[data-ready="true"]', { timeout: minutes });
  await page.locator('#bust').click();
  await page.waitForSelector('body[data-mesh="true"]', { timeout: minutes });
  const view = page.locator('#view canvas');
  const box = await view.boundingBox();
  const frames = () => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  const shot = (name) => view.screenshot({ path: path.join(out, name) });
  await frames();
  await shot('before.png');
  // A stroke across the middle of the view, where the framed bust is.
  await page.locator('#brush').selectOption('seeds');
  const cx = box.x + box.width / 2, cy = box.y + box.height * 0.45;
  await page.mouse.move(cx - 30, cy);
  await page.mouse.down();
  for (let i = 0; i <= 12; ++i) await page.mouse.move(cx - 30 + 5 * i, cy + (i % 3));
  await page.mouse.up();
  const painted = await page.evaluate(() => document.body.dataset.painted === 'true');
  await page.locator('#brush').selectOption('none');
  await page.evaluate(() => document.querySelectorAll('#options details').forEach((group) => { group.open = true; }));
  await page.locator('input[data-option="--particles"]').fill(particles);
  await page.locator('input[data-option="--formats"]').fill('csv,glb,json');

  // Every count the page shows, as it shows it; Stop is clicked as the first particles show, in
  // the same task, so that the stop lands part way even on a fast run.
  await page.evaluate(() => {
    window.seenCounts = [];
    new MutationObserver(() => {
      const count = Number(document.body.dataset.count);
      if (window.seenCounts[window.seenCounts.length - 1] !== count) window.seenCounts.push(count);
      if (count > 0 && !window.stopClicked) {
        window.stopClicked = true;
        document.querySelector('#stop').click();
      }
    }).observe(document.body, { attributes: true, attributeFilter: ['data-count'] });
  });
  await page.locator('#grow').click();
  await page.waitForFunction(() => ['stopped', 'done', 'error'].includes(document.body.dataset.state), null, { timeout: minutes });
  const stopped = await page.evaluate(() => ({ state: document.body.dataset.state, count: Number(document.body.dataset.count) }));
  if (stopped.state === 'stopped') {
    await page.locator('#goon').click();
    await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state) && document.body.dataset.running === 'false',
      null, { timeout: minutes });
  }
  const end = await page.evaluate(() => ({ state: document.body.dataset.state, count: Number(document.body.dataset.count),
    error: document.querySelector('#error').textContent, command: document.querySelector('#command').textContent,
    seen: window.seenCounts }));
  await frames();
  await shot('grown.png');
  const saved = [];
  for (const name of ['run.csv', 'run.glb', 'painted.ply']) {
    const link = page.locator(`#files a[data-file="${name}"]`);
    if (await link.count() === 0) continue;
    const [download] = await Promise.all([page.waitForEvent('download'), link.click()]);
    await download.saveAs(path.join(out, name));
    saved.push(name);
  }
  // Eden with a mask painted on its grid: the sites left of and above the dropped one.
  await page.locator('#model').selectOption('eden');
  const maskShown = await page.locator('#mask-painter').isVisible();
  for (const cell of [39, 31]) await page.locator(`#mask span[data-cell="${cell}"]`).click();
  await page.locator('#mask-use').check();
  await page.evaluate(() => document.querySelectorAll('#options details').forEach((group) => { group.open = true; }));
  await page.locator('select[data-option="--mode"]').selectOption('drop');  // a word of a list: a drop-down
  await page.locator('input[data-option="--sites"]').fill('2000');
  await page.locator('input[data-option="--formats"]').fill('csv');
  await page.locator('#grow').click();
  await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state) && document.body.dataset.running === 'false',
    null, { timeout: minutes });
  const eden = await page.evaluate(() => ({ state: document.body.dataset.state, count: Number(document.body.dataset.count),
    command: document.querySelector('#command').textContent, error: document.querySelector('#error').textContent }));
  eden.shown = maskShown;
  const maskLink = page.locator('#files a[data-file="mask.txt"]');
  if (await maskLink.count() > 0) {
    const [download] = await Promise.all([page.waitForEvent('download'), maskLink.click()]);
    await download.saveAs(path.join(out, 'mask.txt'));
    saved.push('mask.txt');
  }
  console.log('DLA3D ' + JSON.stringify({ messages, refused, painted, stopped, end, saved, eden }));
} finally {
  await browser.close();
}
