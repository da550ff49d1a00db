// Mp4Writer: RGB pictures to an MP4 file through libavcodec/libavformat: H.264 (libx264) or,
// where that encoder is missing, HEVC (libx265); yuv420p, so browsers and players show it.
#ifndef MESHVID_TOOLS_RENDER_MP4_WRITER_H_
#define MESHVID_TOOLS_RENDER_MP4_WRITER_H_

#include <memory>
#include <string>

#include "format/status.h"
#include "tools/render/rgb_image.h"

namespace meshvid {

/// Writes an MP4 frame by frame; Finish() flushes the encoder and completes the file. The file
/// appears only when Finish() succeeds (written to a temporary beside it, then renamed).
class Mp4Writer {
 public:
  /// Starts `path` for `width` x `height` pictures (both even) at `frame_rate` frames/s;
  /// `crf` is x264's/x265's constant-quality setting (lower: better, larger).
  static StatusOr<std::unique_ptr<Mp4Writer>> Create(const std::string& path, int width,
                                                     int height, double frame_rate,
                                                     int crf = 20);
  ~Mp4Writer();
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  /// Encodes one picture of the size given to Create().
  Status AddFrame(const RgbImage& image);
  /// Flushes, writes the trailer and renames the file into place.
  Status Finish();
  /// The encoder in use ("libx264" or "libx265").
  const std::string& codec_name() const { return codec_name_; }

 private:
  Mp4Writer() = default;
  Status Drain();  ///< writes the packets the encoder has ready
  struct State;
  std::unique_ptr<State> state_;
  std::string codec_name_;
};

/// `image` padded with its edge pixels to even width and height (what yuv420p needs).
RgbImage PadToEven(const RgbImage& image);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_MP4_WRITER_H_
