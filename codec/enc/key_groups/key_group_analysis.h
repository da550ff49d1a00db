// The analysis stages of one key group (internal to the encoder, encoder.cc): the frames'
// proxies, the key group's base mesh, its motion (deformed_key_group.h), and where it ends (the
// first frame its tracked base no longer explains, data_fit.h).
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_ANALYSIS_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_ANALYSIS_H_

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/progress.h"
#include "codec/enc/frame_source.h"
#include "codec/enc/fusion/seen_free_space.h"
#include "codec/enc/options.h"
#include "codec/enc/summary.h"
#include "codec/enc/tracking/motion_hint.h"
#include "codec/enc/tracking/normal_shooting.h"
#include "format/status.h"

namespace meshvid {

/// The clock the encoder times its stages by (SecondsSince, codec/common/progress.h).
using Clock = std::chrono::steady_clock;

/// Lengths the options leave at 0, derived from the data's size.
struct Lengths {
  float scale = 1;
  float max_distance = 0, tolerance = 0, detail_max_distance = 0, outlier_distance = 0,
        base_max_error = 0, reacquire_max_distance = 0, node_spacing = 0, base_max_edge = 0,
        proxy_max_edge = 0, farthest_growth = 0;
};

/// A frame's views decimated into one correspondence target, and the target's vertices (the
/// frame's data points for the key-group fit).
struct FrameProxy {
  std::unique_ptr<ShootingTarget> target;  ///< null when the frame has no data
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  ///< per point, the unit normal of its views' surface
  /// Where the frame's calibrated cameras saw through (null without cameras).
  std::shared_ptr<const SeenFreeSpace> free_space;
};

/// Pixel blocks a proxy's SeenFreeSpace keeps (2: a quarter of a full-resolution depth image
/// per view: a key group holds the proxies of the frames it tracks).
inline constexpr int kFreeSpacePixelBlock = 2;

/// Proxies by frame, shared by consecutive key groups (a cut key group's later frames are
/// the next one's first).
using ProxyCache = std::map<int, FrameProxy>;

/// The bounding box of every view of a frame together (empty when they are).
Eigen::AlignedBox3f BoxOf(const std::vector<TriangleMesh>& views);

/// What every stage of one encode shares.
struct EncodeContext {
  const FrameSource& source;
  const EncoderOptions& options;
  const ProgressCallback& progress;
  Lengths lengths;
  ShotLimits shot;  ///< correspondence search (docs/encoder-method.md eq. 4)
  int end = 0;      ///< one past the last frame encoded
  /// The source's cameras when tuning.seen_free_space is on (empty: none used).
  std::vector<ViewCalibration> view_cameras;
};

/// Decimates a frame's views into one proxy (tuning.proxy_fraction of each view's vertices
/// kept, no edge longer than lengths.proxy_max_edge); with `free_space`, also what the
/// context's cameras (view_cameras) saw through.
StatusOr<FrameProxy> BuildProxy(const EncodeContext& ctx, const std::vector<TriangleMesh>& views,
                                bool free_space = true);

/// The error a cancelled progress callback ends an encode with.
Status Cancelled();

/// `ctx` without its progress callback, for work on another thread (the callback is the
/// caller's, on its own thread). Refers to `ctx`'s source and options: `ctx` must outlive it.
EncodeContext WithoutProgress(const EncodeContext& ctx);

/// The analysis of one key group: its base mesh, motion model and the tracks of its frames.
struct KeyGroupAnalysis {
  TriangleMesh base;
  MotionModel motion;
  std::vector<std::vector<RigidTransform>> tracks;  ///< per frame of the key group
  KeyGroupSummary summary;
  double seconds_base = 0;
  /// With EncoderTuning::deform_backward_frames: the base fused for a later key frame that
  /// did not serve (a frame before it was lost), and that frame (-1: none). A key group that
  /// starts at that frame may take it as made ahead.
  std::optional<TriangleMesh> unused_base;
  int unused_base_frame = -1;
  /// Where a frame ended the key group: how the surface moved into it (the next key group's
  /// MotionHint).
  MotionHint hint;
};

/// The base of a key frame whose views are `views` and proxy `proxy`: fused from few points
/// first (fast; `fused`, when given, is FuseFrame's fusion from tuning.base_fusion_points made
/// already, used where that is the fast fusion), redone from the fusion's default number of
/// points when that fails or explains too little of the frame; or the user's base mesh fitted
/// to the frame.
StatusOr<TriangleMesh> MakeKeyFrameBase(const EncodeContext& ctx,
                                        const std::vector<TriangleMesh>& views,
                                        const FrameProxy& proxy,
                                        const TriangleMesh* fused = nullptr);

class TrackingTargets;

/// Analyses the key group that starts at frame `start`: base, motion, tracks; and, when
/// `may_cut`, where it ends (the first frame its tracked base no longer explains). `targets`
/// (tracking_targets.h) keeps the frames' proxies and fused surfaces the next key group may
/// need; the key frame's base starts from its fusion there, when it has one
/// (MakeKeyFrameBase). `hint`, the key group before's (KeyGroupAnalysis::hint), predicts the
/// second frame's motion when its frame is the key frame. `base_made_ahead`, when given, is
/// frame `start`'s base (MakeKeyFrameBase's, made on another thread: key_frame_ahead.h); it is
/// used when `targets` holds the frame's proxy. With EncoderTuning::deform_backward_frames,
/// `later_base_ahead`, when given, is asked for the later key frame's base (and puts its proxy
/// in `targets`' proxies) before one is made.
StatusOr<KeyGroupAnalysis> AnalyseKeyGroup(
    const EncodeContext& ctx, int start, bool may_cut, const MotionHint& hint,
    TrackingTargets* targets, std::optional<TriangleMesh> base_made_ahead = {},
    const std::function<std::optional<TriangleMesh>(int frame)>& later_base_ahead = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_ANALYSIS_H_
