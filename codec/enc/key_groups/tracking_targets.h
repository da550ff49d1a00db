// The frames a key group's nodes are tracked to (internal to the encoder): each frame's proxy
// and, with tuning.deform_track_fused, its views fused, made once each and, one frame at a
// time, ahead on another thread.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_TRACKING_TARGETS_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_TRACKING_TARGETS_H_

#include <future>
#include <map>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "codec/enc/key_groups/key_group_analysis.h"
#include "codec/enc/tracking/deformation_tracking.h"
#include "format/status.h"

namespace meshvid {

/// A frame's views fused (FuseFrame from tuning.base_fusion_points) as the deformation tracker
/// searches it, and as its key frame's base starts from.
struct FusedFrame {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3f> normals;  ///< the mesh's vertex normals
};

/// The tracking targets of an encode's frames: a frame's proxy goes to the encode's
/// ProxyCache, its fused surface stays here, and the key groups share both (the frame that
/// ends a key group is the next one's key frame, whose base starts from the same fusion; a
/// first-frame key group after a later key frame failed fuses its frames again only where
/// they were dropped). One frame at a time can be made on another thread (StartMaking) while
/// this one solves the frame before or makes a base: the solve leaves a core idle at times and
/// a base's decimation runs on one, while a frame's proxy decimation and fusion are most of a
/// tracked frame's time. What is made there is what would be made here, so the file is the
/// same either way. Made there, a frame reports no progress; a cancel waits for it.
class TrackingTargets {
 public:
  /// `ctx` and `proxies` must outlive this object.
  TrackingTargets(const EncodeContext& ctx, ProxyCache* proxies);
  /// Waits for a frame still in making.
  ~TrackingTargets();
  TrackingTargets(const TrackingTargets&) = delete;
  TrackingTargets& operator=(const TrackingTargets&) = delete;

  /// Starts making frame `t`'s targets on another thread, from its views loaded here. Nothing
  /// when they are made or in making, or `t` is not in the encode; another frame in making is
  /// collected first (Collect).
  Status StartMaking(int t);

  /// Waits for frame `t` when it is in making and keeps what was made (nothing when making it
  /// failed: the frame is made again in turn, which meets the error itself).
  void Collect(int t);

  /// What frame `t` is tracked to: its fused surface (tuning.deform_track_fused) or its
  /// proxy's points; made here unless made already or in making (then waited for).
  StatusOr<TrackingData> DataOf(int t);

  /// Frame `t`'s proxy, made by DataOf(t) or earlier.
  const FrameProxy& Proxy(int t) const { return proxies_.at(t); }
  /// Frame `t`'s fused surface, or null when it is not fused (Collect it first where it may be
  /// in making).
  const FusedFrame* Fused(int t) const;
  /// The encode's proxies.
  ProxyCache& proxies() { return proxies_; }
  /// Drops the frames before `t` (a forward run, or the next key group, is done with them),
  /// and one in making among them.
  void DropBefore(int t);

 private:
  /// A frame's targets as made: each only where it was missing.
  struct Made {
    std::optional<FrameProxy> proxy;
    std::optional<FusedFrame> fused;
  };
  struct InMaking {
    int frame = 0;
    std::future<StatusOr<Made>> made;
  };

  /// Which of a frame's targets are not made yet.
  struct Missing {
    bool proxy = false;
    bool fused = false;  ///< only where frames are fused for tracking
    bool any() const { return proxy || fused; }
  };

  /// Which of frame t's targets are not made yet.
  Missing MissingOf(int t) const;
  /// Frame t's `missing` targets, made from its views with `ctx`.
  static StatusOr<Made> Make(const EncodeContext& ctx, const std::vector<TriangleMesh>& views,
                             Missing missing);
  /// Keeps what was made for frame t.
  void Keep(int t, Made made);

  const EncodeContext& ctx_;
  const EncodeContext quiet_;  ///< ctx_ without progress, for the other thread
  ProxyCache& proxies_;
  std::map<int, FusedFrame> fused_;
  std::optional<InMaking> in_making_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_TRACKING_TARGETS_H_
