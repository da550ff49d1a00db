// The player's speed in headless Chromium (software rendering): frames decoded per second in
// the page (WebAssembly + WebCodecs + Draco in the player's worker, stepping through every
// frame in order, paused), and while it plays: frames shown and dropped (skipped to keep up
// with the clock) and pictures drawn per second. Optionally a screenshot of one frame.
// Usage: node bench/web/player_speed.mjs FILE.mvid [--level L] [--seconds S] [--frame T]
//        [--screenshot OUT.png] [--size WxH]
// (run from the project's root after scripts/setup; bench/WEB.md records the results).
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const args = process.argv.slice(2);
const option = (flag, fallback) => {
  const i = args.indexOf(flag);
  return i >= 0 ? args[i + 1] : fallback;
};
const file = path.resolve(args[0]);
const level = Number(option('--level', '1'));
const seconds = Number(option('--seconds', '10'));
const [width, height] = option('--size', '960x540').split('x').map(Number);
const root = process.cwd();
const { serve } = await import(pathToFileURL(path.join(root, 'web', 'serve.mjs')));

const server = await serve(root, path.dirname(file));
const { launchChromium } = await import(pathToFileURL(path.join(root, 'web', 'headless.mjs')));
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: { width, height } });
  await page.goto(`http://127.0.0.1:${server.address().port}/web/player/index.html?src=` +
                  `/files/${encodeURIComponent(path.basename(file))}`);
  await page.waitForFunction(() => window.meshvidPlayer?.state.ready ||
                                   window.meshvidPlayer?.state.error, null, { timeout: 300000 });
  const failure = await page.evaluate(() => window.meshvidPlayer.state.error);
  if (failure) throw new Error(failure);
  const frames = await page.evaluate(() => window.meshvidPlayer.frameCount());

  // Decoding: every frame in order, paused (the first pass warms up; the second is timed).
  const decode = await page.evaluate(async ({ level, frames }) => {
    const player = window.meshvidPlayer;
    player.setLevel(level);
    for (let t = 0; t < frames; ++t) await player.seek(t);
    const before = { ms: player.state.decodeMs, wall: performance.now() };
    for (let t = 0; t < frames; ++t) await player.seek(t);
    return { decodeFps: frames / ((player.state.decodeMs - before.ms) / 1000),
             stepFps: frames / ((performance.now() - before.wall) / 1000) };
  }, { level, frames });

  // Playing.
  const play = await page.evaluate(async (seconds) => {
    const player = window.meshvidPlayer;
    await player.seek(0);
    const before = { shown: player.state.framesShown, renders: player.state.renders,
                     dropped: player.state.dropped, wall: performance.now() };
    player.play();
    await new Promise((resolve) => setTimeout(resolve, seconds * 1000));
    player.pause();
    const elapsed = (performance.now() - before.wall) / 1000;
    return { shownFps: (player.state.framesShown - before.shown) / elapsed,
             drawFps: (player.state.renders - before.renders) / elapsed,
             dropped: player.state.dropped - before.dropped,
             shown: player.state.framesShown - before.shown };
  }, seconds);
  const vertices = await page.evaluate(() => window.meshvidPlayer.positions().length / 3);
  console.log(JSON.stringify({
    file: path.basename(file), frames, level, vertices, viewport: `${width}x${height}`,
    cores: os.cpus().length, chromium: browser.version(),
    decode_fps: +decode.decodeFps.toFixed(1), step_fps: +decode.stepFps.toFixed(1),
    play_seconds: seconds, play_shown: play.shown, play_dropped: play.dropped,
    play_shown_fps: +play.shownFps.toFixed(1), play_draw_fps: +play.drawFps.toFixed(1),
    capture_fps: await page.evaluate(() => window.meshvidPlayer.frameRate()),
  }));
  const screenshot = option('--screenshot');
  if (screenshot) {
    await page.evaluate((t) => window.meshvidPlayer.seek(t), Number(option('--frame', '0')));
    await page.screenshot({ path: screenshot });
  }
} finally {
  await browser.close();
  server.close();
}
