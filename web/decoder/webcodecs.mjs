// The displacement video decoded by the browser's WebCodecs VideoDecoder: meshvid's web
// profile is AV1 (10-bit monochrome), which browsers decode in software. HEVC and FFV1 files
// do not decode in a browser without a hardware decoder; `meshvid transcode --codec av1` makes
// a file that does.
import { MeshvidError } from './errors.mjs';

/** WebCodecs codec strings by the container's codec tag. */
const CODECS = {
  // Main profile, level 2.0, main tier, 10 bits: a level is the decoder's capacity, and
  // Chromium's software decoder takes any picture the stream holds under this string.
  av01: 'av01.0.00M.10',
};

/** The luma plane of a 10-bit VideoFrame as width x height 16-bit samples (width and height
 * 0: the frame's own). */
async function lumaOf(frame, expectedWidth, expectedHeight) {
  if (!/^I4[024]{2}A?P10$/.test(frame.format ?? '')) {
    throw new Error(`a picture of format ${frame.format}, not 10-bit YUV`);
  }
  const width = expectedWidth || frame.visibleRect.width;
  const height = expectedHeight || frame.visibleRect.height;
  if (frame.visibleRect.width !== width || frame.visibleRect.height !== height) {
    throw new Error(`a ${frame.visibleRect.width}x${frame.visibleRect.height} picture, ` +
                    `not ${width}x${height}`);
  }
  const bytes = new Uint8Array(frame.allocationSize());
  const planes = await frame.copyTo(bytes);
  const { offset, stride } = planes[0];
  const samples = new Uint16Array(width * height);
  const view = new DataView(bytes.buffer);
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      samples[y * width + x] = view.getUint16(offset + y * stride + 2 * x, true);
    }
  }
  return samples;
}

/**
 * Decodes a group of frames (openMvid's `decodeGroup`): its pictures' luma, in presentation
 * order. Rejects with a MeshvidError when the browser has no decoder for the codec or the
 * video does not decode.
 */
export async function decodeGroupWithWebCodecs(video) {
  const codec = CODECS[video.codecTag];
  if (!codec || typeof VideoDecoder === 'undefined') {
    throw new MeshvidError(`unsupported: this browser does not decode ${video.codecTag} video` +
                           (codec ? ' (WebCodecs needs a secure context: https or localhost)'
                                  : '; `meshvid transcode --codec av1` makes a file it plays'));
  }
  const config = { codec, hardwareAcceleration: 'prefer-software', optimizeForLatency: true };
  if (video.width > 0) Object.assign(config, { codedWidth: video.width,
                                               codedHeight: video.height });
  if (video.config.length > 0) config.description = video.config;
  const support = await VideoDecoder.isConfigSupported(config);
  if (!support.supported) {
    throw new MeshvidError(`unsupported: this browser does not decode ${codec} video`);
  }
  const copies = [];
  let failure = null;
  const decoder = new VideoDecoder({
    output: (frame) => {
      const timestamp = frame.timestamp;
      copies.push(lumaOf(frame, video.width, video.height)
        .then((samples) => ({ timestamp, samples }))
        .finally(() => frame.close()));
    },
    error: (error) => { failure = failure ?? error; },
  });
  try {
    decoder.configure(config);
    video.packets.forEach((data, i) => {
      decoder.decode(new EncodedVideoChunk({ type: i === 0 ? 'key' : 'delta', timestamp: i,
                                             data }));
    });
    await decoder.flush();
  } catch (error) {
    failure = failure ?? error;
  } finally {
    if (decoder.state !== 'closed') decoder.close();
  }
  const pictures = await Promise.allSettled(copies);
  const refused = pictures.find((p) => p.status === 'rejected');
  failure = failure ?? refused?.reason;
  if (failure) {
    throw new MeshvidError(`corrupt: group ${video.index}: the video does not decode: ` +
                           (failure.message ?? failure));
  }
  return pictures.map((p) => p.value).sort((a, b) => a.timestamp - b.timestamp)
    .map((p) => p.samples);
}
