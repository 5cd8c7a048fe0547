// Drives the studio's option panel in Debian's Chromium, headless: picks the breakdown model,
// reads the controls its described options became (a drop-down for --field, a slider for --eta,
// a check box for --stop-at-strike), applies the lightning preset, moves the slider, picks a
// field, clears the check box, and grows. Prints one JSON line: the console's errors, the
// controls seen, what the preset set, the field the slider wrote, and the end of the run with
// the command the page shows (and a screenshot of the panel in OUT_DIR).
//   node studio_described.mjs ADDRESS OUT_DIR
// Exits 0 when it could look; what it saw is for the test to judge.
import { chromium } from 'playwright-core';
import path from 'node:path';

const [address, out] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking'],
});
try {
  const page = await (await browser.newContext({ viewport: { width: 1000, height: 900 } })).newPage();
  const messages = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') messages.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => messages.push(`uncaught: ${e.message}`));
  const minutes = 120000;
  await page.goto(address);
  await page.waitForSelector('body[data-ready="true"]', { timeout: minutes });
  await page.locator('#model').selectOption('breakdown');
  await page.evaluate(() => document.querySelectorAll('#options details').forEach((group) => { group.open = true; }));
  const controls = await page.evaluate(() => {
    const of = (name) => document.querySelector(`[data-option="${name}"]`);
    const field = of('--field'), eta = of('--eta'), slider = document.querySelector('[data-slider-of="--eta"]');
    const strike = of('--stop-at-strike');
    return {
      field: field && { tag: field.tagName, choices: [...field.options].map((o) => o.value) },
      eta: eta && { tag: eta.tagName, type: eta.type, label: eta.closest('.option').querySelector('label').textContent },
      slider: slider && { type: slider.type, min: slider.min, max: slider.max, value: slider.value },
      strike: strike && { type: strike.type, checked: strike.checked },
    };
  });
  // The lightning preset fills the controls with its options.
  await page.locator('#preset').selectOption('lightning');
  const preset = await page.evaluate(() => ({
    eta: document.querySelector('[data-option="--eta"]').value,
    slider: document.querySelector('[data-slider-of="--eta"]').value,
    seedAt: document.querySelector('[data-option="--seed-at"]').value,
    targetPlane: document.querySelector('[data-option="--target-plane"]').value,
    summary: document.querySelector('#preset').closest('.option').querySelector('small').textContent,
  }));
  // The slider, moved (Playwright fills no range input): its value goes into the field beside it.
  await page.locator('[data-slider-of="--eta"]').evaluate((slider) => {
    slider.value = '2.5';
    slider.dispatchEvent(new Event('input', { bubbles: true }));
  });
  const etaWritten = await page.locator('[data-option="--eta"]').inputValue();
  await page.locator('select[data-option="--field"]').selectOption('conductor');
  await page.locator('[data-option="--stop-at-strike"]').uncheck();  // on by default: sends its negation
  await page.locator('[data-option="--particles"]').fill('300');
  await page.locator('[data-option="--formats"]').fill('csv');
  // The panel's top: the Preset menu and the Discharge group.
  await page.locator('#preset').scrollIntoViewIfNeeded();
  const top = await page.locator('#options').boundingBox();
  await page.screenshot({ path: path.join(out, 'panel.png'), clip: { x: top.x, y: top.y, width: top.width, height: 520 } });
  await page.locator('#grow').click();
  await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state) && document.body.dataset.running === 'false',
    null, { timeout: minutes });
  const end = await page.evaluate(() => ({ state: document.body.dataset.state, count: Number(document.body.dataset.count),
    error: document.querySelector('#error').textContent, command: document.querySelector('#command').textContent }));
  console.log('DLA3D ' + JSON.stringify({ messages, controls, preset, etaWritten, end }));
} finally {
  await browser.close();
}
