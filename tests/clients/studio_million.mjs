// Grows COUNT particles of DLA from the growth studio's page in Debian's Chromium, headless, and
// looks at what the page draws: prints one JSON line with the page's state and count at the end,
// every count it showed on the way, and its console's errors, and saves the view as
// OUT_DIR/million.png.
//   node studio_million.mjs ADDRESS OUT_DIR COUNT
// Exits 0 when it could look; what it saw is for the test to judge.
import { chromium } from 'playwright-core';
import path from 'node:path';

const [address, out, count] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking'],
});
try {
  const page = await (await browser.newContext({ viewport: { width: 1000, height: 600 } })).newPage();
  const messages = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') messages.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => messages.push(`uncaught: ${e.message}`));
  await page.goto(address);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 120000 });
  await page.evaluate(() => document.querySelectorAll('#options details').forEach((group) => { group.open = true; }));
  await page.locator('input[data-option="--particles"]').fill(count);
  await page.locator('input[data-option="--formats"]').fill('csv');
  await page.evaluate(() => {
    window.seenCounts = [];
    new MutationObserver(() => window.seenCounts.push(Number(document.body.dataset.count)))
      .observe(document.body, { attributes: true, attributeFilter: ['data-count'] });
  });
  await page.locator('#grow').click();
  await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state) && document.body.dataset.running === 'false',
    null, { timeout: 1200000 });
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  await page.locator('#view canvas').screenshot({ path: path.join(out, 'million.png') });
  const end = await page.evaluate(() => ({ state: document.body.dataset.state, count: Number(document.body.dataset.count),
    error: document.querySelector('#error').textContent, command: document.querySelector('#command').textContent,
    seen: window.seenCounts }));
  console.log('DLA3D ' + JSON.stringify({ messages, end }));
} finally {
  await browser.close();
}
