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

Status TrackDeformedKeyGroup(const EncodeContext& ctx, const BaseTopology& topology, int first,
                             int key, bool may_cut, const MotionHint& hint, ProxyCache* proxies,
                             FusedFrames* fused_frames, KeyGroupAnalysis* analysis) {
  const EncoderOptions& options = ctx.options;
  const TriangleMesh& base = analysis->base;
  KeyGroupSummary& summary = analysis->summary;
  MESHVID_ASSIGN_OR_RETURN(const DeformationGraph graph,
                           BuildDeformationGraph(topology, ctx.lengths.node_spacing));
  analysis->motion = graph.motion;
  const int nodes = static_cast<int>(graph.node_count());
  summary.segments = nodes;
  summary.key_frame = key;
  DeformationTrackingOptions tracking;
  tracking.max_distance = ctx.lengths.max_distance;
  tracking.tolerance = ctx.lengths.tolerance;
  tracking.min_normal_cos = ctx.shot.min_abs_cos;
  tracking.rigidity = options.tuning.deform_rigidity;
  tracking.coarse_stiffness = options.tuning.deform_coarse_stiffness;
  tracking.point_weight = options.tuning.deform_point_weight;
  tracking.iterations = options.tuning.deform_iterations;
  tracking.first_iterations = options.tuning.deform_first_iterations;
  if (options.tuning.deform_reacquire) {
    tracking.reacquire_max_distance = ctx.lengths.reacquire_max_distance;
    tracking.reacquire_below = static_cast<float>(options.tuning.reacquire_below);
    tracking.reacquire_gain = static_cast<float>(options.tuning.reacquire_gain);
    tracking.reacquire_min_vertices = options.tuning.reacquire_min_vertices;
  }
  const DeformationTracker tracker(topology, graph, tracking);
  // The key group's second frame is also solved at the set rigidity throughout (see below).
  DeformationTrackingOptions supple_tracking = tracking;
  supple_tracking.coarse_stiffness = 1;
  std::optional<DeformationTracker> supple_tracker;
  if (tracking.coarse_stiffness > 1) supple_tracker.emplace(topology, graph, supple_tracking);

  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice,
                           RegularSubdivision::Create(base, std::min(options.levels, 2)));
  FitMeter meter(base, analysis->motion, lattice, ctx.lengths.detail_max_distance,
                 ctx.lengths.max_distance, /*judge_across=*/true);
  const std::vector<RigidTransform> identity(nodes);
  // The frame after the key frame, moving on as the surface moved into the key frame.
  const std::vector<RigidTransform> hinted_before =
      hint.frame == key ? StepsBefore(hint, base, analysis->motion) : std::vector<RigidTransform>();
  const FrameProxy& key_frame = (*proxies)[key];
  const DataFit key_fit = meter.Measure(identity, key_frame);
  summary.key_frame_unexplained = summary.worst_unexplained = key_fit.unexplained_share;
  summary.key_frame_seen_through = key_fit.seen_through_share;
  ClearCut(&summary);
  std::vector<char> observed(base.vertex_count(), 0);
  if (key_frame.target) {
    ObserveVertices(ctx, base, analysis->motion, *key_frame.target, identity, &observed);
  }
  // What frame t is tracked to: the frame fused (closed where no view saw it, as a key
  // frame's base would be), or its views' proxy. Loaded once: the second frame looks ahead.
  auto tracking_data = [&](int t) -> StatusOr<TrackingData> {
    const bool track_fused = options.tuning.deform_track_fused;
    if (track_fused && fused_frames->count(t) > 0) {
      const PointsWithNormals& fused = fused_frames->at(t);
      return TrackingData{fused.positions, fused.normals};
    }
    if (!track_fused && proxies->count(t) > 0) {
      return TrackingData{proxies->at(t).points, proxies->at(t).normals};
    }
    // The frame's views, loaded once for whichever of the proxy and the fused target needs them.
    MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh> views, ctx.source.LoadFrame(t));
    if (proxies->count(t) == 0) {
      MESHVID_ASSIGN_OR_RETURN((*proxies)[t], BuildProxy(ctx, views));
    }
    if (!track_fused) return TrackingData{proxies->at(t).points, proxies->at(t).normals};
    MESHVID_ASSIGN_OR_RETURN(TriangleMesh fused,
                             FuseFrame(ctx, views, options.tuning.base_fusion_points));
    PointsWithNormals& kept = (*fused_frames)[t];
    kept.normals = ComputeVertexNormals(fused);
    kept.positions = std::move(fused.positions);
    return TrackingData{kept.positions, kept.normals};
  };
  // Tracks the frames from the key frame's neighbour in `direction` (+1 forwards, -1
  // backwards) to `last` (included) while the posed base explains them (all of them when the
  // key group may not be cut), their poses appended to `run` in that order. Returns whether a
  // frame was not explained (its figures recorded as the cut).
  auto track_run = [&](int direction, int last,
                       std::vector<std::vector<RigidTransform>>* run) -> StatusOr<bool> {
    // A frame's pose already tracked while looking ahead from the one before, and the lost
    // parts its tracking found again.
    std::optional<std::vector<RigidTransform>> looked_ahead;
    int looked_ahead_reacquired = 0;
    for (int t = key + direction; direction * (last - t) >= 0; t += direction) {
      if (!ReportProgress(ctx.progress, "tracking", t, ctx.end)) return Cancelled();
      if (direction > 0) {  // the frames behind are done with
        proxies->erase(proxies->begin(), proxies->lower_bound(t));
        fused_frames->erase(fused_frames->begin(), fused_frames->lower_bound(t));
      }
      MESHVID_ASSIGN_OR_RETURN(const TrackingData data, tracking_data(t));
      const FrameProxy& proxy = (*proxies)[t];
      const std::vector<RigidTransform>& previous = run->empty() ? identity : run->back();
      const std::span<const RigidTransform> before =
          run->size() >= 2   ? std::span<const RigidTransform>((*run)[run->size() - 2])
          : run->size() == 1 ? std::span<const RigidTransform>(identity)
                             : std::span<const RigidTransform>();
      std::vector<RigidTransform> next;
      DeformationTrackStats next_stats;
      if (looked_ahead) {
        next = *std::move(looked_ahead);
        next_stats.reacquired = looked_ahead_reacquired;
        looked_ahead.reset();
      } else {
        next = tracker.Track(data, previous, before, &next_stats);
      }
      const int ahead_frame = t + direction;
      if (run->empty()) {
        // The first frame from the key frame has no velocity of its own to predict from.
        // Solved stiff at first, a fast part moves as a whole; at the set rigidity throughout,
        // a waving sheet bends from the start; forwards from a key frame that ended the key
        // group before, its nodes also move on as the surface moved into the key frame. These
        // may explain this frame alike (a sheet that slid along itself still lies on its data)
        // and part at the next, tracked from each: the start whose next frame leaves less of
        // the data unexplained and less of the surface seen through is kept, the first on a
        // tie (without a next frame there is no supple start, and the better of the others on
        // this frame is kept).
        const bool has_ahead = ahead_frame >= first && ahead_frame < ctx.end;
        std::vector<std::vector<RigidTransform>> starts;
        std::vector<DeformationTrackStats> starts_stats;
        starts.push_back(std::move(next));
        starts_stats.push_back(next_stats);
        if (supple_tracker && has_ahead) {
          starts_stats.emplace_back();
          starts.push_back(supple_tracker->Track(data, previous, {}, &starts_stats.back()));
        }
        if (direction > 0 && !hinted_before.empty()) {
          starts_stats.emplace_back();
          starts.push_back(tracker.Track(data, previous, hinted_before, &starts_stats.back()));
        }
        std::size_t chosen = 0;
        if (starts.size() > 1) {
          std::optional<TrackingData> ahead;
          if (has_ahead) {
            MESHVID_ASSIGN_OR_RETURN(ahead, tracking_data(ahead_frame));
          }
          double best_miss = std::numeric_limits<double>::infinity();
          std::vector<RigidTransform> best_ahead;
          DeformationTrackStats best_ahead_stats;
          for (std::size_t k = 0; k < starts.size(); ++k) {
            const DataFit fit = meter.Measure(starts[k], proxy);
            if (may_cut && !TrackedFrameExplained(ctx, key_fit, fit)) continue;
            double miss = DataMiss(fit);
            std::vector<RigidTransform> ahead_pose;
            DeformationTrackStats ahead_stats;
            if (has_ahead) {
              ahead_pose = tracker.Track(*ahead, starts[k], previous, &ahead_stats);
              miss = DataMiss(meter.Measure(ahead_pose, (*proxies)[ahead_frame]));
            }
            if (miss < best_miss) {
              best_miss = miss;
              chosen = k;
              best_ahead = std::move(ahead_pose);
              best_ahead_stats = ahead_stats;
            }
          }
          if (std::isfinite(best_miss) && has_ahead) {
            looked_ahead = std::move(best_ahead);
            looked_ahead_reacquired = best_ahead_stats.reacquired;
          }
        }
        next = std::move(starts[chosen]);
        next_stats = starts_stats[chosen];
      }
      if (may_cut) {
        if (!KeepTrackedFrame(ctx, key_fit, meter.Measure(next, proxy), &summary)) {
          if (direction > 0) analysis->hint = HintOf(t, base, analysis->motion, previous, next);
          return true;
        }
      } else {
        RecordHeldFrame(ctx, key_fit, meter.Measure(next, proxy), t, &summary);
      }
      if (proxy.target) {
        ObserveVertices(ctx, base, analysis->motion, *proxy.target, next, &observed);
      }
      summary.reacquired_parts += next_stats.reacquired;
      run->push_back(std::move(next));
    }
    return false;
  };
  std::vector<std::vector<RigidTransform>> backwards, forwards;
  MESHVID_ASSIGN_OR_RETURN(const bool lost_before_key, track_run(-1, first, &backwards));
  if (lost_before_key) {
    ClearCut(&summary);
    summary.frames = 0;
    return Status::Ok();
  }
  // Where a frame ends the key group, its figures are in the summary.
  MESHVID_RETURN_IF_ERROR(track_run(+1, ctx.end - 1, &forwards).status());
  auto& tracks = analysis->tracks;
  tracks.assign(std::make_move_iterator(backwards.rbegin()),
                std::make_move_iterator(backwards.rend()));
  tracks.push_back(identity);
  tracks.insert(tracks.end(), std::make_move_iterator(forwards.begin()),
                std::make_move_iterator(forwards.end()));
  summary.frames = static_cast<int>(tracks.size());
  proxies->erase(proxies->begin(), proxies->lower_bound(first + summary.frames));
  summary.rigid_groups = nodes;
  if (options.tuning.deform_rigid_group_factor > 0) {
    const RigidNodeGroups groups = FindRigidNodeGroups(
        base.positions, graph.motion, graph.adjacent, tracks,
        static_cast<float>(options.tuning.deform_rigid_group_factor * ctx.lengths.tolerance));
    ApplyRigidNodeGroups(groups, &tracks);
    summary.rigid_groups = groups.group_count;
  }
  MarkSurface(ctx, base, observed, &analysis->motion, &summary);
  return Status::Ok();
}

}  // namespace meshvid
