// The page's side of worker.mjs: a .mvid opened in a dedicated worker, with the interface of
// meshvid.mjs's MvidFile (frameCount, frameRate, levels, keyGroupCount, frame(t, level)).
import { MeshvidError } from './errors.mjs';

/** An opened .mvid decoded in a worker (openMvidInWorker). */
class WorkerMvidFile {
  constructor(worker, call, info) {
    Object.assign(this, info);
    this.worker_ = worker;
    this.call_ = call;
    this.triangles_ = null;  // the last triangles the worker sent
    this.bytesFetched = 0;   // bytes of a streamed file received so far (as of the last frame)
  }

  /** Frame t at `level`: positions (Float32Array, the caller's), triangles (one array per key
   * group and level, as MvidFile gives them) and the key group. */
  async frame(t, level = this.levels) {
    const reply = await this.call_({ type: 'frame', t, level });
    if (reply.triangles) this.triangles_ = reply.triangles;
    this.bytesFetched = reply.bytesFetched;
    return { positions: reply.positions, triangles: this.triangles_, keyGroup: reply.keyGroup };
  }

  /** Ends the worker. */
  close() {
    this.worker_.terminate();
  }
}

/**
 * Opens a .mvid in a new worker: its bytes (Uint8Array or ArrayBuffer; transferred to the
 * worker), or a URL (string or URL, relative to the page), which the worker streams.
 * options.dracoUrl: the URL of a Draco decoder's classic script (three.js's draco_decoder.js).
 */
export async function openMvidInWorker(source, { dracoUrl, allowPartial = false } = {}) {
  const worker = new Worker(new URL('./worker.mjs', import.meta.url), { type: 'module' });
  const pending = new Map();
  let next = 0;
  const failAll = (message) => {
    for (const { reject } of pending.values()) reject(new MeshvidError(message));
    pending.clear();
  };
  worker.onmessage = ({ data }) => {
    const call = pending.get(data.id);
    pending.delete(data.id);
    if (data.error) call?.reject(new MeshvidError(data.error));
    else call?.resolve(data);
  };
  worker.onerror = (event) => failAll(`internal: the decoder's worker failed: ${event.message}`);
  const call = (message, transfer = []) => new Promise((resolve, reject) => {
    const id = next++;
    pending.set(id, { resolve, reject });
    worker.postMessage({ ...message, id }, transfer);
  });
  const streamed = typeof source === 'string' || source instanceof URL;
  const view = source instanceof ArrayBuffer ? new Uint8Array(source) : source;
  try {
    const { info } = await call(
      streamed ? { type: 'open', url: new URL(source, location.href).href, dracoUrl, allowPartial }
               : { type: 'open', bytes: view, dracoUrl, allowPartial },
      streamed ? [] : [view.buffer]);
    return new WorkerMvidFile(worker, call, info);
  } catch (error) {
    worker.terminate();
    throw error;
  }
}
