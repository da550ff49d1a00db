// What native_reference writes (the native decoder's pictures, positions and triangles of
// every frame and level), read back, and the WebAssembly decoder's frames compared with it.
// Shared by the Node.js test (decoder_test.mjs) and the browser's (browser_check.mjs).

/** Parses native_reference's output (a Uint8Array). */
export function readReference(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let at = 0;
  const u32 = () => { const v = view.getUint32(at, true); at += 4; return v; };
  const take = (Type, count) => {
    const array = new Type(count);
    const get = Type === Float32Array ? (o) => view.getFloat32(o, true)
              : Type === Uint16Array ? (o) => view.getUint16(o, true)
              : (o) => view.getUint32(o, true);
    for (let i = 0; i < count; ++i, at += Type.BYTES_PER_ELEMENT) array[i] = get(at);
    return array;
  };
  const frameCount = u32();
  const levels = u32();
  const frames = [];
  for (let t = 0; t < frameCount; ++t) {
    const keyGroup = u32();
    const width = u32();
    const height = u32();
    const picture = take(Uint16Array, width * height);
    const perLevel = [];
    for (let level = 0; level <= levels; ++level) {
      const positions = take(Float32Array, 3 * u32());
      const triangles = take(Uint32Array, 3 * u32());
      perLevel.push({ positions, triangles });
    }
    frames.push({ keyGroup, picture, levels: perLevel });
  }
  if (at !== bytes.length) throw new Error('the reference has trailing bytes');
  return { frameCount, levels, frames };
}

/** The diagonal of the bounding box of x y z positions. */
export function sizeOf(positions) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; ++i) {
    lo[i % 3] = Math.min(lo[i % 3], positions[i]);
    hi[i % 3] = Math.max(hi[i % 3], positions[i]);
  }
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

/**
 * Compares one decoded frame with the reference: throws on another key group, vertex count or
 * triangles; returns the largest coordinate difference as a share of `scale`.
 */
export function compareFrame(name, reference, t, level, decoded, scale) {
  const expected = reference.frames[t].levels[level];
  const where = `${name}: frame ${t} level ${level}`;
  if (decoded.keyGroup !== reference.frames[t].keyGroup) {
    throw new Error(`${where}: key group ${decoded.keyGroup}, native ` +
                    `${reference.frames[t].keyGroup}`);
  }
  if (decoded.positions.length !== expected.positions.length) {
    throw new Error(`${where}: ${decoded.positions.length / 3} vertices, native ` +
                    `${expected.positions.length / 3}`);
  }
  if (decoded.triangles.length !== expected.triangles.length ||
      decoded.triangles.some((v, i) => v !== expected.triangles[i])) {
    throw new Error(`${where}: the triangles differ from the native decoder's`);
  }
  let worst = 0;
  for (let i = 0; i < expected.positions.length; ++i) {
    worst = Math.max(worst, Math.abs(decoded.positions[i] - expected.positions[i]) / scale);
  }
  return worst;
}
