// The one error type of meshvid's JavaScript decoder.

/** An error of meshvid's decoder: a bad or cut file, an unsupported codec, a call out of
 * range. The message starts with the kind (`corrupt:`, `unsupported:`, `invalid argument:`). */
export class MeshvidError extends Error {
  constructor(message) {
    super(message);
    this.name = 'MeshvidError';
  }
}
