#include "codec/enc/key_groups/deformed_key_group.h"

#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "codec/common/deformation_graph.h"
#include "codec/common/subdivision.h"
#include "codec/enc/key_groups/key_group_rules.h"
#include "codec/enc/tracking/deformation_tracking.h"
#include "codec/enc/tracking/motion_hint.h"
#include "codec/enc/tracking/rigid_node_groups.h"

namespace meshvid {
namespace {

/// The tracker's settings for an encode.
DeformationTrackingOptions TrackingOptions(const EncodeContext& ctx) {
  const EncoderTuning& tuning = ctx.options.tuning;
  DeformationTrackingOptions tracking;
  tracking.max_distance = ctx.lengths.max_distance;
  tracking.tolerance = ctx.lengths.tolerance;
  tracking.min_normal_cos = ctx.shot.min_abs_cos;
  tracking.rigidity = tuning.deform_rigidity;
  tracking.coarse_stiffness = tuning.deform_coarse_stiffness;
  tracking.point_weight = tuning.deform_point_weight;
  tracking.iterations = tuning.deform_iterations;
  tracking.first_iterations = tuning.deform_first_iterations;
  if (tuning.deform_reacquire) {
    tracking.reacquire_max_distance = ctx.lengths.reacquire_max_distance;
    tracking.reacquire_below = static_cast<float>(tuning.reacquire_below);
    tracking.reacquire_gain = static_cast<float>(tuning.reacquire_gain);
    tracking.reacquire_min_vertices = tuning.reacquire_min_vertices;
  }
  return tracking;
}

/// One key group's tracking: the trackers, the fit meter and what the runs from the key frame
/// (backwards, then forwards) share.
class KeyGroupTracking {
 public:
  KeyGroupTracking(const EncodeContext& ctx, const BaseTopology& topology,
                   const DeformationGraph& graph, const RegularSubdivision& lattice, int first,
                   int key, bool may_cut, const MotionHint& hint, TrackingTargets* targets,
                   KeyGroupAnalysis* analysis)
      : ctx_(ctx),
        first_(first),
        key_(key),
        may_cut_(may_cut),
        targets_(*targets),
        proxies_(targets->proxies()),
        analysis_(*analysis),
        tracking_options_(TrackingOptions(ctx)),
        tracker_(topology, graph, tracking_options_),
        meter_(analysis->base, analysis->motion, lattice, ctx.lengths.detail_max_distance,
               ctx.lengths.max_distance, /*judge_across=*/true),
        identity_(graph.node_count()),
        observed_(analysis->base.vertex_count(), 0) {
    // The key group's second frame is also solved at the set rigidity throughout (FirstStep).
    DeformationTrackingOptions supple = tracking_options_;
    if (supple.coarse_stiffness > 1) {
      supple.coarse_stiffness = 1;
      supple_tracker_.emplace(topology, graph, supple);
    }
    // The frame after the key frame, moving on as the surface moved into the key frame.
    if (hint.frame == key) hinted_before_ = StepsBefore(hint, analysis->base, analysis->motion);
    const FrameProxy& key_frame = proxies_[key];
    key_fit_ = meter_.Measure(identity_, key_frame);
    KeyGroupSummary& summary = analysis->summary;
    summary.key_frame_unexplained = summary.worst_unexplained = key_fit_.unexplained_share;
    summary.key_frame_seen_through = key_fit_.seen_through_share;
    ClearCut(&summary);
    if (key_frame.target) {
      ObserveVertices(ctx, analysis->base, analysis->motion, *key_frame.target, identity_,
                      &observed_);
    }
  }

  const std::vector<RigidTransform>& identity() const { return identity_; }
  const std::vector<char>& observed() const { return observed_; }

  /// Tracks the frames from the key frame's neighbour in `direction` (+1 forwards, -1
  /// backwards) to `last` (included) while the posed base explains them (all of them when the
  /// key group may not be cut), their poses appended to `run` in that order. Returns whether a
  /// frame was not explained (its figures recorded as the cut).
  StatusOr<bool> TrackRun(int direction, int last, std::vector<std::vector<RigidTransform>>* run);

 private:
  /// What frame t is tracked to: the frame fused (closed where no view saw it, as a key
  /// frame's base would be), or its views' proxy (TrackingTargets::DataOf). Loaded once: the
  /// second frame looks ahead.
  StatusOr<TrackingData> DataOf(int t) { return targets_.DataOf(t); }
  /// What a fresh base fused from frame `t` would lose of the key group's surface posed by
  /// `track` (MeasureForgottenSurface against the frame's fused surface, or its proxy's
  /// points when frames are not fused for tracking).
  ForgottenSurface Forgotten(int t, std::span<const RigidTransform> track) const;

  /// The first frame from the key frame, `t`, which has no velocity of its own to predict
  /// from; `stiff` is its stiff solve. Solved stiff at first, a fast part moves as a whole; at
  /// the set rigidity throughout, a waving sheet bends from the start; forwards from a key
  /// frame that ended the key group before, its nodes also move on as the surface moved into
  /// the key frame. These may explain this frame alike (a sheet that slid along itself still
  /// lies on its data) and part at the next, tracked from each: the start whose next frame
  /// leaves less of the data unexplained and less of the surface seen through is kept, the
  /// first on a tie (without a next frame there is no supple start, and the better of the
  /// others on this frame is kept). The next frame's pose from the kept start goes to
  /// `looked_ahead`.
  Status FirstStep(int t, int direction, const TrackingData& data,
                   std::vector<RigidTransform>* stiff, DeformationTrackStats* stiff_stats,
                   std::optional<std::vector<RigidTransform>>* looked_ahead,
                   int* looked_ahead_reacquired);

  const EncodeContext& ctx_;
  const int first_, key_;
  const bool may_cut_;
  TrackingTargets& targets_;
  ProxyCache& proxies_;
  KeyGroupAnalysis& analysis_;
  /// The tracker's settings for this encode (TrackingOptions).
  const DeformationTrackingOptions tracking_options_;
  const DeformationTracker tracker_;
  std::optional<DeformationTracker> supple_tracker_;
  FitMeter meter_;
  const std::vector<RigidTransform> identity_;
  std::vector<RigidTransform> hinted_before_;
  DataFit key_fit_;
  std::vector<char> observed_;
};

ForgottenSurface KeyGroupTracking::Forgotten(int t, std::span<const RigidTransform> track) const {
  const FusedFrame* fused = targets_.Fused(t);
  const FrameProxy& proxy = proxies_.at(t);
  const std::span<const Eigen::Vector3f> surface =
      fused != nullptr ? std::span<const Eigen::Vector3f>(fused->mesh.positions)
                       : std::span<const Eigen::Vector3f>(proxy.points);
  return MeasureForgottenSurface(ctx_, analysis_.base, analysis_.motion, track, observed_, surface,
                                 proxy.free_space.get());
}

Status KeyGroupTracking::FirstStep(int t, int direction, const TrackingData& data,
                                   std::vector<RigidTransform>* stiff,
                                   DeformationTrackStats* stiff_stats,
                                   std::optional<std::vector<RigidTransform>>* looked_ahead,
                                   int* looked_ahead_reacquired) {
  const int ahead_frame = t + direction;
  const bool has_ahead = ahead_frame >= first_ && ahead_frame < ctx_.end;
  std::vector<std::vector<RigidTransform>> starts;
  std::vector<DeformationTrackStats> starts_stats;
  starts.push_back(std::move(*stiff));
  starts_stats.push_back(*stiff_stats);
  if (supple_tracker_ && has_ahead) {
    starts_stats.emplace_back();
    starts.push_back(supple_tracker_->Track(data, identity_, {}, &starts_stats.back()));
  }
  if (direction > 0 && !hinted_before_.empty()) {
    starts_stats.emplace_back();
    starts.push_back(tracker_.Track(data, identity_, hinted_before_, &starts_stats.back()));
  }
  std::size_t chosen = 0;
  if (starts.size() > 1) {
    std::optional<TrackingData> ahead;
    if (has_ahead) {
      MESHVID_ASSIGN_OR_RETURN(ahead, DataOf(ahead_frame));
    }
    const FrameProxy& proxy = proxies_[t];
    double best_miss = std::numeric_limits<double>::infinity();
    std::vector<RigidTransform> best_ahead;
    DeformationTrackStats best_ahead_stats;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      const DataFit fit = meter_.Measure(starts[k], proxy);
      if (may_cut_ && !TrackedFrameExplained(ctx_, key_fit_, fit)) continue;
      double miss = DataMiss(fit);
      std::vector<RigidTransform> ahead_pose;
      DeformationTrackStats ahead_stats;
      if (has_ahead) {
        ahead_pose = tracker_.Track(*ahead, starts[k], identity_, &ahead_stats);
        miss = DataMiss(meter_.Measure(ahead_pose, proxies_[ahead_frame]));
      }
      if (miss < best_miss) {
        best_miss = miss;
        chosen = k;
        best_ahead = std::move(ahead_pose);
        best_ahead_stats = ahead_stats;
      }
    }
    if (std::isfinite(best_miss) && has_ahead) {
      *looked_ahead = std::move(best_ahead);
      *looked_ahead_reacquired = best_ahead_stats.reacquired;
    }
  }
  *stiff = std::move(starts[chosen]);
  *stiff_stats = starts_stats[chosen];
  return Status::Ok();
}

StatusOr<bool> KeyGroupTracking::TrackRun(int direction, int last,
                                          std::vector<std::vector<RigidTransform>>* run) {
  KeyGroupSummary& summary = analysis_.summary;
  // A frame's pose already tracked while looking ahead from the one before, and the lost
  // parts its tracking found again.
  std::optional<std::vector<RigidTransform>> looked_ahead;
  int looked_ahead_reacquired = 0;
  for (int t = key_ + direction; direction * (last - t) >= 0; t += direction) {
    if (!ReportProgress(ctx_.progress, "tracking", t, ctx_.end)) return Cancelled();
    if (direction > 0) targets_.DropBefore(t);  // the frames behind are done with
    MESHVID_ASSIGN_OR_RETURN(const TrackingData data, DataOf(t));
    if (direction * (last - (t + direction)) >= 0) {
      MESHVID_RETURN_IF_ERROR(targets_.StartMaking(t + direction));
    }
    const FrameProxy& proxy = proxies_[t];
    const std::vector<RigidTransform>& previous = run->empty() ? identity_ : run->back();
    const std::span<const RigidTransform> before =
        run->size() >= 2   ? std::span<const RigidTransform>((*run)[run->size() - 2])
        : run->size() == 1 ? std::span<const RigidTransform>(identity_)
                           : std::span<const RigidTransform>();
    std::vector<RigidTransform> next;
    DeformationTrackStats next_stats;
    if (looked_ahead) {
      next = *std::move(looked_ahead);
      next_stats.reacquired = looked_ahead_reacquired;
      looked_ahead.reset();
    } else {
      next = tracker_.Track(data, previous, before, &next_stats);
    }
    if (run->empty()) {
      MESHVID_RETURN_IF_ERROR(FirstStep(t, direction, data, &next, &next_stats, &looked_ahead,
                                        &looked_ahead_reacquired));
    }
    const DataFit fit = meter_.Measure(next, proxy);
    // The surface a fresh base would lose is measured only where the data alone would end the
    // key group: it can only keep a frame.
    const ForgottenSurface forgotten =
        TrackedFrameExplained(ctx_, key_fit_, fit) ? ForgottenSurface{} : Forgotten(t, next);
    if (may_cut_) {
      if (!KeepTrackedFrame(ctx_, key_fit_, fit, forgotten, &summary)) {
        if (direction > 0) {
          analysis_.hint = HintOf(t, analysis_.base, analysis_.motion, previous, next);
        }
        return true;
      }
    } else {
      RecordHeldFrame(ctx_, key_fit_, fit, forgotten, t, &summary);
    }
    if (proxy.target) {
      ObserveVertices(ctx_, analysis_.base, analysis_.motion, *proxy.target, next, &observed_);
    }
    summary.reacquired_parts += next_stats.reacquired;
    run->push_back(std::move(next));
  }
  return false;
}

}  // namespace

Status TrackDeformedKeyGroup(const EncodeContext& ctx, const BaseTopology& topology, int first,
                             int key, bool may_cut, const MotionHint& hint,
                             TrackingTargets* targets, KeyGroupAnalysis* analysis) {
  const EncoderOptions& options = ctx.options;
  const TriangleMesh& base = analysis->base;
  KeyGroupSummary& summary = analysis->summary;
  MESHVID_ASSIGN_OR_RETURN(
      const DeformationGraph graph,
      BuildDeformationGraph(
          topology, ctx.lengths.node_spacing,
          static_cast<float>(options.tuning.deform_join_pieces * ctx.lengths.node_spacing)));
  analysis->motion = graph.motion;
  const int nodes = static_cast<int>(graph.node_count());
  summary.segments = nodes;
  summary.key_frame = key;
  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice,
                           RegularSubdivision::Create(base, std::min(options.levels, 2)));
  KeyGroupTracking tracking(ctx, topology, graph, lattice, first, key, may_cut, hint, targets,
                            analysis);
  std::vector<std::vector<RigidTransform>> backwards, forwards;
  MESHVID_ASSIGN_OR_RETURN(const bool lost_before_key, tracking.TrackRun(-1, first, &backwards));
  if (lost_before_key) {
    ClearCut(&summary);
    summary.frames = 0;
    return Status::Ok();
  }
  // Where a frame ends the key group, its figures are in the summary.
  MESHVID_RETURN_IF_ERROR(tracking.TrackRun(+1, ctx.end - 1, &forwards).status());
  auto& tracks = analysis->tracks;
  tracks.assign(std::make_move_iterator(backwards.rbegin()),
                std::make_move_iterator(backwards.rend()));
  tracks.push_back(tracking.identity());
  tracks.insert(tracks.end(), std::make_move_iterator(forwards.begin()),
                std::make_move_iterator(forwards.end()));
  summary.frames = static_cast<int>(tracks.size());
  targets->DropBefore(first + summary.frames);
  summary.rigid_groups = nodes;
  if (options.tuning.deform_rigid_group_factor > 0) {
    const RigidNodeGroups groups = FindRigidNodeGroups(
        base.positions, graph.motion, graph.adjacent, tracks,
        static_cast<float>(options.tuning.deform_rigid_group_factor * ctx.lengths.tolerance));
    ApplyRigidNodeGroups(groups, &tracks);
    summary.rigid_groups = groups.group_count;
  }
  MarkSurface(ctx, base, tracking.observed(), &analysis->motion, &summary);
  return Status::Ok();
}

}  // namespace meshvid
