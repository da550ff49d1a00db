// The player (web/player) in headless Chromium: it opens a file by ?src=URL, shows every frame
// as the native decoder makes it at the level picked, keeps one index buffer per key group,
// plays, draws the subject (not a blank canvas), and shows an error, never a hang, for a file
// that is not a .mvid, one cut short and a URL that is not there.
// Usage: node player_test.mjs PROJECT_ROOT WORK_DIR FILE.mvid (FILE and its native_reference
// .bin in WORK_DIR).
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { compareFrame, readReference, sizeOf } from './reference.mjs';

const [root, work] = process.argv.slice(2, 4).map((a) => path.resolve(a));
const name = process.argv[4];
const { serve } = await import(pathToFileURL(path.join(root, 'web', 'serve.mjs')));
const reference = readReference(new Uint8Array(
  readFileSync(path.join(work, name.replace(/\.mvid$/, '.bin')))));
const bytes = readFileSync(path.join(work, name));
writeFileSync(path.join(work, 'not-a-file.mvid'), Buffer.alloc(4096, 7));
writeFileSync(path.join(work, 'cut.mvid'), bytes.subarray(0, Math.floor(bytes.length / 3)));

const server = await serve(root, work);
const { launchChromium } = await import(pathToFileURL(path.join(root, 'web', 'headless.mjs')));
const browser = await launchChromium();
const base = `http://127.0.0.1:${server.address().port}`;

/** Opens the player on `src`; resolves to the page once it shows a frame or an error. */
async function openPlayer(src) {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(`${error}`));
  await page.goto(`${base}/web/player/index.html?src=${encodeURIComponent(src)}`);
  await page.waitForFunction(() => window.meshvidPlayer?.state.ready ||
                                   window.meshvidPlayer?.state.error, null, { timeout: 120000 });
  assert.deepEqual(pageErrors, [], `${src}: errors in the page`);
  return page;
}

try {
  const page = await openPlayer(`/files/${name}`);
  const state = () => page.evaluate(() => ({ ...window.meshvidPlayer.state }));
  assert.equal((await state()).error, null);

  // Every frame at every level, paused and stepped, as the native decoder makes it.
  const scale = sizeOf(reference.frames[0].levels[reference.levels].positions);
  let worst = 0;
  // Stepping in order through a level, a new index buffer at each key group and nowhere else.
  const runs = reference.frames.filter((f, t) => t === 0 ||
                                       f.keyGroup !== reference.frames[t - 1].keyGroup).length;
  await page.evaluate(() => window.meshvidPlayer.seek(0));  // paused, the opening's frames out
  for (let level = 0; level <= reference.levels; ++level) {
    await page.evaluate((l) => window.meshvidPlayer.setLevel(l), level);
    const uploadsBefore = (await state()).indexUploads;
    for (let t = 0; t < reference.frameCount; ++t) {
      await page.evaluate((f) => window.meshvidPlayer.seek(f), t);
      const shown = await page.evaluate(() => ({
        positions: window.meshvidPlayer.positions(),
        keyGroup: window.meshvidPlayer.state.keyGroup }));
      worst = Math.max(worst, compareFrame(name, reference, t, level, {
        positions: shown.positions, keyGroup: shown.keyGroup,
        triangles: reference.frames[t].levels[level].triangles }, scale));
    }
    const uploads = (await state()).indexUploads - uploadsBefore;
    assert.equal(uploads, runs, `level ${level}: ${uploads} index buffers for ${runs} key groups`);
  }
  assert.ok(worst <= 1e-5, `the player's positions differ by ${worst} of the size`);

  // It plays: frames go by on their own.
  await page.evaluate(() => window.meshvidPlayer.seek(0));
  const before = (await state()).framesShown;
  await page.evaluate(() => window.meshvidPlayer.play());
  await page.waitForTimeout(1500);
  await page.evaluate(() => window.meshvidPlayer.pause());
  const played = (await state()).framesShown - before;
  assert.ok(played >= 3, `only ${played} frames shown in 1.5 s of playing`);

  // The subject is drawn: a share of the canvas differs from the background.
  const drawn = await page.evaluate(() => {
    const canvas = document.querySelector('#view canvas');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    let subject = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      subject += Math.abs(pixels[i] - 0x20) + Math.abs(pixels[i + 1] - 0x24) +
                 Math.abs(pixels[i + 2] - 0x2a) > 24 ? 1 : 0;
    }
    return subject / (pixels.length / 4);
  });
  assert.ok(drawn > 0.02, `the canvas is blank (${(100 * drawn).toFixed(2)}% drawn)`);
  if (process.env.MESHVID_PLAYER_SCREENSHOT) {
    await page.screenshot({ path: process.env.MESHVID_PLAYER_SCREENSHOT });
  }
  console.log(`player: ${name}: ${reference.frameCount} frames x ${reference.levels + 1} levels ` +
              `as native (largest difference ${worst.toExponential(2)} of the size), ` +
              `an index buffer per key group (${runs}), ${played} frames in 1.5 s ` +
              `of playing, ${(100 * drawn).toFixed(1)}% of the canvas drawn`);
  await page.close();

  // Bad input: an error in the page, not a hang.
  for (const [src, pattern] of [['/files/not-a-file.mvid', /corrupt|not a/i],
                                ['/files/cut.mvid', /partial|cut|corrupt|readable/i],
                                ['/files/missing.mvid', /404/]]) {
    const bad = await openPlayer(src);
    const { error, ready } = await bad.evaluate(() => ({ ...window.meshvidPlayer.state }));
    assert.ok(!ready && pattern.test(error ?? ''), `${src}: ${error}`);
    assert.equal(await bad.evaluate(() => document.getElementById('message').className), 'error');
    console.log(`player: ${src}: shows "${error}"`);
    await bad.close();
  }
} finally {
  await browser.close();
  server.close();
}
