#include "codec/enc/key_group_analysis.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include <tbb/parallel_for.h>

#include "codec/common/subdivision.h"
#include "codec/enc/data_fit.h"
#include "codec/enc/decimation.h"
#include "codec/enc/deformed_key_group.h"
#include "codec/enc/key_group_rules.h"
#include "codec/enc/motion_blend.h"
#include "codec/enc/patch_tracking.h"
#include "codec/enc/surface_fusion.h"

namespace meshvid {

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Status Cancelled() { return CancelledError("encode cancelled"); }

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

/// A key group's base mesh: the user's, rigidly fitted to the key frame, or the key frame's
/// fused views (at most `fusion_points` of them) decimated.
StatusOr<TriangleMesh> MakeBaseMesh(const EncodeContext& ctx,
                                    const std::vector<TriangleMesh>& views,
                                    const ShootingTarget* proxy, std::size_t fusion_points) {
  const EncoderOptions& options = ctx.options;
  if (options.base_mesh) {
    TriangleMesh base = *options.base_mesh;
    MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "the base mesh"));
    base.normals.clear();
    if (proxy != nullptr) {
      const std::vector<std::int32_t> labels(base.vertex_count(), 0);
      const std::vector<RigidTransform> identity(1);
      const RigidTransform fitted =
          TrackSegments(base, labels, 1, *proxy, identity, ctx.seg).front();
      for (auto& p : base.positions) p = fitted.Apply(p);
    }
    return base;
  }
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh fused, FuseFrame(ctx, views, fusion_points));
  DecimationOptions decimation;
  decimation.target_vertices = options.base_vertices;
  decimation.max_error = ctx.lengths.base_max_error;
  decimation.max_normal_deviation_degrees = options.tuning.base_max_normal_deviation_degrees;
  decimation.max_edge_length = ctx.lengths.base_max_edge;
  TriangleMesh base = std::move(fused);
  if (base.vertex_count() > options.base_vertices) {
    MESHVID_ASSIGN_OR_RETURN(base, DecimateMesh(base, decimation));
  }
  // One vertex per fan, as the base mesh coder keeps them (its vertex order found again).
  SplitNonManifoldVertices(&base);
  return base;
}

/// Segments, patches and blend weights of a base over the frames `analysed` (all with
/// proxies), and the tracks of those frames.
struct SegmentedMotion {
  std::vector<std::int32_t> labels;
  int segment_count = 0;
  std::vector<std::vector<RigidTransform>> tracks;  ///< per analysed frame
  int soft_from = 0;  ///< pieces from this one on blend into their neighbours
  std::vector<std::int32_t> parents;  ///< per piece, the piece its graph node was split from
};

/// Tracks patches fixed_count..total_count-1 of `labels` through the frames of `targets`
/// (with their points) with the graph tracker, the segments below fixed_count held to their
/// `transforms`, to which the patches' are appended (frame 0: the identity).
void TrackPatchesByGraph(const EncodeContext& ctx, const BaseTopology& base,
                         const std::vector<std::int32_t>& labels, int fixed_count,
                         int total_count, const std::vector<const ShootingTarget*>& targets,
                         const std::vector<std::span<const Eigen::Vector3f>>& points,
                         std::vector<std::vector<RigidTransform>>* transforms) {
  const GraphTracker tracker(base, labels, total_count, ctx.seg, ctx.track, fixed_count);
  for (auto& frame : *transforms) frame.resize(total_count);
  for (std::size_t k = 1; k < targets.size(); ++k) {
    auto& frame = (*transforms)[k];
    const auto& previous = (*transforms)[k - 1];
    const std::span<const RigidTransform> before =
        k >= 2 ? std::span<const RigidTransform>((*transforms)[k - 2])
               : std::span<const RigidTransform>();
    if (targets[k] == nullptr) {
      for (int p = fixed_count; p < total_count; ++p) {
        frame[p] = before.empty() ? previous[p] : PredictConstantVelocity(before[p], previous[p]);
      }
      continue;
    }
    const std::vector<RigidTransform> fixed(frame.begin(), frame.begin() + fixed_count);
    frame = tracker.Track(*targets[k], points[k], previous, before, fixed);
  }
}

StatusOr<SegmentedMotion> SegmentFrames(const EncodeContext& ctx, const BaseTopology& base,
                                        const std::vector<const ShootingTarget*>& targets,
                                        const std::vector<std::span<const Eigen::Vector3f>>& points,
                                        KeyGroupSummary* summary) {
  const EncoderOptions& options = ctx.options;
  SegmentationOptions seg = ctx.seg;
  // A long capture of a non-rigid subject leaves few vertices rigid with their segment in
  // all but 5 frames; by default a tenth of the analysed frames may disagree.
  if (options.tuning.occlusion_frames < 0) {
    seg.occlusion_frames = std::max(5, static_cast<int>(targets.size()) / 10);
  }
  MESHVID_ASSIGN_OR_RETURN(Segmentation segmentation,
                           SegmentPiecewiseRigid(base, targets, seg, ctx.progress));
  SegmentedMotion result;
  summary->segments = segmentation.segment_count;
  std::size_t registered = 0;
  for (std::int32_t label : segmentation.labels) registered += label >= 0;
  summary->registered_share = double(registered) / double(base.mesh.vertex_count());
  // No segment: a user's base that misses the data is an error. A base fused from the key
  // frame explains that frame; its vertices are left to the patches below (a surface folding
  // on itself can defeat every segment's seed), and the key-group fit ends the key group where
  // they no longer explain the data.
  if (segmentation.segment_count == 0 && options.base_mesh) {
    return InvalidArgumentError(
        "no rigid segment found: the base mesh does not match the data (fewer than " +
        std::to_string(seg.min_segment_vertices) + " connected vertices within the tolerance " +
        std::to_string(seg.tolerance) + " over the frames)");
  }
  result.labels = segmentation.labels;
  result.segment_count = segmentation.segment_count;
  if (options.tuning.patch_vertices > 0) {
    // Patches over the unregistered vertices, tracked jointly through the frames.
    PatchTrackingOptions patching;
    patching.patch_vertices = options.tuning.patch_vertices;
    patching.max_segments = options.tuning.max_segments;
    patching.stiffness = static_cast<float>(options.tuning.patch_stiffness);
    result.segment_count = PartitionUnregistered(base, segmentation.segment_count,
                                                 options.tuning.min_segment_vertices, patching,
                                                 &result.labels);
    if (options.tuning.graph_tracking) {
      TrackPatchesByGraph(ctx, base, result.labels, segmentation.segment_count,
                          result.segment_count, targets, points, &segmentation.transforms);
    } else {
      MESHVID_RETURN_IF_ERROR(TrackPatches(base, result.labels, segmentation.segment_count,
                                           result.segment_count, targets, seg, patching,
                                           &segmentation.transforms, ctx.progress));
    }
    result.segment_count =
        MergePatchesIntoSegments(base, segmentation.segment_count, result.segment_count, seg,
                                 &result.labels, &segmentation.transforms);
  }
  if (result.segment_count == 0) {
    // No segment and no patches: the base stays where it is, as one piece.
    result.labels.assign(base.mesh.vertex_count(), 0);
    result.segment_count = 1;
    for (auto& frame : segmentation.transforms) frame.assign(1, RigidTransform{});
  }
  result.soft_from = segmentation.segment_count;
  if (options.tuning.graph_tracking && options.tuning.graph_node_vertices > 0) {
    // Graph nodes: pieces larger than a node are split; the nodes of a piece move with it
    // through the analysed frames and apart from it where the frames after them need.
    std::vector<std::int32_t> parents;
    const int split =
        SplitIntoNodes(base, result.segment_count, options.tuning.graph_node_vertices,
                       options.tuning.max_segments, &result.labels, &parents);
    for (auto& frame : segmentation.transforms) {
      for (int p = result.segment_count; p < split; ++p) frame.push_back(frame[parents[p]]);
    }
    if (split > result.segment_count && options.tuning.blend_nodes) result.soft_from = 0;
    result.segment_count = split;
    result.parents = std::move(parents);
  }
  // Hard pieces: each moves its vertices alone (the blends of soft ones cost most of a key
  // group's motion bytes once there are many pieces).
  if (options.tuning.graph_tracking && !options.tuning.blend_nodes) {
    result.soft_from = result.segment_count;
  }
  summary->patches = result.segment_count - segmentation.segment_count;
  result.tracks = std::move(segmentation.transforms);
  return result;
}

/// Graph nodes that moved with the piece they were split from in every frame of the key
/// group (RMS apart over their members within tuning.node_rejoin_factor x the tolerance)
/// join it again, so a rigid part
/// stays one segment; the blend weights and tracks are rebuilt to match.
void RejoinNodes(const EncodeContext& ctx, const BaseTopology& topology,
                 SegmentedMotion* segmented, KeyGroupAnalysis* analysis) {
  const int count = segmented->segment_count;
  const std::vector<std::int32_t>& parents = segmented->parents;
  if (static_cast<int>(parents.size()) != count) return;
  std::vector<std::vector<std::uint32_t>> members(count);
  for (std::uint32_t v = 0; v < segmented->labels.size(); ++v) {
    if (segmented->labels[v] >= 0) members[segmented->labels[v]].push_back(v);
  }
  const auto& positions = topology.mesh.positions;
  const double tolerance = ctx.seg.tolerance * ctx.options.tuning.node_rejoin_factor;
  std::vector<std::int32_t> index(count, -1);
  int kept = 0;
  for (int p = 0; p < count; ++p) {
    const std::int32_t q = parents[p];
    bool together = q != p && !members[p].empty();
    for (std::size_t f = 0; together && f < analysis->tracks.size(); ++f) {
      const auto& frame = analysis->tracks[f];
      double squared = 0;
      for (std::uint32_t v : members[p]) {
        squared += (frame[p].Apply(positions[v]) - frame[q].Apply(positions[v])).squaredNorm();
      }
      together = squared <= tolerance * tolerance * double(members[p].size());
    }
    if (!together) index[p] = kept++;
  }
  if (kept == count) return;
  for (std::int32_t& l : segmented->labels) {
    if (l >= 0) l = index[l] >= 0 ? index[l] : index[parents[l]];
  }
  for (auto& frame : analysis->tracks) {
    std::vector<RigidTransform> rejoined;
    for (int p = 0; p < count; ++p) {
      if (index[p] >= 0) rejoined.push_back(frame[p]);
    }
    frame = std::move(rejoined);
  }
  std::vector<std::int32_t> kept_parents;
  for (int p = 0; p < count; ++p) {
    if (index[p] >= 0) kept_parents.push_back(index[parents[p]]);
  }
  segmented->parents = std::move(kept_parents);
  segmented->segment_count = kept;
  analysis->summary.patches -= count - kept;
  std::vector<std::uint8_t> surface = std::move(analysis->motion.surface_triangles);
  analysis->motion = BlendWeightsFromLabels(topology, segmented->labels, kept, /*smoothing=*/4,
                                            segmented->soft_from);
  analysis->motion.surface_triangles = std::move(surface);
}

/// The tracks of a frame of a key group from its previous frames (`tracks`, the last is the
/// frame before): the joint graph tracker's (tuning.graph_tracking) or each segment's alone.
std::vector<RigidTransform> TrackFrame(const EncodeContext& ctx, const BaseTopology& topology,
                                       const SegmentedMotion& segmented,
                                       const GraphTracker* tracker, const FrameProxy& proxy,
                                       std::span<const std::vector<RigidTransform>> tracks) {
  const std::vector<RigidTransform>& previous = tracks.back();
  if (!proxy.target) return previous;
  if (tracker == nullptr) {
    return TrackSegments(topology, segmented.labels, segmented.segment_count, *proxy.target,
                         previous, ctx.seg);
  }
  const std::span<const RigidTransform> before =
      tracks.size() >= 2 ? std::span<const RigidTransform>(tracks[tracks.size() - 2])
                         : std::span<const RigidTransform>();
  return tracker->Track(*proxy.target, proxy.points, previous, before);
}

/// The graph tracker of a segmentation's pieces, or nothing when tuning.graph_tracking is off.
std::unique_ptr<GraphTracker> MakeTracker(const EncodeContext& ctx, const BaseTopology& topology,
                                          const SegmentedMotion& segmented) {
  if (!ctx.options.tuning.graph_tracking) return nullptr;
  return std::make_unique<GraphTracker>(topology, segmented.labels, segmented.segment_count,
                                        ctx.seg, ctx.track);
}

/// The motion of a key group's base over frames [start, stop): every `stride`-th frame
/// segmented jointly (proxies cached), the others tracked from the previous frame. Fills the
/// analysis' motion, tracks (stop - start of them) and segment figures.
StatusOr<SegmentedMotion> SegmentKeyGroup(const EncodeContext& ctx,
                                          const BaseTopology& topology, int start, int stop,
                                          int stride, ProxyCache* proxies,
                                          KeyGroupAnalysis* analysis) {
  const EncoderOptions& options = ctx.options;
  const TriangleMesh& base = analysis->base;
  auto stage_start = Clock::now();
  std::vector<int> analysed;
  for (int t = start; t < stop; t += stride) analysed.push_back(t);
  for (std::size_t k = 0; k < analysed.size(); ++k) {
    if (!ReportProgress(ctx.progress, "proxies", long(k), long(analysed.size()))) {
      return Cancelled();
    }
    if (proxies->count(analysed[k])) continue;
    MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views,
                             ctx.source.LoadFrame(analysed[k]));
    MESHVID_ASSIGN_OR_RETURN((*proxies)[analysed[k]], BuildProxy(ctx, views));
  }
  analysis->seconds_proxies += SecondsSince(stage_start);
  std::vector<const ShootingTarget*> targets;
  std::vector<std::span<const Eigen::Vector3f>> points;
  for (int t : analysed) {
    targets.push_back((*proxies)[t].target.get());
    points.push_back((*proxies)[t].points);
  }
  MESHVID_ASSIGN_OR_RETURN(SegmentedMotion segmented,
                           SegmentFrames(ctx, topology, targets, points, &analysis->summary));
  std::vector<std::vector<RigidTransform>>& tracks = analysis->tracks;
  tracks.assign(stop - start, {});
  for (std::size_t k = 0; k < analysed.size(); ++k) {
    tracks[analysed[k] - start] = segmented.tracks[k];
  }
  // Frames between analysed frames: tracked from the previous frames with the fixed pieces.
  const std::unique_ptr<GraphTracker> tracker =
      stride > 1 ? MakeTracker(ctx, topology, segmented) : nullptr;
  for (int t = start + 1; stride > 1 && t < stop; ++t) {
    if ((t - start) % stride == 0) continue;
    if (!ReportProgress(ctx.progress, "tracking", t - start, stop - start)) return Cancelled();
    MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, ctx.source.LoadFrame(t));
    // Tracked only, never measured by the key-group fit: no free space needed.
    MESHVID_ASSIGN_OR_RETURN(FrameProxy proxy, BuildProxy(ctx, views, /*free_space=*/false));
    tracks[t - start] = TrackFrame(ctx, topology, segmented, tracker.get(), proxy,
                                   std::span(tracks.data(), std::size_t(t - start)));
  }
  SmoothTracks(options.tuning.track_smoothing,
               PieceCentres(base.positions, segmented.labels, segmented.segment_count), &tracks);
  analysis->motion = BlendWeightsFromLabels(topology, segmented.labels,
                                            segmented.segment_count,
                                            /*smoothing=*/4,
                                            /*soft_from=*/segmented.soft_from);
  std::vector<std::vector<RigidTransform>> analysed_tracks;
  for (int t : analysed) analysed_tracks.push_back(tracks[t - start]);
  std::vector<char> observed(base.vertex_count(), 0);
  for (std::size_t k = 0; k < targets.size(); ++k) {
    if (targets[k] != nullptr) {
      ObserveVertices(ctx, base, analysis->motion, *targets[k], analysed_tracks[k], &observed);
    }
  }
  MarkSurface(ctx, base, observed, &analysis->motion, &analysis->summary);
  return segmented;
}

/// Frames a key group that may be cut is first analysed over: where tracking fails fast,
/// each key group costs a short segmentation; one that holds is analysed again over
/// key_group_window frames. After a key group of n frames, the next starts with 2n frames
/// (at least 2, at most this): where every frame is a key frame (fast motion), a key group
/// then costs a segmentation of 2 frames, not 8.
constexpr int kFirstKeyGroupWindow = 8;

}  // namespace

StatusOr<TriangleMesh> MakeKeyFrameBase(const EncodeContext& ctx,
                                        const std::vector<TriangleMesh>& views,
                                        const FrameProxy& proxy) {
  const SurfaceFusionOptions defaults;
  const std::size_t fast = std::min(ctx.options.tuning.base_fusion_points, defaults.max_points);
  StatusOr<TriangleMesh> base = MakeBaseMesh(ctx, views, proxy.target.get(), fast);
  if (ctx.options.base_mesh || fast >= defaults.max_points) return base;
  double unexplained = 1;
  if (base.ok()) {
    MESHVID_ASSIGN_OR_RETURN(const DataFit fit, FitOfBase(*base, ctx.options.levels, proxy.points,
                                                          ctx.lengths.detail_max_distance));
    unexplained = fit.unexplained_share;
    if (unexplained <= kMostUnexplainedAtKeyFrame) return base;
  }
  StatusOr<TriangleMesh> careful =
      MakeBaseMesh(ctx, views, proxy.target.get(), defaults.max_points);
  if (!careful.ok()) return base.ok() ? base : careful;
  if (!base.ok()) return careful;
  MESHVID_ASSIGN_OR_RETURN(const DataFit fit, FitOfBase(*careful, ctx.options.levels,
                                                        proxy.points,
                                                        ctx.lengths.detail_max_distance));
  return fit.unexplained_share < unexplained ? careful : base;
}

namespace {

/// The base of a key group whose key frame is `frame`: `made_ahead` (the same base, made on
/// another thread) when given and the frame's proxy is cached, else MakeKeyFrameBase, the
/// frame's proxy made and cached when missing.
StatusOr<TriangleMesh> BaseOfKeyFrame(const EncodeContext& ctx, int frame, ProxyCache* proxies,
                                      std::optional<TriangleMesh> made_ahead) {
  if (made_ahead && proxies->count(frame)) return *std::move(made_ahead);
  MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh> views, ctx.source.LoadFrame(frame));
  if (!proxies->count(frame)) {
    MESHVID_ASSIGN_OR_RETURN((*proxies)[frame], BuildProxy(ctx, views));
  }
  return MakeKeyFrameBase(ctx, views, (*proxies)[frame]);
}

}  // namespace

StatusOr<KeyGroupAnalysis> AnalyseKeyGroup(
    const EncodeContext& ctx, int start, bool may_cut, int previous_frames, ProxyCache* cache,
    std::optional<TriangleMesh> base_made_ahead,
    const std::function<std::optional<TriangleMesh>(int frame)>& later_base_ahead) {
  const EncoderOptions& options = ctx.options;
  KeyGroupAnalysis analysis;
  KeyGroupSummary& summary = analysis.summary;
  summary.first_frame = start;
  summary.key_frame = start;
  if (!ReportProgress(ctx.progress, "base mesh", start, ctx.end)) return Cancelled();
  auto stage_start = Clock::now();
  ProxyCache& proxies = *cache;
  proxies.erase(proxies.begin(), proxies.lower_bound(start));
  // With --deform-backward: the key frame a few frames on, tracked back to this one.
  FusedFrames fused_frames;
  double seconds_on_later_key_frame = 0;
  const int later_key = std::min(start + options.tuning.deform_backward_frames, ctx.end - 1);
  if (options.tuning.deformation_tracking && may_cut && !options.base_mesh && later_key > start) {
    KeyGroupAnalysis later;
    later.summary.first_frame = start;
    MESHVID_ASSIGN_OR_RETURN(
        later.base,
        BaseOfKeyFrame(ctx, later_key, &proxies,
                       later_base_ahead ? later_base_ahead(later_key) : std::nullopt));
    const BaseTopology later_topology(later.base);
    later.summary.base_vertices = later.base.vertex_count();
    later.seconds_base = SecondsSince(stage_start);
    MESHVID_RETURN_IF_ERROR(TrackDeformedKeyGroup(ctx, later_topology, start, later_key, may_cut,
                                                  &proxies, &fused_frames, &later));
    if (later.summary.frames > 0) return later;
    // A frame before the later key frame was lost: the key frame is this one after all.
    seconds_on_later_key_frame = later.seconds_base;
    analysis.unused_base = std::move(later.base);
    analysis.unused_base_frame = later_key;
    stage_start = Clock::now();
  }
  MESHVID_ASSIGN_OR_RETURN(analysis.base,
                           BaseOfKeyFrame(ctx, start, &proxies, std::move(base_made_ahead)));
  const TriangleMesh& base = analysis.base;
  const BaseTopology topology(base);  // one-rings and normals, once per key group
  summary.base_vertices = base.vertex_count();
  analysis.seconds_base = SecondsSince(stage_start) + seconds_on_later_key_frame;

  if (options.tuning.deformation_tracking) {
    MESHVID_RETURN_IF_ERROR(TrackDeformedKeyGroup(ctx, topology, start, start, may_cut,
                                                  &proxies, &fused_frames, &analysis));
    return analysis;
  }
  if (!may_cut) {
    // Every remaining frame, or `window` of them spread evenly, segmented jointly.
    const int stride = (ctx.end - start + options.tuning.window - 1) / options.tuning.window;
    MESHVID_ASSIGN_OR_RETURN(
        SegmentedMotion segmented,
        SegmentKeyGroup(ctx, topology, start, ctx.end, stride, &proxies, &analysis));
    summary.frames = ctx.end - start;
    RejoinNodes(ctx, topology, &segmented, &analysis);
    return analysis;
  }

  // Where the key group ends: the first frame its tracked base no longer explains.
  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice,
                           RegularSubdivision::Create(base, std::min(options.levels, 2)));
  std::vector<std::vector<RigidTransform>>& tracks = analysis.tracks;
  DataFit key_fit;
  std::optional<FitMeter> meter;
  auto explained = [&](int t, const FrameProxy& frame) {
    return KeepTrackedFrame(ctx, key_fit, meter->Measure(tracks[t - start], frame), &summary);
  };
  SegmentedMotion segmented;
  std::unique_ptr<GraphTracker> tracker;
  int stop = start;
  int kept = start;
  const int first_window = previous_frames > 0
                               ? std::clamp(2 * previous_frames, 2, kFirstKeyGroupWindow)
                               : kFirstKeyGroupWindow;
  for (const int window : {std::min(first_window, options.tuning.key_group_window),
                           options.tuning.key_group_window}) {
    if (stop > start && (kept < stop || stop == ctx.end || window <= stop - start)) break;
    stop = std::min(ctx.end, start + window);
    MESHVID_ASSIGN_OR_RETURN(segmented,
                             SegmentKeyGroup(ctx, topology, start, stop, 1, &proxies, &analysis));
    // Stray: farther from every data point than a correspondence may reach. Free space is
    // judged at a sample's pixel alone, as kSegmentationKeyGroupThreshold was measured: judged
    // across the tolerance too, arm-block 3-arc gave 47 key groups against 50 and 0.05 dB less
    // (bench/DEFORM.md).
    meter.emplace(base, analysis.motion, lattice, ctx.lengths.detail_max_distance,
                  ctx.lengths.max_distance, /*judge_across=*/false);
    key_fit = meter->Measure(tracks[0], proxies[start]);
    summary.key_frame_unexplained = key_fit.unexplained_share;
    summary.key_frame_seen_through = key_fit.seen_through_share;
    summary.worst_unexplained = key_fit.unexplained_share;
    summary.worst_loss_db = 0;
    ClearCut(&summary);
    tracker = MakeTracker(ctx, topology, segmented);
    kept = stop;
    for (int t = start + 1; t < stop; ++t) {
      if (explained(t, proxies[t])) continue;
      // The segmentation lost the frame: tracked again from the frames before it.
      if (tracker) {
        tracks[t - start] = TrackFrame(ctx, topology, segmented, tracker.get(), proxies[t],
                                       std::span(tracks.data(), std::size_t(t - start)));
        if (explained(t, proxies[t])) {
          ClearCut(&summary);
          continue;
        }
      }
      kept = t;
      break;
    }
  }
  // Past the analysed frames: tracked frame by frame while the base explains the data.
  for (int t = stop; kept == stop && t < ctx.end; ++t) {
    if (!ReportProgress(ctx.progress, "tracking", t, ctx.end)) return Cancelled();
    proxies.erase(proxies.begin(), proxies.lower_bound(t));
    MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, ctx.source.LoadFrame(t));
    MESHVID_ASSIGN_OR_RETURN(proxies[t], BuildProxy(ctx, views));
    tracks.push_back(TrackFrame(ctx, topology, segmented, tracker.get(), proxies[t], tracks));
    if (!explained(t, proxies[t])) {
      tracks.pop_back();
      break;
    }
    stop = t + 1;
    kept = stop;
  }
  proxies.erase(proxies.begin(), proxies.lower_bound(kept));
  tracks.resize(kept - start);
  summary.frames = kept - start;
  RejoinNodes(ctx, topology, &segmented, &analysis);
  return analysis;
}

}  // namespace meshvid
