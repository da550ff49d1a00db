// Reads parts of a remote file with HTTP range requests, for the streamed .mvid (meshvid.mjs).
import { MeshvidError } from './errors.mjs';

/** [start, end, size] of a 206 answer's Content-Range, or null when it cannot be read (another
 * site's server that does not expose it to pages). */
function contentRange(response) {
  const range = /^bytes (\d+)-(\d+)\/(\d+)$/.exec(response.headers.get('content-range') ?? '');
  return range ? [Number(range[1]), Number(range[2]) + 1, Number(range[3])] : null;
}

/** A file at a URL, read a byte range at a time. */
export class RemoteFile {
  constructor(url, fetchImpl = globalThis.fetch) {
    this.url = url;
    this.fetch_ = (...request) => fetchImpl(...request);  // called unbound, as fetch must be
    this.size = 0;          // known after start()
    this.bytesFetched = 0;  // bytes received so far
  }

  /** The answer to a GET of bytes [start, end), or of the whole file when `start` is null. */
  async get_(start, end) {
    let response;
    try {
      response = await this.fetch_(this.url, start === null ? {}
        : { headers: { range: `bytes=${start}-${end - 1}` } });
    } catch (error) {
      throw new MeshvidError(`i/o error: ${this.url}: ${error.message ?? error}`);
    }
    if (!response.ok) {
      const kind = response.status === 404 ? 'not found' : 'i/o error';
      throw new MeshvidError(`${kind}: ${this.url}: HTTP ${response.status} ` +
                             `${response.statusText}`.trimEnd());
    }
    const bytes = new Uint8Array(await response.arrayBuffer());
    this.bytesFetched += bytes.length;
    return { response, bytes };
  }

  /**
   * Reads the file's first `length` bytes and learns its size. Resolves to {bytes, whole}:
   * whole is true when the server sent the whole file (it does not answer range requests, or
   * hides the size of the file from the page).
   */
  async start(length) {
    const { response, bytes } = await this.get_(0, length);
    const range = response.status === 206 ? contentRange(response) : null;
    if (response.status === 206 && !range) {
      const whole = (await this.get_(null)).bytes;
      this.size = whole.length;
      return { bytes: whole, whole: true };
    }
    if (!range) {
      this.size = bytes.length;
      return { bytes, whole: true };
    }
    if (range[0] !== 0) {
      throw new MeshvidError(`i/o error: ${this.url}: asked for its first bytes, the server ` +
                             `sent bytes from ${range[0]}`);
    }
    this.size = range[2];
    return { bytes, whole: false };
  }

  /** Bytes [start, end) of the file (a Uint8Array of end - start bytes). */
  async read(start, end) {
    const { response, bytes } = await this.get_(start, end);
    const range = contentRange(response);
    if (range && range[2] !== this.size) {
      throw new MeshvidError(`i/o error: ${this.url}: the file changed on the server while it ` +
                             `was read (${this.size} bytes, now ${range[2]}); open it again`);
    }
    if (response.status !== 206 || bytes.length !== end - start ||
        (range && (range[0] !== start || range[1] !== end))) {
      throw new MeshvidError(`i/o error: ${this.url}: asked for bytes ${start}..${end}, the ` +
                             `server answered HTTP ${response.status} with ${bytes.length} bytes`);
    }
    return bytes;
  }
}
