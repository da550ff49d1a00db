// The meshvid encoder: a multi-view capture in, a .mvid out, by the method of
// docs/encoder-method.md (base mesh, its motion as a tracked embedded deformation, fused
// displacement video).
#ifndef MESHVID_CODEC_ENC_ENCODER_H_
#define MESHVID_CODEC_ENC_ENCODER_H_

#include "codec/common/progress.h"
#include "codec/enc/frame_source.h"
#include "codec/enc/options.h"
#include "codec/enc/summary.h"
#include "format/container_writer.h"
#include "format/status.h"

namespace meshvid {

/// Encodes frames of `source` into `sink`, key group after key group. Stages report progress
/// ("base mesh", "tracking", "detail"); a cancelled callback stops with kCancelled.
StatusOr<EncodeSummary> EncodeCapture(const FrameSource& source, ByteSink sink,
                                      const EncoderOptions& options,
                                      const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_ENCODER_H_
