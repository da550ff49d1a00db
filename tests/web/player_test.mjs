// The player (web/player) in headless Chromium: it opens a file by ?src=URL, shows every frame
// as the native decoder makes it at the level picked, keeps one index buffer per key group,
// plays, draws the subject (not a blank canvas) where `meshvid render` draws it from the same
// camera, and shows an error, never a hang, for a file
// that is not a .mvid, one cut short and a URL that is not there. It streams: a long file
// served slowly starts playing once its first group has arrived, and a seek far into it fetches
// that group, not the file.
// Usage: node player_test.mjs PROJECT_ROOT WORK_DIR MESHVID FILE.mvid LONG.mvid (FILE and its
// native_reference .bin, and LONG, in WORK_DIR; MESHVID the command line tool).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync, statSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { compareFrame, readReference, sizeOf } from './reference.mjs';

const [root, work] = process.argv.slice(2, 4).map((a) => path.resolve(a));
const [meshvid, name, longName] = process.argv.slice(4, 7);
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
async function openPlayer(src, origin = base) {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(`${error}`));
  await page.goto(`${origin}/web/player/index.html?src=${encodeURIComponent(src)}`);
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

  // Where `meshvid render` draws it: frame 5 at level 1 from the same camera has the same
  // silhouette (the shading and the background differ; the render's labels are cropped).
  const [width, height] = await page.evaluate(() => {
    const canvas = document.querySelector('#view canvas');
    return [canvas.width, canvas.height];
  });
  const rendered = path.join(work, 'render.png');
  const shownFrame = Math.min(5, reference.frameCount - 1);
  execFileSync(meshvid, ['render', path.join(work, name), '--frames', `${shownFrame}`,
                         '--level', '1', '--camera', '25,12', '--size', `${width}x${height}`,
                         '-o', rendered, '-q']);
  await page.evaluate(() => window.meshvidPlayer.setLevel(1));
  await page.evaluate((t) => window.meshvidPlayer.seek(t), shownFrame);
  await page.evaluate(() => window.meshvidPlayer.aim(25, 12));
  await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() =>
    requestAnimationFrame(resolve))));  // drawn from there
  const overlap = await page.evaluate(async (src) => {
    const pixelsOf = (source, width, height) => {
      const copy = document.createElement('canvas');
      copy.width = width;
      copy.height = height;
      const context = copy.getContext('2d');
      context.drawImage(source, 0, 0, width, height);
      return context.getImageData(0, 0, width, height).data;
    };
    const canvas = document.querySelector('#view canvas');
    const { width, height } = canvas;
    const image = new Image();
    image.src = src;
    await image.decode();
    const player = pixelsOf(canvas, width, height);
    const render = pixelsOf(image, width, height);
    const margin = Math.round(0.1 * height);  // the render's labels
    let both = 0, either = 0, inPlayer = 0, inRender = 0;
    for (let y = margin; y < height - margin; ++y) {
      for (let x = 0; x < width; ++x) {
        const i = 4 * (y * width + x);
        // Each picture's background is even along a row (the render's is a vertical
        // gradient): the subject is what differs from the row's first pixel.
        const subject = (pixels) => {
          const row = 4 * y * width;
          return Math.abs(pixels[i] - pixels[row]) + Math.abs(pixels[i + 1] - pixels[row + 1]) +
                 Math.abs(pixels[i + 2] - pixels[row + 2]) > 24;
        };
        const a = subject(player);
        const b = subject(render);
        both += a && b;
        either += a || b;
        inPlayer += a;
        inRender += b;
      }
    }
    return { iou: both / Math.max(1, either), inPlayer, inRender };
  }, `/files/${path.basename(rendered)}`);
  assert.ok(overlap.inRender > 0.01 * width * height, `the render is blank: ${overlap.inRender}`);
  assert.ok(overlap.iou > 0.9, `the player's silhouette overlaps the render's by ` +
            `${overlap.iou.toFixed(3)} (${overlap.inPlayer} and ${overlap.inRender} pixels)`);
  if (process.env.MESHVID_PLAYER_SCREENSHOT) {
    await page.screenshot({ path: process.env.MESHVID_PLAYER_SCREENSHOT });
  }
  console.log(`player: ${name}: ${reference.frameCount} frames x ${reference.levels + 1} levels ` +
              `as native (largest difference ${worst.toExponential(2)} of the size), ` +
              `an index buffer per key group (${runs}), ${played} frames in 1.5 s ` +
              `of playing, ${(100 * drawn).toFixed(1)}% of the canvas drawn, its silhouette ` +
              `${overlap.iou.toFixed(3)} of meshvid render's (intersection over union)`);
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

  // Streaming: the long file through a server sending 1 MB/s starts playing once its first
  // group is in (long before the whole file could have arrived), plays on as the rest arrives,
  // and a seek to its last frame fetches that frame's group.
  const longSize = statSync(path.join(work, longName)).size;
  const slow = await serve(root, work, 0, { bytesPerSecond: 1e6 });
  try {
    const began = Date.now();
    const page = await openPlayer(`/files/${longName}`, `http://127.0.0.1:${slow.address().port}`);
    const seconds = (Date.now() - began) / 1000;
    // The bytes the player had when its first frame was on screen (it plays on at once).
    const atStart = await page.evaluate(() => window.meshvidPlayer.state.firstFrameBytes);
    const state = () => page.evaluate(() => ({ ...window.meshvidPlayer.state }));
    assert.equal((await state()).error, null);
    assert.ok(atStart < 0.02 * longSize, `${longName}: ${atStart} of ${longSize} bytes ` +
              'fetched before the first frame');
    // It plays on while the rest arrives (slowly, on a loaded machine: no clock is asserted).
    const shownBefore = (await state()).framesShown;
    await page.waitForFunction((n) => window.meshvidPlayer.state.framesShown >= n,
                               shownBefore + 10, { timeout: 60000 });
    const played = (await state()).framesShown - shownBefore;
    const beforeSeek = slow.bytesServed;
    const frames = await page.evaluate(() => window.meshvidPlayer.frameCount());
    await page.evaluate((t) => window.meshvidPlayer.seek(t), frames - 1);
    assert.equal((await state()).frame, frames - 1);
    const forSeek = slow.bytesServed - beforeSeek;
    assert.ok(forSeek < 0.02 * longSize, `${longName}: the seek fetched ${forSeek} bytes`);
    console.log(`player: ${longName} (${(longSize / 1e6).toFixed(1)} MB, ${frames} frames) at ` +
                `1 MB/s: first frame after ${seconds.toFixed(2)} s and ${atStart} bytes, ` +
                `then ${played} more frames, a seek to the last frame fetched ${forSeek} ` +
                `bytes; ${slow.bytesServed} bytes in all`);
    await page.close();
  } finally {
    slow.close();
  }
} finally {
  await browser.close();
  server.close();
}
