// meshvid's decoder for JavaScript: opens a .mvid and gives every frame as positions and
// triangles, with the same triangles through a key group. The container, motion and
// reconstruction run in WebAssembly (meshvid_wasm.mjs, built from web/wasm); the base meshes
// are decoded by a Draco decoder module (draco3d's, or three.js's), zstd by fzstd (npm, copied
// beside this file by the build), and the displacement video by WebCodecs (webcodecs.mjs) or
// the `decodeGroup` given to openMvid. worker.mjs runs it off the page's thread.
import { decompress as zstdDecompress } from './fzstd.mjs';
import { MeshvidError } from './errors.mjs';
import createMeshvidWasm from './meshvid_wasm.mjs';
import { decodeGroupWithWebCodecs } from './webcodecs.mjs';

export { MeshvidError };

function check(error) {
  if (error) throw new MeshvidError(error);
}

let wasmModule = null;

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
  constructor(module, wasm, { draco, decodeGroup }) {
    this.module_ = module;
    this.wasm_ = wasm;
    this.draco_ = draco;
    this.decodeGroup_ = decodeGroup;
    this.triangles_ = new Map();  // level -> the current key group's triangles
    this.frameCount = wasm.frameCount();
    this.frameRate = wasm.frameRate();
    this.levels = wasm.levels();
    this.keyGroupCount = wasm.keyGroupCount();
    this.codecTag = wasm.codecTag();
    /** True when fewer frames are readable than the header promises (opened allowPartial). */
    this.partial = wasm.declaredFrameCount() > this.frameCount;
    this.loadedGroup_ = -1;
    this.queue_ = Promise.resolve();
    this.videos_ = new Map();  // group -> promise of its pictures
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
      let video;
      try {
        video = new GroupVideo(this.wasm_, g, this.codecTag);
      } catch (error) {
        return Promise.reject(error);
      }
      this.videos_.set(g, Promise.resolve().then(() => this.decodeGroup_(video)));
    }
    return this.videos_.get(g);
  }

  async loadGroupOf_(t) {
    const g = this.wasm_.gofOfFrame(t);
    if (g === this.loadedGroup_) return;
    this.loadedGroup_ = -1;
    const k = this.wasm_.keyGroupOfGof(g);
    if (this.wasm_.currentKeyGroup() !== k) {
      const base = this.wasm_.baseBytes(k).slice();
      check(this.wasm_.error());
      const mesh = decodeDracoMesh(this.draco_, base);
      check(this.wasm_.setKeyGroup(k, mesh.positions, mesh.triangles));
      this.triangles_.clear();
    }
    check(this.wasm_.loadGof(g));
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
    }
    const frames = this.wasm_.gofFrameCount(g);
    if (!pictures || pictures.length !== frames) {
      throw new MeshvidError(`corrupt: file: group ${g}: the video gives ` +
                             `${pictures ? pictures.length : 0} pictures for ${frames} frames`);
    }
    const samples = this.wasm_.pictureSamples();
    pictures.forEach((picture, i) => {
      if (picture.length !== samples) {
        throw new MeshvidError(`corrupt: file: group ${g}: picture ${i} has ${picture.length} ` +
                               `samples, the layout needs ${samples}`);
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
    await this.loadGroupOf_(t);
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

/**
 * Opens a .mvid from its bytes (Uint8Array or ArrayBuffer).
 * options.draco: a Draco decoder module (draco3d's createDecoderModule(), or three.js's).
 * options.decodeGroup: async (GroupVideo) => array of Uint16Array pictures (width x height
 *   samples each, in presentation order); the browser's WebCodecs by default.
 * options.allowPartial: open a cut file, giving the frames that are readable.
 */
export async function openMvid(bytes, { draco, decodeGroup = decodeGroupWithWebCodecs,
                                        allowPartial = false } = {}) {
  if (!draco) throw new MeshvidError('invalid argument: openMvid needs a Draco decoder module');
  const module = await loadWasm();
  const wasm = new module.WasmDecoder();
  const view = bytes instanceof ArrayBuffer ? new Uint8Array(bytes) : bytes;
  const error = wasm.open(view, allowPartial);
  if (error) {
    wasm.delete();
    throw new MeshvidError(error);
  }
  return new MvidFile(module, wasm, { draco, decodeGroup });
}
