// Runs browser_check.html in headless Chromium (web/headless.mjs) and checks
// its outcome: every frame of each file as the native decoder makes it, and a file of a codec
// browsers lack refused with an error rather than a hang.
// Usage: node browser_test.mjs PROJECT_ROOT WORK_DIR --files a.mvid,b.mvid --unsupported c.mvid
// (the files and native_reference's .bin beside each in WORK_DIR).
import assert from 'node:assert/strict';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [root, work, ...rest] = process.argv.slice(2).map((a, i) => (i < 2 ? path.resolve(a) : a));
const option = (flag) => { const i = rest.indexOf(flag); return i >= 0 ? rest[i + 1] : ''; };

const { serve } = await import(pathToFileURL(path.join(root, 'web', 'serve.mjs')));
const server = await serve(root, work);

const { launchChromium } = await import(pathToFileURL(path.join(root, 'web', 'headless.mjs')));
const browser = await launchChromium();
try {
  const page = await browser.newPage();
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(`${error}`));
  const query = new URLSearchParams({ files: option('--files'),
                                      unsupported: option('--unsupported') });
  await page.goto(`http://127.0.0.1:${server.address().port}/tests/web/browser_check.html?` +
                  query);
  await page.waitForFunction(() => window.meshvidCheck !== undefined, null, { timeout: 300000 });
  const outcome = await page.evaluate(() => window.meshvidCheck);
  assert.deepEqual(pageErrors, [], 'errors in the page');
  assert.equal(outcome.error, undefined, outcome.error);
  for (const file of outcome.files) {
    console.log(`browser: ${file.name}: ${file.frames} frames x ${file.levels + 1} levels, ` +
                `largest difference ${file.worst.toExponential(2)} of the size`);
    assert.ok(file.worst <= 1e-5, `${file.name}: ${file.worst} of the size`);
  }
  assert.equal(outcome.files.length, option('--files').split(',').filter(Boolean).length);
  for (const file of outcome.unsupported) {
    console.log(`browser: ${file.name}: refused: ${file.error}`);
    assert.match(file.error ?? '', /^unsupported: /, `${file.name} was not refused`);
  }
} finally {
  await browser.close();
  server.close();
}
