// Coding a .mvid's displacement video again with another codec or quality, nothing else
// redone: every key group's base mesh and motion, and every group's transforms and
// displacement range, are copied byte for byte; only the pictures are decoded and encoded
// again. The web player needs AV1 (the codec browsers decode in 10 bits), so HEVC and FFV1
// files are transcoded for it without a new analysis of the capture.
#ifndef MESHVID_CODEC_ENC_CODING_TRANSCODE_H_
#define MESHVID_CODEC_ENC_CODING_TRANSCODE_H_

#include <cstdint>
#include <string>

#include "codec/common/progress.h"
#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// Settings of TranscodeVideo.
struct TranscodeOptions {
  VideoCodec codec = VideoCodec::kAv1;
  int quality = 40;  ///< 0..100, as `meshvid encode --quality` (QualityToQp)
  int effort = 4;    ///< video encoder effort 0 (fastest) .. 9
  int threads = 0;   ///< video encoder threads, 0: automatic
  /// The output header's metadata_json; empty keeps the input's.
  std::string metadata_json;
  ProgressCallback progress;  ///< stages "transcoding" (groups), then "measuring" (frames)
};

/// What TranscodeVideo did.
struct TranscodeSummary {
  std::uint32_t frames = 0;
  std::uint32_t groups = 0;
  std::uint64_t input_bytes = 0, output_bytes = 0;              ///< whole files
  std::uint64_t input_video_bytes = 0,
                output_video_bytes = 0;  ///< the videos' packets (displacement and colour)
  /// How far the decoded displacements moved, against the input's, over every sample of every
  /// frame, in scene units: root mean square and largest.
  double displacement_rms_change = 0, displacement_max_change = 0;
};

/// Writes `output`: `input` with its displacement video coded again as `options` say. The
/// output is written atomically (nothing is left on failure); `input` must be whole (not
/// truncated). Errors name the file and the group.
StatusOr<TranscodeSummary> TranscodeVideo(const std::string& input, const std::string& output,
                                          const TranscodeOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_TRANSCODE_H_
