// The WebAssembly decoder against the native one: every frame of each file at every level,
// positions within 1e-5 of the object's size, the same triangles and key groups; frames asked
// for out of order; bad, cut and out-of-range input refused with a MeshvidError.
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
