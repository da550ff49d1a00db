// The WebAssembly decoder against the native one: every frame of each file at every level,
// positions within 1e-5 of the object's size, the same triangles and key groups; frames asked
// for out of order; bad, cut and out-of-range input refused with a MeshvidError; the same
// files streamed by range requests (a fetch over the bytes), no byte fetched twice.
// Usage: node decoder_test.mjs WEB_BUILD_DIR FILE.mvid REFERENCE.bin [FILE.mvid REFERENCE.bin]...
// (REFERENCE.bin from native_reference). The native decoder's displacement pictures stand in
// for the browser's video decoder, which Node.js lacks.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { compareFrame, readReference, sizeOf } from './reference.mjs';

const [webBuildArgument, ...pairs] = process.argv.slice(2);
const webBuild = path.resolve(webBuildArgument);
const { openMvid, MeshvidError } = await import(pathToFileURL(path.join(webBuild, 'meshvid.mjs')));
const draco = await createRequire(path.join(webBuild, 'package.json'))('draco3d')
  .createDecoderModule({});

async function rejects(promise, pattern, what) {
  await assert.rejects(promise, (e) => e instanceof MeshvidError && pattern.test(e.message), what);
}

/** A fetch serving `bytes` at any URL as an HTTP server does, answering range requests unless
 * `ranges` is false; it adds each request's [start, end) to `log`. */
function fetchOver(bytes, log = [], ranges = true) {
  return async (url, { headers = {} } = {}) => {
    const range = /^bytes=(\d+)-(\d+)$/.exec(headers.range ?? '');
    if (!range || !ranges) {
      log.push([0, bytes.length]);
      return new Response(bytes, { status: 200 });
    }
    const start = Number(range[1]);
    const end = Math.min(Number(range[2]) + 1, bytes.length);
    if (start >= end) return new Response(null, { status: 416 });
    log.push([start, end]);
    return new Response(bytes.slice(start, end), { status: 206, headers: {
      'content-range': `bytes ${start}-${end - 1}/${bytes.length}` } });
  };
}

for (let p = 0; p < pairs.length; p += 2) {
  const name = path.basename(pairs[p]);
  const bytes = new Uint8Array(readFileSync(pairs[p]));
  const reference = readReference(new Uint8Array(readFileSync(pairs[p + 1])));
  let groupsDecoded = 0;
  const decodeGroup = async (video) => {
    ++groupsDecoded;
    assert.ok(video.packets.length > 0, `${name}: group ${video.index} has packets`);
    return reference.frames.slice(video.firstFrame, video.firstFrame + video.frameCount)
      .map((frame) => frame.picture);
  };
  const file = await openMvid(bytes, { draco, decodeGroup });
  assert.equal(file.frameCount, reference.frameCount, `${name}: frame count`);
  assert.equal(file.levels, reference.levels, `${name}: levels`);
  assert.equal(file.partial, false);
  const scale = sizeOf(reference.frames[0].levels[reference.levels].positions);
  let worst = 0;
  const checkFrame = async (t, level) => {
    const decoded = await file.frame(t, level);
    assert.equal(file.keyGroupOf(t), decoded.keyGroup);
    worst = Math.max(worst, compareFrame(name, reference, t, level, decoded, scale));
    return decoded.triangles;
  };
  // In order, every level; a key group's triangles are one array at a level.
  for (let t = 0; t < file.frameCount; ++t) {
    for (let level = 0; level <= file.levels; ++level) {
      const triangles = await checkFrame(t, level);
      if (t > 0 && reference.frames[t - 1].keyGroup === reference.frames[t].keyGroup &&
          level === file.levels) {
        const again = (await file.frame(t - 1, level)).triangles;
        assert.equal(again, triangles, `${name}: frames ${t - 1} and ${t} share one index array`);
      }
    }
  }
  // Out of order, and several asked for at once (they are answered one after another).
  const order = [...Array(file.frameCount).keys()].reverse();
  await Promise.all(order.map((t) => checkFrame(t, file.levels)));
  assert.ok(worst <= 1e-5, `${name}: positions differ by ${worst} of the size`);

  // Streamed: every frame as from the bytes, each byte fetched at most once; from a server
  // without range requests, the file comes whole.
  for (const ranges of [true, false]) {
    const log = [];
    const streamed = await openMvid(`http://localhost/files/${name}`,
                                    { draco, decodeGroup, fetch: fetchOver(bytes, log, ranges) });
    for (let t = 0; t < streamed.frameCount; ++t) {
      const decoded = await streamed.frame(t, streamed.levels);
      worst = Math.max(worst, compareFrame(name, reference, t, streamed.levels, decoded, scale));
    }
    const fetched = log.reduce((sum, [start, end]) => sum + end - start, 0);
    const covered = new Uint8Array(bytes.length);
    for (const [start, end] of log) covered.fill(1, start, end);
    assert.equal(fetched, covered.reduce((sum, b) => sum + b, 0), `${name}: a byte fetched twice`);
    if (!ranges) assert.equal(log.length, 1, `${name}: ${log.length} requests`);
    streamed.close();
  }
  assert.ok(worst <= 1e-5, `${name}: streamed positions differ by ${worst} of the size`);
  // A server that hides Content-Range from the page (another site's, not exposing it): the
  // file is fetched whole.
  {
    const hiding = async (url, init) => {
      const answer = await fetchOver(bytes)(url, init);
      return new Response(await answer.arrayBuffer(), { status: answer.status });
    };
    const whole = await openMvid(`http://localhost/files/${name}`,
                                 { draco, decodeGroup, fetch: hiding });
    assert.equal(whole.frameCount, reference.frameCount, `${name}: opened whole`);
    assert.equal(whole.bytesFetched, 0, `${name}: opened as bytes, not streamed`);
    whole.close();
  }
  // Streamed out of order (key groups set up from the middle), and cut: the cut file has no
  // index, so it is read by a scan, as from bytes.
  {
    const streamed = await openMvid(`http://localhost/files/${name}`,
                                    { draco, decodeGroup, fetch: fetchOver(bytes) });
    for (const t of [...Array(streamed.frameCount).keys()].reverse()) {
      const decoded = await streamed.frame(t, 0);
      worst = Math.max(worst, compareFrame(name, reference, t, 0, decoded, scale));
    }
    streamed.close();
    const cut = bytes.slice(0, Math.floor(bytes.length * 0.7));
    const options = { draco, decodeGroup, allowPartial: true };
    let fromBytes = null;
    try {
      fromBytes = await openMvid(cut, options);
    } catch (e) {
      await rejects(openMvid(`http://localhost/cut-${name}`, { ...options, fetch: fetchOver(cut) }),
                    new RegExp(e.message.split(':')[0]), 'a cut stream');
    }
    if (fromBytes) {
      const cutStream = await openMvid(`http://localhost/cut-${name}`,
                                       { ...options, fetch: fetchOver(cut) });
      assert.equal(cutStream.frameCount, fromBytes.frameCount, `${name}: a cut stream's frames`);
      const last = cutStream.frameCount - 1;
      const decoded = await cutStream.frame(last, 0);
      worst = Math.max(worst, compareFrame(name, reference, last, 0, decoded, scale));
      cutStream.close();
      fromBytes.close();
    }
    assert.ok(worst <= 1e-5, `${name}: streamed positions differ by ${worst} of the size`);
  }
  await rejects(openMvid('http://localhost/missing.mvid', { draco, decodeGroup,
    fetch: async () => new Response(null, { status: 404, statusText: 'Not Found' }) }),
                /^not found: .*404/, 'a missing URL');

  await rejects(file.frame(file.frameCount, 0), /not in 0\.\./, 'a frame past the end');
  await rejects(file.frame(0, file.levels + 1), /level/, 'a level past the finest');
  assert.throws(() => file.keyGroupOf(-1), MeshvidError);
  file.close();

  // A file cut in its second half: refused when its header promised more frames (unless
  // allowPartial), and then opened to the frames it holds, which decode as in the whole file.
  const cut = bytes.slice(0, Math.floor(bytes.length * 0.7));
  let partial = null;
  try {
    partial = await openMvid(cut, { draco, decodeGroup });
    assert.equal(partial.partial, false, `${name}: a partial file opened without allowPartial`);
  } catch (e) {
    assert.ok(e instanceof MeshvidError && /partial file|no frame is readable/.test(e.message),
              String(e));
    if (/partial file/.test(e.message)) {
      partial = await openMvid(cut, { draco, decodeGroup, allowPartial: true });
      assert.ok(partial.partial, `${name}: the cut file is not marked partial`);
    }
  }
  if (partial) {
    assert.ok(partial.frameCount < reference.frameCount, `${name}: the cut file is whole`);
    const last = partial.frameCount - 1;
    const { positions } = await partial.frame(last, 0);
    const expected = reference.frames[last].levels[0].positions;
    for (let i = 0; i < positions.length; ++i) {
      assert.ok(Math.abs(positions[i] - expected[i]) <= 1e-5 * scale, `${name}: cut file's frame`);
    }
    partial.close();
  }
  // Not a .mvid; and a damaged byte past the header, which the chunk it falls in refuses (CRC).
  await rejects(openMvid(new Uint8Array(100).fill(7), { draco, decodeGroup }), /./, 'not a .mvid');
  const damaged = bytes.slice();
  damaged[Math.floor(bytes.length * 0.6)] ^= 0x5a;
  let refused = 0;
  try {
    const opened = await openMvid(damaged, { draco, decodeGroup, allowPartial: true });
    for (let t = 0; t < opened.frameCount; ++t) {
      await opened.frame(t, 0).catch((e) => {
        assert.ok(e instanceof MeshvidError, String(e));
        ++refused;
      });
    }
    opened.close();
  } catch (e) {
    assert.ok(e instanceof MeshvidError, String(e));
    ++refused;
  }
  assert.ok(refused > 0, `${name}: a damaged byte went unnoticed`);
  console.log(`${name}: ${reference.frameCount} frames x ${reference.levels + 1} levels, ` +
              `${groupsDecoded} groups decoded, largest difference ${worst.toExponential(2)} ` +
              'of the size');
}
