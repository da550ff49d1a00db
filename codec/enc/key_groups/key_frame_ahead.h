// A key frame's base made on a second thread while the key group before it is analysed. Where
// the subject moves fast every frame starts a key group, and a fresh base (fused, then
// decimated on one core) is most of an encode's time; the other core meanwhile tracks the key
// group before. The base made ahead is the one AnalyseKeyGroup would make, so
// the file is the same either way.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_KEY_FRAME_AHEAD_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_KEY_FRAME_AHEAD_H_

#include <future>
#include <map>
#include <optional>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/enc/key_groups/key_group_analysis.h"

namespace meshvid {

/// Makes key frames' proxies and bases, each frame on its own thread (the proxy first, then
/// the base), without reporting progress. No base is made ahead for a user's base mesh (its fit
/// needs the proxy's correspondence target, which is handed on as soon as it is made).
class KeyFrameAhead {
 public:
  /// `ctx` must outlive this object.
  explicit KeyFrameAhead(const EncodeContext& ctx);
  /// Waits for the frames still in making.
  ~KeyFrameAhead();
  KeyFrameAhead(const KeyFrameAhead&) = delete;
  KeyFrameAhead& operator=(const KeyFrameAhead&) = delete;

  /// Whether frame `frame` was started and not taken yet.
  bool Started(int frame) const { return made_.count(frame) > 0; }

  /// Starts making frame `frame`'s proxy and base from its `views` (nothing when it was
  /// started already).
  void Start(int frame, std::vector<TriangleMesh> views);

  /// Frame `frame`'s proxy, waited for (not its base); nothing when the frame was not started,
  /// its proxy was taken already or making it failed.
  std::optional<FrameProxy> TakeProxy(int frame);

  /// Frame `frame`'s base, waited for; nothing when it was not started, or when making it
  /// failed (the caller makes it again and meets the error itself). Take its proxy first
  /// (TakeProxy): it is dropped with the frame. Frames before it still in making are waited
  /// for and dropped; later ones go on.
  std::optional<TriangleMesh> TakeBase(int frame);

 private:
  /// One frame in making: its proxy is ready first.
  struct InMaking {
    std::future<StatusOr<FrameProxy>> proxy;  ///< invalid once taken
    std::future<StatusOr<TriangleMesh>> base;
  };

  EncodeContext quiet_;  ///< the encode's context without a progress callback
  std::map<int, InMaking> made_;  ///< by frame
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_KEY_FRAME_AHEAD_H_
