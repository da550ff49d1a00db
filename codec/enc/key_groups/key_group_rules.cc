#include "codec/enc/key_groups/key_group_rules.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "codec/common/point_tree.h"
#include "codec/enc/fusion/surface_fusion.h"

namespace meshvid {

bool TrackedFrameExplained(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                           const ForgottenSurface& forgotten) {
  return StillExplains(key_fit, fit, ctx.lengths.detail_max_distance, RebaseGainDb(ctx.options),
                       ctx.lengths.farthest_growth, forgotten,
                       ctx.options.tuning.rebase_forgotten_excuse_db);
}

bool KeepTrackedFrame(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                      const ForgottenSurface& forgotten, KeyGroupSummary* summary) {
  const double loss_db = TrackingLossDb(key_fit, fit, ctx.lengths.detail_max_distance, forgotten);
  if (!TrackedFrameExplained(ctx, key_fit, fit, forgotten)) {
    // Where the lost surface offset the loss within the gain, the loss at the data past the
    // offset's limit ended the key group (or the farthest growth, recorded beside it).
    summary->cut_loss_db = loss_db <= RebaseGainDb(ctx.options)
                               ? TrackingLossDb(key_fit, fit, ctx.lengths.detail_max_distance)
                               : loss_db;
    summary->cut_unexplained = fit.unexplained_share;
    summary->cut_seen_through = fit.seen_through_share;
    summary->cut_farthest_growth = fit.farthest_from_data - key_fit.farthest_from_data;
    return false;
  }
  summary->worst_unexplained = std::max(summary->worst_unexplained, fit.unexplained_share);
  summary->worst_loss_db = std::max(summary->worst_loss_db, loss_db);
  return true;
}

void RecordHeldFrame(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                     const ForgottenSurface& forgotten, int frame, KeyGroupSummary* summary) {
  const double loss_db = TrackingLossDb(key_fit, fit, ctx.lengths.detail_max_distance, forgotten);
  summary->worst_unexplained = std::max(summary->worst_unexplained, fit.unexplained_share);
  summary->worst_loss_db = std::max(summary->worst_loss_db, loss_db);
  if (!TrackedFrameExplained(ctx, key_fit, fit, forgotten)) {
    summary->held_frames.push_back({frame, loss_db, fit.unexplained_share, fit.seen_through_share});
  }
}

ForgottenSurface MeasureForgottenSurface(const EncodeContext& ctx, const TriangleMesh& base,
                                         const MotionModel& motion,
                                         std::span<const RigidTransform> track,
                                         const std::vector<char>& observed,
                                         std::span<const Eigen::Vector3f> frame_surface,
                                         const SeenFreeSpace* free_space) {
  const double range = ctx.lengths.detail_max_distance;
  const double cap = ctx.options.tuning.rebase_forgotten_reach * range;
  // Without cameras nothing tells surface the views lost from surface the subject left (a
  // teleported block's old place): no surface counts as lost.
  if (cap <= 0 || frame_surface.empty() || free_space == nullptr) return {};
  std::vector<Eigen::Vector3f> posed, normals;
  PoseVertices(motion, track, base.positions, &posed);
  ComputeVertexNormals(posed, base.triangles, &normals);
  const PointCloud cloud{frame_surface};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  struct Sums {
    std::size_t observed = 0, forgotten = 0;
    double squares = 0;
  };
  // Deterministic: the sums feed the key-group decision, which must not depend on the threads.
  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, posed.size(), 1024), Sums{},
      [&](const tbb::blocked_range<std::size_t>& vertices, Sums partial) {
        for (std::size_t v = vertices.begin(); v != vertices.end(); ++v) {
          if (v >= observed.size() || !observed[v]) continue;
          ++partial.observed;
          std::uint32_t nearest = 0;
          float squared = 0;
          tree.knnSearch(posed[v].data(), 1, &nearest, &squared);
          const double distance = std::sqrt(double(squared));
          if (distance <= range) continue;
          if (free_space->Judge(posed[v], normals[v], float(range),
                                /*across_too=*/true) == SeenFreeSpace::Verdict::kSeenThrough) {
            continue;
          }
          ++partial.forgotten;
          partial.squares += std::min(distance, cap) * std::min(distance, cap);
        }
        return partial;
      },
      [](Sums a, const Sums& b) {
        a.observed += b.observed;
        a.forgotten += b.forgotten;
        a.squares += b.squares;
        return a;
      });
  if (sums.observed == 0 || sums.forgotten == 0) return {};
  return {double(sums.forgotten) / double(sums.observed), sums.squares / double(sums.forgotten)};
}

void ClearCut(KeyGroupSummary* summary) {
  summary->cut_unexplained = summary->cut_seen_through = summary->cut_farthest_growth =
      summary->cut_loss_db = -1;
}

StatusOr<TriangleMesh> FuseFrame(const EncodeContext& ctx, const std::vector<TriangleMesh>& views,
                                 std::size_t fusion_points) {
  SurfaceFusionOptions fusion_options;
  fusion_options.max_points = fusion_points;
  fusion_options.voxel_scale = ctx.options.tuning.base_voxel_scale;
  fusion_options.max_extension_spacings = ctx.options.tuning.base_max_extension;
  fusion_options.view_cameras = ctx.view_cameras;
  return FuseRangeMeshes(views, fusion_options, ctx.progress);
}

void ObserveVertices(const EncodeContext& ctx, const TriangleMesh& base,
                     const MotionModel& motion, const ShootingTarget& target,
                     std::span<const RigidTransform> track, std::vector<char>* observed) {
  std::vector<Eigen::Vector3f> posed, normals;
  ShotLimits limits = ctx.shot;
  limits.max_distance = ctx.lengths.detail_max_distance;
  PoseVertices(motion, track, base.positions, &posed);
  ComputeVertexNormals(posed, base.triangles, &normals);
  observed->resize(base.vertex_count(), 0);
  tbb::parallel_for(std::size_t(0), posed.size(), [&](std::size_t v) {
    if (!(*observed)[v] && !std::isnan(target.Shoot(posed[v], normals[v], limits))) {
      (*observed)[v] = 1;
    }
  });
}

void MarkSurface(const EncodeContext& ctx, const TriangleMesh& base,
                 const std::vector<char>& observed, MotionModel* motion,
                 KeyGroupSummary* summary) {
  motion->surface_triangles.resize(base.triangle_count());
  std::size_t surface = 0;
  for (std::size_t i = 0; i < base.triangle_count(); ++i) {
    const Triangle& tri = base.triangles[i];
    const int seen = observed[tri[0]] + observed[tri[1]] + observed[tri[2]];
    motion->surface_triangles[i] = seen >= 2;
    surface += seen >= 2;
  }
  summary->surface_share = double(surface) / double(base.triangle_count());
  if (!ctx.options.hide_unseen) motion->surface_triangles.clear();
}

DataFit FitMeter::Measure(const std::vector<RigidTransform>& transforms, const FrameProxy& frame) {
  PoseVertices(motion_, transforms, base_.positions, &posed_);
  ComputeVertexNormals(posed_, base_.triangles, &normals_);
  EvaluateSampleFrames(lattice_, lattice_.levels(), posed_, normals_, &samples_, &directions_);
  DataFit fit = MeasureDataFit(samples_, frame.points, distance_, stray_distance_,
                               directions_, SampleReach(samples_, triangles_));
  if (frame.free_space && !samples_.empty()) {
    // Farther in front of what a camera saw than a displacement reaches (along the normal,
    // or past the edge of a view's data across the image), among the samples some camera
    // can judge (a one-view rig judges fewer than a ring).
    struct Counts {
      std::size_t judged = 0, seen_through = 0;
    };
    const Counts counts = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, samples_.size(), 2048), Counts{},
        [&](const tbb::blocked_range<std::size_t>& range, Counts partial) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const SeenFreeSpace::Verdict verdict =
                frame.free_space->Judge(samples_[i], directions_[i], distance_,
                                        judge_across_);
            partial.judged += verdict != SeenFreeSpace::Verdict::kUnjudged;
            partial.seen_through += verdict == SeenFreeSpace::Verdict::kSeenThrough;
          }
          return partial;
        },
        [](Counts a, const Counts& b) {
          a.judged += b.judged;
          a.seen_through += b.seen_through;
          return a;
        });
    if (counts.judged > 0) {
      fit.seen_through_share = double(counts.seen_through) / double(counts.judged);
    }
  }
  return fit;
}

}  // namespace meshvid
