// In the browser: every frame and level of each file (?files=a.mvid,b.mvid under /files/, with
// native_reference's a.bin beside it) decoded by the WebAssembly decoder with WebCodecs and
// three.js's Draco decoder, compared with the native decoder; and a file the browser cannot
// decode (?unsupported=c.mvid) refused with a MeshvidError. The outcome lands in
// window.meshvidCheck ({ files: [...] } or { error }).
import { loadDracoDecoder } from '/web/build/draco_loader.mjs';
import { MeshvidError, openMvid } from '/web/build/meshvid.mjs';
import { compareFrame, readReference, sizeOf } from './reference.mjs';

const log = (line) => { document.getElementById('log').textContent += `${line}\n`; };

async function fetchBytes(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

async function check() {
  const params = new URLSearchParams(location.search);
  const draco =
    await loadDracoDecoder('/web/node_modules/three/examples/jsm/libs/draco/draco_decoder.js');
  const files = [];
  for (const name of (params.get('files') ?? '').split(',').filter(Boolean)) {
    const bytes = await fetchBytes(`/files/${name}`);
    const reference = readReference(await fetchBytes(`/files/${name.replace(/\.mvid$/, '.bin')}`));
    const file = await openMvid(bytes, { draco });
    const scale = sizeOf(reference.frames[0].levels[reference.levels].positions);
    let worst = 0;
    for (let level = 0; level <= file.levels; ++level) {
      for (let t = 0; t < file.frameCount; ++t) {
        worst = Math.max(worst, compareFrame(name, reference, t, level, await file.frame(t, level),
                                             scale));
      }
    }
    file.close();
    files.push({ name, frames: file.frameCount, levels: file.levels, worst });
    log(`${name}: ${file.frameCount} frames, largest difference ${worst} of the size`);
  }
  const unsupported = [];
  for (const name of (params.get('unsupported') ?? '').split(',').filter(Boolean)) {
    const file = await openMvid(await fetchBytes(`/files/${name}`), { draco });
    try {
      await file.frame(0, 0);
      unsupported.push({ name, error: null });
    } catch (error) {
      unsupported.push({ name, error: error instanceof MeshvidError ? error.message : `${error}` });
    }
    file.close();
  }
  return { files, unsupported };
}

check().then((outcome) => { window.meshvidCheck = outcome; },
             (error) => { window.meshvidCheck = { error: `${error.stack ?? error}` }; });
