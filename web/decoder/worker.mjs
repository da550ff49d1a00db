// meshvid's decoder in a dedicated worker, so that a page draws one frame while the next is
// decoded on another core. The page side is openMvidInWorker (worker_client.mjs); the
// messages: {id, type: 'open', bytes or url, dracoUrl, allowPartial} answered with the
// file's figures (a URL is streamed), {id, type: 'frame', t, level} answered with positions (transferred), the triangles
// when they differ from the last frame's (a new key group or level), and the key group; an
// error is answered with {id, error}.
import { loadDracoDecoder } from './draco_loader.mjs';
import { openMvid } from './meshvid.mjs';

let draco = null;
let file = null;
let lastTriangles = null;

self.onmessage = async ({ data }) => {
  const { id } = data;
  try {
    if (data.type === 'open') {
      draco = draco ?? await loadDracoDecoder(data.dracoUrl);
      file?.close();
      file = null;
      lastTriangles = null;
      file = await openMvid(data.url ?? data.bytes, { draco, allowPartial: data.allowPartial });
      const { frameCount, frameRate, levels, keyGroupCount, codecTag, partial } = file;
      self.postMessage({ id, info: { frameCount, frameRate, levels, keyGroupCount, codecTag,
                                     partial } });
    } else if (data.type === 'frame') {
      if (!file) throw new Error('invalid argument: no file is open');
      const frame = await file.frame(data.t, data.level);
      const positions = frame.positions.slice();
      const triangles = frame.triangles !== lastTriangles ? frame.triangles.slice() : null;
      lastTriangles = frame.triangles;
      self.postMessage({ id, positions, triangles, keyGroup: frame.keyGroup,
                         bytesFetched: file.bytesFetched },
                       triangles ? [positions.buffer, triangles.buffer] : [positions.buffer]);
    } else if (data.type === 'close') {
      file?.close();
      file = null;
      self.postMessage({ id });
    }
  } catch (error) {
    self.postMessage({ id, error: `${error.message ?? error}` });
  }
};
