#include "codec/enc/key_groups/key_group_analysis.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <string>

#include <tbb/parallel_for.h>

#include "codec/common/point_tree.h"
#include "codec/common/subdivision.h"
#include "codec/enc/fusion/decimation.h"
#include "codec/enc/fusion/surface_fusion.h"
#include "codec/enc/key_groups/deformed_key_group.h"
#include "codec/enc/key_groups/key_group_rules.h"
#include "codec/enc/key_groups/tracking_targets.h"
#include "codec/enc/tracking/closest_point_align.h"
#include "codec/enc/tracking/data_fit.h"

namespace meshvid {

Status Cancelled() { return CancelledError("encode cancelled"); }

EncodeContext WithoutProgress(const EncodeContext& ctx) {
  static const ProgressCallback kNoProgress;
  return EncodeContext{ctx.source, ctx.options, kNoProgress,     ctx.lengths,
                       ctx.shot,   ctx.end,     ctx.view_cameras};
}

StatusOr<FrameProxy> BuildProxy(const EncodeContext& ctx, const std::vector<TriangleMesh>& views,
                                bool free_space) {
  const double fraction = ctx.options.tuning.proxy_fraction;
  std::vector<StatusOr<TriangleMesh>> decimated(views.size(), TriangleMesh{});
  tbb::parallel_for(std::size_t(0), views.size(), [&](std::size_t v) {
    if (views[v].empty()) return;
    DecimationOptions options;
    options.target_vertices = std::max<std::size_t>(
        16, static_cast<std::size_t>(fraction * double(views[v].vertex_count())));
    options.max_edge_length = ctx.lengths.proxy_max_edge;
    decimated[v] = options.target_vertices >= views[v].vertex_count()
                       ? StatusOr<TriangleMesh>(views[v])
                       : DecimateMesh(views[v], options);
  });
  TriangleMesh proxy;
  for (auto& view : decimated) {
    if (!view.ok()) return view.status();
    AppendMesh(*view, &proxy);
  }
  FrameProxy result;
  if (proxy.empty()) return result;
  if (free_space && !ctx.view_cameras.empty()) {
    auto seen = std::make_shared<const SeenFreeSpace>(views, ctx.view_cameras, /*margin_pixels=*/0,
                                                      /*min_facing_cosine=*/0.5f,
                                                      kFreeSpacePixelBlock);
    if (seen->view_count() > 0) result.free_space = std::move(seen);
  }
  MESHVID_ASSIGN_OR_RETURN(result.target, ShootingTarget::Create(proxy));
  result.normals = ComputeVertexNormals(proxy);
  result.points = std::move(proxy.positions);
  return result;
}

Eigen::AlignedBox3f BoxOf(const std::vector<TriangleMesh>& views) {
  Eigen::AlignedBox3f box;
  for (const TriangleMesh& view : views) box.extend(BoundingBox(view));
  return box;
}

namespace {

/// The fit of a frame's points to its unposed base (sampled on lattice level <= 2).
StatusOr<DataFit> FitOfBase(const TriangleMesh& base, int levels,
                            const std::vector<Eigen::Vector3f>& points, float distance) {
  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice,
                           RegularSubdivision::Create(base, std::min(levels, 2)));
  std::vector<Eigen::Vector3f> samples, directions;
  EvaluateSampleFrames(lattice, lattice.levels(), base.positions, ComputeVertexNormals(base),
                       &samples, &directions);
  return MeasureDataFit(samples, points, distance, std::numeric_limits<float>::infinity(),
                        directions, SampleReach(samples, lattice.Triangles(lattice.levels())));
}

/// A key group's base mesh: the user's, rigidly fitted to the key frame's data points
/// (`points`, its proxy's), or the key frame's fused views (at most `fusion_points` of them;
/// `fused` when given, that fusion made already) decimated.
StatusOr<TriangleMesh> MakeBaseMesh(const EncodeContext& ctx,
                                    const std::vector<TriangleMesh>& views,
                                    std::span<const Eigen::Vector3f> points,
                                    std::size_t fusion_points, const TriangleMesh* fused_views) {
  const EncoderOptions& options = ctx.options;
  if (options.base_mesh) {
    TriangleMesh base = *options.base_mesh;
    MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "the base mesh"));
    base.normals.clear();
    if (!points.empty()) {
      const PointCloud cloud{points};
      const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
      std::vector<std::uint32_t> members(base.vertex_count());
      std::iota(members.begin(), members.end(), 0u);
      const RigidTransform fitted =
          ClosestPointAlign(tree, points, base.positions, members, ctx.lengths.max_distance,
                            2 * ctx.lengths.tolerance, RigidTransform{});
      for (auto& p : base.positions) p = fitted.Apply(p);
    }
    return base;
  }
  TriangleMesh fused;
  if (fused_views != nullptr) {
    fused = *fused_views;
  } else {
    MESHVID_ASSIGN_OR_RETURN(fused, FuseFrame(ctx, views, fusion_points));
  }
  // Lower qualities divide the target by the coarsening and multiply the bounds by its square.
  const double coarsening = BaseCoarsening(options.quality);
  const double bounds = coarsening * coarsening;
  DecimationOptions decimation;
  decimation.target_vertices = std::max<std::size_t>(
      4, static_cast<std::size_t>(std::lround(options.base_vertices / coarsening)));
  decimation.max_error = static_cast<float>(bounds) * ctx.lengths.base_max_error;
  decimation.max_normal_deviation_degrees =
      std::min(180.0, bounds * options.tuning.base_max_normal_deviation_degrees);
  decimation.max_edge_length = static_cast<float>(bounds) * ctx.lengths.base_max_edge;
  TriangleMesh base = std::move(fused);
  if (base.vertex_count() > decimation.target_vertices) {
    MESHVID_ASSIGN_OR_RETURN(base, DecimateMesh(base, decimation));
  }
  // One vertex per fan, as the base mesh coder keeps them (its vertex order found again).
  SplitNonManifoldVertices(&base);
  return base;
}

}  // namespace

StatusOr<TriangleMesh> MakeKeyFrameBase(const EncodeContext& ctx,
                                        const std::vector<TriangleMesh>& views,
                                        const FrameProxy& proxy, const TriangleMesh* fused) {
  const SurfaceFusionOptions defaults;
  const std::size_t fast = std::min(ctx.options.tuning.base_fusion_points, defaults.max_points);
  // `fused` is FuseFrame's from base_fusion_points: it serves where that is the fast fusion.
  const bool made = fused != nullptr && fast == ctx.options.tuning.base_fusion_points;
  StatusOr<TriangleMesh> base =
      MakeBaseMesh(ctx, views, proxy.points, fast, made ? fused : nullptr);
  if (ctx.options.base_mesh || fast >= defaults.max_points) return base;
  double unexplained = 1;
  if (base.ok()) {
    MESHVID_ASSIGN_OR_RETURN(const DataFit fit, FitOfBase(*base, ctx.options.levels, proxy.points,
                                                          ctx.lengths.detail_max_distance));
    unexplained = fit.unexplained_share;
    if (unexplained <= kMostUnexplainedAtKeyFrame) return base;
  }
  StatusOr<TriangleMesh> careful =
      MakeBaseMesh(ctx, views, proxy.points, defaults.max_points, nullptr);
  if (!careful.ok()) return base.ok() ? base : careful;
  if (!base.ok()) return careful;
  MESHVID_ASSIGN_OR_RETURN(const DataFit fit, FitOfBase(*careful, ctx.options.levels,
                                                        proxy.points,
                                                        ctx.lengths.detail_max_distance));
  return fit.unexplained_share < unexplained ? careful : base;
}

namespace {

/// The base of a key group whose key frame is `frame`: `made_ahead` (the same base, made on
/// another thread) when given and the frame's proxy is cached, else MakeKeyFrameBase (from the
/// frame's fusion when `targets` has it), the frame's proxy made and cached when missing.
StatusOr<TriangleMesh> BaseOfKeyFrame(const EncodeContext& ctx, int frame, TrackingTargets* targets,
                                      std::optional<TriangleMesh> made_ahead) {
  ProxyCache& proxies = targets->proxies();
  if (made_ahead && proxies.count(frame)) return *std::move(made_ahead);
  MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh> views, ctx.source.LoadFrame(frame));
  if (!proxies.count(frame)) {
    MESHVID_ASSIGN_OR_RETURN(proxies[frame], BuildProxy(ctx, views));
  }
  targets->Collect(frame);
  const FusedFrame* fused = targets->Fused(frame);
  return MakeKeyFrameBase(ctx, views, proxies[frame], fused != nullptr ? &fused->mesh : nullptr);
}

}  // namespace

StatusOr<KeyGroupAnalysis> AnalyseKeyGroup(
    const EncodeContext& ctx, int start, bool may_cut, const MotionHint& hint,
    TrackingTargets* targets, std::optional<TriangleMesh> base_made_ahead,
    const std::function<std::optional<TriangleMesh>(int frame)>& later_base_ahead) {
  const EncoderOptions& options = ctx.options;
  KeyGroupAnalysis analysis;
  KeyGroupSummary& summary = analysis.summary;
  summary.first_frame = start;
  summary.key_frame = start;
  if (!ReportProgress(ctx.progress, "base mesh", start, ctx.end)) return Cancelled();
  auto stage_start = Clock::now();
  targets->DropBefore(start);
  // With tuning.deform_backward_frames: the key frame a few frames on, tracked back to this one.
  double seconds_on_later_key_frame = 0;
  const int later_key = std::min(start + options.tuning.deform_backward_frames, ctx.end - 1);
  const bool later_key_first = may_cut && !options.base_mesh && later_key > start;
  // The first frame tracked is made on another thread while the base is made here.
  MESHVID_RETURN_IF_ERROR(targets->StartMaking(later_key_first ? later_key - 1 : start + 1));
  if (later_key_first) {
    KeyGroupAnalysis later;
    later.summary.first_frame = start;
    MESHVID_ASSIGN_OR_RETURN(
        later.base, BaseOfKeyFrame(ctx, later_key, targets,
                                   later_base_ahead ? later_base_ahead(later_key) : std::nullopt));
    const BaseTopology later_topology(later.base);
    later.summary.base_vertices = later.base.vertex_count();
    later.seconds_base = SecondsSince(stage_start);
    MESHVID_RETURN_IF_ERROR(TrackDeformedKeyGroup(ctx, later_topology, start, later_key, may_cut,
                                                  hint, targets, &later));
    if (later.summary.frames > 0) return later;
    // A frame before the later key frame was lost: the key frame is this one after all.
    seconds_on_later_key_frame = later.seconds_base;
    analysis.unused_base = std::move(later.base);
    analysis.unused_base_frame = later_key;
    stage_start = Clock::now();
  }
  MESHVID_ASSIGN_OR_RETURN(analysis.base,
                           BaseOfKeyFrame(ctx, start, targets, std::move(base_made_ahead)));
  const TriangleMesh& base = analysis.base;
  const BaseTopology topology(base);  // one-rings and normals, once per key group
  summary.base_vertices = base.vertex_count();
  analysis.seconds_base = SecondsSince(stage_start) + seconds_on_later_key_frame;

  MESHVID_RETURN_IF_ERROR(
      TrackDeformedKeyGroup(ctx, topology, start, start, may_cut, hint, targets, &analysis));
  return analysis;
}

}  // namespace meshvid
