// meshvid's decoder for JavaScript: opens a .mvid and gives every frame as positions and
// triangles, with the same triangles through a key group. The container, motion and
// reconstruction run in WebAssembly (meshvid_wasm.mjs, built from web/wasm); the base meshes
// are decoded by a Draco decoder module (draco3d's, or three.js's), zstd by fzstd (npm, copied
// beside this file by the build), and the displacement video by WebCodecs (webcodecs.mjs) or
// the `decodeGroup` given to openMvid. A file at a URL is streamed: read by HTTP range
// requests through its index, a group (and its key group's base) at a time, the next group
// fetched and decoded while the current one is shown. worker.mjs runs it off the page's thread.
import { decompress as zstdDecompress } from './fzstd.mjs';
import { MeshvidError } from './errors.mjs';
import createMeshvidWasm from './meshvid_wasm.mjs';
import { RemoteFile } from './range_fetch.mjs';
import { decodeGroupWithWebCodecs } from './webcodecs.mjs';

export { MeshvidError };

function check(error) {
  if (error) throw new MeshvidError(error);
}

let wasmModule = null;

/** Bytes a streamed file's opening reads from each end (the header, the index). */
const OPEN_BYTES = 16384;
/** The least a streamed file's read fetches when it finds bytes missing. */
const MISS_BYTES = 16384;

async function loadWasm() {
  if (!wasmModule) wasmModule = createMeshvidWasm({ zstdDecompress });
  return wasmModule;
}

/**
 * Decodes a Draco-coded triangle mesh with a Draco decoder module: positions (x y z per point,
 * in Draco's point order, which is the encoder's) and triangles (3 corner indices each).
 */
export function decodeDracoMesh(draco, bytes) {
  const buffer = new draco.DecoderBuffer();
  const decoder = new draco.Decoder();
  const mesh = new draco.Mesh();
  try {
    buffer.Init(bytes, bytes.length);
    if (decoder.GetEncodedGeometryType(buffer) !== draco.TRIANGULAR_MESH) {
      throw new MeshvidError('corrupt: base mesh: the Draco stream is not a triangle mesh');
    }
    const status = decoder.DecodeBufferToMesh(buffer, mesh);
    if (!status.ok()) {
      throw new MeshvidError(`corrupt: base mesh: Draco cannot decode it: ${status.error_msg()}`);
    }
    const attribute = decoder.GetAttribute(mesh, decoder.GetAttributeId(mesh, draco.POSITION));
    if (!attribute.ptr || attribute.num_components() !== 3) {
      throw new MeshvidError('corrupt: base mesh: no position attribute of 3 components');
    }
    const points = mesh.num_points();
    const faces = mesh.num_faces();
    const positionBytes = points * 3 * 4;
    const triangleBytes = faces * 3 * 4;
    const scratch = draco._malloc(Math.max(positionBytes, triangleBytes, 4));
    try {
      decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, draco.DT_FLOAT32, positionBytes,
                                                scratch);
      const positions = new Float32Array(draco.HEAPF32.buffer, scratch, points * 3).slice();
      decoder.GetTrianglesUInt32Array(mesh, triangleBytes, scratch);
      const triangles = new Uint32Array(draco.HEAPU32.buffer, scratch, faces * 3).slice();
      return { positions, triangles };
    } finally {
      draco._free(scratch);
    }
  } finally {
    draco.destroy(mesh);
    draco.destroy(decoder);
    draco.destroy(buffer);
  }
}

/** A group of frames as `decodeGroup` receives it: what its video decoder needs. */
class GroupVideo {
  constructor(wasm, index, codecTag) {
    const video = wasm.groupVideo(index);
    check(video.error);
    this.index = index;
    this.codecTag = codecTag;  // the container's codec tag ("av01", "hvc1", "ffv1")
    this.firstFrame = wasm.gofFirstFrame(index);
    this.frameCount = wasm.gofFrameCount(index);
    this.width = video.width;  // picture size in samples (0: the stream's, its key group not
    this.height = video.height;  // being loaded yet)
    this.config = video.config;    // the decoder configuration record
    this.packets = video.packets;  // coded pictures, in decoding order
  }
}

/** An opened .mvid (openMvid). */
export class MvidFile {
  constructor(module, wasm, { draco, decodeGroup, remote = null, name = 'file' }) {
    this.module_ = module;
    this.name_ = name;  // the file's name in errors
    this.wasm_ = wasm;
    this.remote_ = remote;  // the RemoteFile of a streamed file
    this.fetches_ = Promise.resolve();  // a streamed file's range requests, one at a time
    this.draco_ = draco;
    this.decodeGroup_ = decodeGroup;
    this.triangles_ = new Map();  // level -> the current key group's triangles
    this.readFileFigures_();
    this.loadedGroup_ = -1;
    this.queue_ = Promise.resolve();
    this.videos_ = new Map();  // group -> promise of its pictures
    this.preparing_ = -1;      // the key group last made ready ahead
  }

  /** Reads the opened file's figures (a streamed file's once it has opened). */
  readFileFigures_() {
    if (!this.wasm_.isOpen()) return;
    this.frameCount = this.wasm_.frameCount();
    this.frameRate = this.wasm_.frameRate();
    this.levels = this.wasm_.levels();
    this.keyGroupCount = this.wasm_.keyGroupCount();
    this.codecTag = this.wasm_.codecTag();
    /** True when fewer frames are readable than the header promises (opened allowPartial). */
    this.partial = this.wasm_.declaredFrameCount() > this.frameCount;
  }

  /** Bytes received so far of a streamed file (0 for one opened from bytes). */
  get bytesFetched() {
    return this.remote_?.bytesFetched ?? 0;
  }

  checkFrame_(t) {
    if (!Number.isInteger(t) || t < 0 || t >= this.frameCount) {
      throw new MeshvidError(`invalid argument: frame ${t} is not in 0..${this.frameCount} ` +
                             '(exclusive)');
    }
  }

  /** The key group holding frame t. */
  keyGroupOf(t) {
    this.checkFrame_(t);
    return this.wasm_.keyGroupOfGof(this.wasm_.gofOfFrame(t));
  }

  /** Group g's pictures, decoded once (a promise, kept while g or the group before it is
   * loaded). */
  decodeVideo_(g) {
    if (!this.videos_.has(g)) {
      this.videos_.set(g, this.fetchGroup_(g)
        .then(() => this.withBytes_(() => new GroupVideo(this.wasm_, g, this.codecTag)))
        .then((video) => this.decodeGroup_(video)));
    }
    return this.videos_.get(g);
  }

  /** Fetches what of bytes [start, end) of a streamed file has not arrived. */
  async fetchRange_(start, end) {
    for (;;) {
      // One request at a time, each for a gap found just before it, so no byte comes twice.
      const fetched = this.fetches_.then(async () => {
        const gap = this.wasm_.firstGap(start, end);
        if (!gap) return false;
        this.wasm_.addBytes(gap.start, await this.remote_.read(gap.start, gap.end));
        return true;
      });
      this.fetches_ = fetched.catch(() => {});
      if (!await fetched) return;
    }
  }

  /** Fetches group g's bytes, and its key group's base and motion unless it is current. */
  async fetchGroup_(g) {
    if (!this.remote_) return;
    const k = this.wasm_.keyGroupOfGof(g);
    if (this.wasm_.currentKeyGroup() !== k && this.wasm_.preparedKeyGroup() !== k) {
      const { start, end } = this.wasm_.keyGroupSpan(k);
      await this.fetchRange_(start, end);
    }
    const { start, end } = this.wasm_.groupSpan(g);
    await this.fetchRange_(start, end);
  }

  /** call()'s result, fetching and calling again while it finds bytes of a streamed file
   * missing (then its error, if any, is only that). */
  async withBytes_(call) {
    // Each miss of one call fetches twice what the last did: a file without a usable index is
    // read by a scan of its chunks, one miss after another.
    for (let least = MISS_BYTES; ; least *= 2) {
      let result;
      let error = null;
      try {
        result = call();
      } catch (thrown) {
        error = thrown;
      }
      const missing = this.wasm_.takeMissing();
      if (!missing) {
        if (error) throw error;
        return result;
      }
      const end = Math.min(this.remote_.size, Math.max(missing.end, missing.start + least));
      await this.fetchRange_(missing.start, end);
    }
  }

  /** Key group k's base mesh, decoded by Draco (its bytes fetched if need be). */
  async baseMesh_(k) {
    const base = await this.withBytes_(() => {
      const bytes = this.wasm_.baseBytes(k).slice();
      check(this.wasm_.error());
      return bytes;
    });
    return decodeDracoMesh(this.draco_, base);
  }

  /** Makes key group k (which group g starts) ready ahead, with its triangles at `level`, so
   * that its first frame costs what any frame costs; work done between frames. */
  async prepareKeyGroup_(k, g, level) {
    if (this.preparing_ === k || this.wasm_.preparedKeyGroup() === k) return;
    this.preparing_ = k;
    const between = () => new Promise((resolve) => setTimeout(resolve, 0));  // frames go first
    try {
      await this.fetchGroup_(g);
      await between();
      const mesh = await this.baseMesh_(k);
      await between();
      if (this.wasm_.currentKeyGroup() === k) return;
      await this.withBytes_(() => check(this.wasm_.prepareKeyGroup(k, mesh.positions,
                                                                   mesh.triangles, level)));
    } catch {
      // It is set up again when it is needed, which reports the error.
    } finally {
      this.preparing_ = -1;
    }
  }

  async loadGroupOf_(t, level) {
    const g = this.wasm_.gofOfFrame(t);
    if (g === this.loadedGroup_) return;
    this.loadedGroup_ = -1;
    const k = this.wasm_.keyGroupOfGof(g);
    await this.fetchGroup_(g);
    if (this.wasm_.currentKeyGroup() !== k) {
      if (!this.wasm_.usePreparedKeyGroup(k)) {
        const mesh = await this.baseMesh_(k);
        await this.withBytes_(() => check(this.wasm_.setKeyGroup(k, mesh.positions,
                                                                 mesh.triangles)));
      }
      this.triangles_.clear();
    }
    await this.withBytes_(() => check(this.wasm_.loadGof(g)));
    const pictures = await this.decodeVideo_(g).catch((error) => {
      this.videos_.delete(g);  // asked for again, it is decoded again
      throw error;
    });
    // The next group's video decodes while this one's frames are asked for.
    for (const cached of this.videos_.keys()) {
      if (cached !== g) this.videos_.delete(cached);
    }
    if (g + 1 < this.wasm_.gofCount()) {
      this.decodeVideo_(g + 1).catch(() => {});  // a failure surfaces when it is needed
      const next = this.wasm_.keyGroupOfGof(g + 1);
      if (next !== k) this.prepareKeyGroup_(next, g + 1, level);
    }
    const frames = this.wasm_.gofFrameCount(g);
    if (!pictures || pictures.length !== frames) {
      throw new MeshvidError(`corrupt: ${this.name_}: group ${g}: the video gives ` +
                             `${pictures ? pictures.length : 0} pictures for ${frames} frames`);
    }
    const samples = this.wasm_.pictureSamples();
    pictures.forEach((picture, i) => {
      if (picture.length !== samples) {
        throw new MeshvidError(`corrupt: ${this.name_}: group ${g}: picture ${i} has ` +
                               `${picture.length} samples, the layout needs ${samples}`);
      }
      const address = this.wasm_.pictureAddress(i);
      this.module_.HEAPU16.set(picture, address / 2);
    });
    this.loadedGroup_ = g;
  }

  /**
   * Frame t at `level` (0..levels; default the finest): positions (Float32Array, x y z per
   * vertex; a view valid until the next call) and triangles (Uint32Array, 3 corners each; the
   * same array for every frame of a key group at a level, so a new one marks a new key group).
   */
  frame(t, level = this.levels) {
    // One frame at a time: a frame's group stays loaded until its positions are out.
    const result = this.queue_.then(() => this.frameNow_(t, level));
    this.queue_ = result.catch(() => {});
    return result;
  }

  async frameNow_(t, level) {
    this.checkFrame_(t);
    if (!Number.isInteger(level) || level < 0 || level > this.levels) {
      throw new MeshvidError(`invalid argument: level ${level} is not in 0..${this.levels}`);
    }
    await this.loadGroupOf_(t, level);
    check(this.wasm_.decodePositions(t, level));
    let triangles = this.triangles_.get(level);
    if (!triangles) {
      triangles = this.wasm_.triangles(level).slice();
      this.triangles_.set(level, triangles);
    }
    return { positions: this.wasm_.positions(), triangles, keyGroup: this.wasm_.currentKeyGroup() };
  }

  /** Frees the decoder's memory; the file cannot be used afterwards. */
  close() {
    this.wasm_.delete();
  }
}

/** The name of the file at `url` in errors: its last path segment. */
function nameOf(url) {
  const path = url.split(/[?#]/)[0];
  const last = path.slice(path.lastIndexOf('/') + 1);
  try {
    return decodeURIComponent(last) || url;
  } catch {
    return last;  // a malformed escape: the name as it is
  }
}

/**
 * Opens a .mvid: its bytes (Uint8Array or ArrayBuffer), or a URL (string or URL), which is
 * streamed: read with HTTP range requests through the file's index, so frames can be asked
 * for once their group has arrived (a server that ignores range requests sends it whole).
 * options.draco: a Draco decoder module (draco3d's createDecoderModule(), or three.js's).
 * options.decodeGroup: async (GroupVideo) => array of Uint16Array pictures (width x height
 *   samples each, in presentation order); the browser's WebCodecs by default.
 * options.allowPartial: open a cut file, giving the frames that are readable.
 * options.fetch: the fetch function for a URL (globalThis.fetch by default).
 * options.name: the file's name in errors (by default its URL's last segment, or "file").
 */
export async function openMvid(source, { draco, decodeGroup = decodeGroupWithWebCodecs,
                                         allowPartial = false, fetch = globalThis.fetch,
                                         name } = {}) {
  if (!draco) throw new MeshvidError('invalid argument: openMvid needs a Draco decoder module');
  const module = await loadWasm();
  const wasm = new module.WasmDecoder();
  try {
    let remote = null;
    if (typeof source === 'string' || source instanceof URL) {
      const url = `${source}`;
      name ??= nameOf(url);
      remote = new RemoteFile(url, fetch);
      const head = await remote.start(OPEN_BYTES);
      if (head.whole) {
        source = head.bytes;
        remote = null;
      } else {
        wasm.beginStream(remote.size, name);
        wasm.addBytes(0, head.bytes);
      }
    }
    name ??= 'file';
    const file = () => new MvidFile(module, wasm, { draco, decodeGroup, remote, name });
    if (!remote) {
      check(wasm.open(source instanceof ArrayBuffer ? new Uint8Array(source) : source,
                      name, allowPartial));
      return file();
    }
    // The index is at the end: fetch the end, then whatever else opening finds missing.
    const opened = file();
    await opened.fetchRange_(Math.max(0, remote.size - OPEN_BYTES), remote.size);
    await opened.withBytes_(() => check(wasm.openStream(allowPartial)));
    opened.readFileFigures_();
    return opened;
  } catch (error) {
    wasm.delete();
    throw error;
  }
}
