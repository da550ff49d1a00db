#include "codec/enc/encoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include <tbb/parallel_for.h>

#include "codec/enc/decimation.h"
#include "codec/enc/detail.h"
#include "codec/enc/motion_blend.h"
#include "codec/enc/normal_shooting.h"
#include "codec/enc/patch_tracking.h"
#include "codec/enc/segmentation.h"
#include "codec/enc/surface_fusion.h"

namespace meshvid {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Lengths the options leave at 0, derived from the data's size.
struct Lengths {
  float scale = 1;
  float max_distance = 0, tolerance = 0, detail_max_distance = 0, outlier_distance = 0,
        base_max_error = 0;
};

Lengths DeriveLengths(const EncoderOptions& o, float scale) {
  auto pick = [scale](double value, double fraction) {
    return static_cast<float>(value > 0 ? value : fraction * scale);
  };
  Lengths l;
  l.scale = scale;
  l.max_distance = pick(o.max_distance, 0.08);
  l.tolerance = pick(o.tolerance, 0.005);
  l.detail_max_distance = pick(o.detail_max_distance, 0.02);
  l.outlier_distance = pick(o.outlier_distance, 0.005);
  l.base_max_error = pick(o.base_max_error, 0.01);
  return l;
}

Status CheckOptions(const EncoderOptions& o) {
  auto bad = [](const std::string& what) { return InvalidArgumentError(what); };
  if (o.levels < 0 || o.levels > RegularSubdivision::kMaxLevels) {
    return bad("--levels must be in 0.." + std::to_string(RegularSubdivision::kMaxLevels));
  }
  if (o.quality < 0 || o.quality > 100) return bad("--quality must be in 0..100");
  if (o.effort < 0 || o.effort > 9) return bad("--effort must be in 0..9");
  if (o.gof_size < 1 || o.gof_size > 1024) return bad("--gof must be in 1..1024");
  if (o.window < 2) return bad("--window must be at least 2 frames");
  if (o.base_vertices < 4) return bad("--base-vertices must be at least 4");
  if (!(o.proxy_fraction > 0 && o.proxy_fraction <= 1)) {
    return bad("--proxy-fraction must be in (0, 1]");
  }
  if (!(o.max_angle_degrees > 0 && o.max_angle_degrees < 90)) {
    return bad("--max-angle must be in (0, 90) degrees");
  }
  if (!(o.tolerance_shrink > 0 && o.tolerance_shrink < 1)) {
    return bad("--tol-shrink must be in (0, 1)");
  }
  if (o.initial_tolerance_factor < 1) return bad("--tol-start must be at least 1");
  if (o.occlusion_frames < -1) return bad("--occlusion-frames must be >= 0 (or -1: automatic)");
  if (o.seed_vertices < 0) return bad("--seed-vertices must be >= 0");
  if (!(o.max_turn_degrees > 0 && o.max_turn_degrees <= 180)) {
    return bad("--max-turn must be in (0, 180] degrees");
  }
  if (!(o.min_solved_share >= 0 && o.min_solved_share <= 1)) {
    return bad("--min-solved must be in [0, 1]");
  }
  if (o.patch_vertices < 0) return bad("--patch-vertices must be >= 0");
  if (!(o.patch_stiffness > 0)) return bad("--stiffness must be positive");
  if (o.max_segments < 1 || o.max_segments > 65535) return bad("--max-segments must be in 1..65535");
  if (o.max_distance < 0 || o.tolerance < 0 || o.detail_max_distance < 0 ||
      o.outlier_distance < 0 || o.base_max_error < 0) {
    return bad("lengths must not be negative (0 derives them from the data)");
  }
  return Status::Ok();
}

/// The decimated copies of a frame's views, appended into one correspondence target.
StatusOr<std::unique_ptr<ShootingTarget>> BuildProxy(const std::vector<TriangleMesh>& views,
                                                     double fraction) {
  std::vector<StatusOr<TriangleMesh>> decimated(views.size(), TriangleMesh{});
  tbb::parallel_for(std::size_t(0), views.size(), [&](std::size_t v) {
    if (views[v].empty()) return;
    DecimationOptions options;
    options.target_vertices = std::max<std::size_t>(
        16, static_cast<std::size_t>(fraction * double(views[v].vertex_count())));
    decimated[v] = options.target_vertices >= views[v].vertex_count()
                       ? StatusOr<TriangleMesh>(views[v])
                       : DecimateMesh(views[v], options);
  });
  TriangleMesh proxy;
  for (auto& view : decimated) {
    if (!view.ok()) return view.status();
    AppendMesh(*view, &proxy);
  }
  if (proxy.empty()) return std::unique_ptr<ShootingTarget>();
  return ShootingTarget::Create(proxy);
}

float DiagonalOf(const std::vector<TriangleMesh>& views) {
  Eigen::AlignedBox3f box;
  for (const TriangleMesh& view : views) box.extend(BoundingBox(view));
  return box.isEmpty() ? 0.0f : box.diagonal().norm();
}

/// The base mesh: the user's, rigidly fitted to frame 0, or frame 0's fused views decimated.
StatusOr<TriangleMesh> MakeBaseMesh(const EncoderOptions& options, const Lengths& lengths,
                                    const SegmentationOptions& fit,
                                    const std::vector<TriangleMesh>& views,
                                    const ShootingTarget* proxy0,
                                    const ProgressCallback& progress) {
  if (options.base_mesh) {
    TriangleMesh base = *options.base_mesh;
    MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "the base mesh"));
    base.normals.clear();
    if (proxy0 != nullptr) {
      const std::vector<std::int32_t> labels(base.vertex_count(), 0);
      const std::vector<RigidTransform> identity(1);
      const RigidTransform fitted =
          TrackSegments(base, labels, 1, *proxy0, identity, fit).front();
      for (auto& p : base.positions) p = fitted.Apply(p);
    }
    return base;
  }
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh fused, FuseRangeMeshes(views, {}, progress));
  DecimationOptions decimation;
  decimation.target_vertices = options.base_vertices;
  decimation.max_error = lengths.base_max_error;
  decimation.max_normal_deviation_degrees = options.base_max_normal_deviation_degrees;
  if (fused.vertex_count() <= options.base_vertices) return fused;
  return DecimateMesh(fused, decimation);
}

}  // namespace

int QualityToQp(VideoCodec codec, int quality) {
  const double fraction = 1.0 - std::clamp(quality, 0, 100) / 100.0;
  switch (codec) {
    case VideoCodec::kAv1: return static_cast<int>(std::lround(63 * fraction));
    case VideoCodec::kFfv1: return 0;
    case VideoCodec::kHevc:
    default: return static_cast<int>(std::lround(51 * fraction));
  }
}

StatusOr<EncodeSummary> EncodeCapture(const FrameSource& source, ByteSink sink,
                                      const EncoderOptions& options,
                                      const ProgressCallback& progress) {
  MESHVID_RETURN_IF_ERROR(CheckOptions(options));
  const int first = options.first_frame;
  const int end = options.end_frame < 0 ? source.frame_count() : options.end_frame;
  if (first < 0 || first >= end || end > source.frame_count()) {
    return InvalidArgumentError("frames " + std::to_string(first) + ":" + std::to_string(end) +
                                " are outside the capture's 0:" +
                                std::to_string(source.frame_count()));
  }
  const int frames = end - first;
  EncodeSummary summary;
  summary.frames = frames;
  summary.views = source.view_count();
  summary.frame_rate = source.frame_rate();

  // --- frame 0: scale, base mesh
  auto start = Clock::now();
  if (!ReportProgress(progress, "base mesh", 0, 1)) return CancelledError("encode cancelled");
  MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views0, source.LoadFrame(first));
  const float scale = DiagonalOf(views0);
  if (!(scale > 0)) {
    return InvalidArgumentError("frame " + std::to_string(first) + " holds no surface");
  }
  const Lengths lengths = DeriveLengths(options, scale);
  summary.scale = scale;
  summary.tolerance = lengths.tolerance;
  SegmentationOptions seg;
  seg.tolerance = lengths.tolerance;
  seg.initial_tolerance_factor = static_cast<float>(options.initial_tolerance_factor);
  seg.tolerance_shrink = static_cast<float>(options.tolerance_shrink);
  seg.min_segment_vertices = options.min_segment_vertices;
  seg.max_segments = options.max_segments;
  seg.occlusion_frames = options.occlusion_frames;
  seg.icp_iterations = options.icp_iterations;
  seg.seed_vertices = options.seed_vertices;
  seg.max_turn_per_frame = static_cast<float>(options.max_turn_degrees * M_PI / 180);
  seg.min_solved_share = static_cast<float>(options.min_solved_share);
  seg.shot.max_distance = lengths.max_distance;
  seg.shot.min_abs_cos = static_cast<float>(std::cos(options.max_angle_degrees * M_PI / 180));

  // Key frames: all frames, or `window` of them spread evenly over a longer capture.
  const int stride = (frames + options.window - 1) / options.window;
  std::vector<int> key_frames;
  for (int t = first; t < end; t += stride) key_frames.push_back(t);
  // A long capture of a non-rigid subject leaves few vertices rigid with their segment in
  // all but 5 frames; by default a tenth of the key frames may disagree.
  if (options.occlusion_frames < 0) {
    seg.occlusion_frames = std::max(5, static_cast<int>(key_frames.size()) / 10);
  }
  std::map<int, std::unique_ptr<ShootingTarget>> proxies;
  MESHVID_ASSIGN_OR_RETURN(proxies[first], BuildProxy(views0, options.proxy_fraction));
  MESHVID_ASSIGN_OR_RETURN(
      TriangleMesh base, MakeBaseMesh(options, lengths, seg, views0, proxies[first].get(),
                                      progress));
  views0 = {};
  summary.base_vertices = base.vertex_count();
  summary.seconds_base = SecondsSince(start);

  // --- proxies of the key frames (method.md 5.1)
  start = Clock::now();
  for (std::size_t k = 0; k < key_frames.size(); ++k) {
    if (!ReportProgress(progress, "proxies", long(k), long(key_frames.size()))) {
      return CancelledError("encode cancelled");
    }
    if (proxies.count(key_frames[k])) continue;
    MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, source.LoadFrame(key_frames[k]));
    MESHVID_ASSIGN_OR_RETURN(proxies[key_frames[k]], BuildProxy(views, options.proxy_fraction));
  }
  summary.seconds_proxies = SecondsSince(start);

  // --- segmentation (method.md 5.2-5.4) and the tracks of every frame
  start = Clock::now();
  std::vector<const ShootingTarget*> targets;
  for (int t : key_frames) targets.push_back(proxies[t].get());
  MESHVID_ASSIGN_OR_RETURN(Segmentation segmentation,
                           SegmentPiecewiseRigid(base, targets, seg, progress));
  summary.segments = segmentation.segment_count;
  std::size_t registered = 0;
  for (std::int32_t label : segmentation.labels) registered += label >= 0;
  summary.registered_share = double(registered) / double(base.vertex_count());
  // Patches over the unregistered vertices, tracked jointly through the key frames.
  std::vector<std::int32_t> labels = segmentation.labels;
  int segment_count = segmentation.segment_count;
  if (options.patch_vertices > 0) {
    PatchTrackingOptions patching;
    patching.patch_vertices = options.patch_vertices;
    patching.max_segments = options.max_segments;
    patching.stiffness = static_cast<float>(options.patch_stiffness);
    segment_count = PartitionUnregistered(base, segmentation.segment_count,
                                          options.min_segment_vertices, patching, &labels);
    MESHVID_RETURN_IF_ERROR(TrackPatches(base, labels, segmentation.segment_count,
                                         segment_count, targets, seg, patching,
                                         &segmentation.transforms, progress));
    segment_count = MergePatchesIntoSegments(base, segmentation.segment_count, segment_count,
                                             seg, &labels, &segmentation.transforms);
  }
  summary.patches = segment_count - segmentation.segment_count;
  std::vector<std::vector<RigidTransform>> tracks(frames);
  for (std::size_t k = 0; k < key_frames.size(); ++k) {
    tracks[key_frames[k] - first] = segmentation.transforms[k];
  }
  if (stride > 1) {
    // Frames between key frames: tracked from the previous frame with the fixed segments.
    for (int t = first + 1; t < end; ++t) {
      if ((t - first) % stride == 0) continue;
      if (!ReportProgress(progress, "tracking", t - first, frames)) {
        return CancelledError("encode cancelled");
      }
      MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, source.LoadFrame(t));
      MESHVID_ASSIGN_OR_RETURN(auto proxy, BuildProxy(views, options.proxy_fraction));
      const auto& previous = tracks[t - first - 1];
      tracks[t - first] =
          proxy ? TrackSegments(base, labels, segment_count, *proxy, previous, seg)
                : previous;
    }
  }
  SmoothTracks(options.track_smoothing, &tracks);
  MotionModel motion = BlendWeightsFromLabels(base, labels, segment_count, /*smoothing=*/4,
                                              /*soft_from=*/segmentation.segment_count);
  // The surface: base triangles some view saw (two corners or more) in some key frame. The
  // summary states its share; with --hide-unseen the rest is hidden, as the method leaves
  // pixels that exist in no frame unfilled.
  {
    std::vector<char> observed(base.vertex_count(), 0);
    std::vector<Eigen::Vector3f> posed, normals;
    ShotLimits limits = seg.shot;
    limits.max_distance = lengths.detail_max_distance;
    for (int t : key_frames) {
      if (!proxies[t]) continue;
      PoseVertices(motion, tracks[t - first], base.positions, &posed);
      ComputeVertexNormals(posed, base.triangles, &normals);
      tbb::parallel_for(std::size_t(0), posed.size(), [&](std::size_t v) {
        if (!observed[v] && !std::isnan(proxies[t]->Shoot(posed[v], normals[v], limits))) {
          observed[v] = 1;
        }
      });
    }
    motion.surface_triangles.resize(base.triangle_count());
    std::size_t surface = 0;
    for (std::size_t i = 0; i < base.triangle_count(); ++i) {
      const Triangle& tri = base.triangles[i];
      const int seen = observed[tri[0]] + observed[tri[1]] + observed[tri[2]];
      motion.surface_triangles[i] = seen >= 2;
      surface += seen >= 2;
    }
    summary.surface_share = double(surface) / double(base.triangle_count());
    if (!options.hide_unseen) motion.surface_triangles.clear();
  }
  proxies.clear();
  summary.seconds_segmentation = SecondsSince(start);

  // --- detail, filling and coding, one group of frames at a time
  MvidWriterSettings settings;
  settings.levels = options.levels;
  settings.codec = options.codec;
  settings.qp = QualityToQp(options.codec, options.quality);
  settings.effort = options.effort;
  settings.gof_size = options.gof_size;
  settings.frame_rate = source.frame_rate();
  settings.frame_count = static_cast<std::uint32_t>(frames);
  settings.metadata_json = options.metadata_json;
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<MvidWriter> writer,
                           MvidWriter::Create(std::move(sink), base, motion, settings));
  const RegularSubdivision& lattice = writer->subdivision();
  summary.samples_per_frame = lattice.samples().size();
  const SampleGraph graph = SampleGraph::Build(lattice);
  DetailOptions detail;
  detail.shot.max_distance = lengths.detail_max_distance;
  detail.shot.min_abs_cos = seg.shot.min_abs_cos;
  detail.outlier_distance = lengths.outlier_distance;
  std::vector<float> last_measured;
  std::vector<Eigen::Vector3f> posed;
  std::size_t filled = 0, hits = 0;
  for (int group = first; group < end; group += options.gof_size) {
    const int group_end = std::min(end, group + options.gof_size);
    const std::vector<std::vector<RigidTransform>> group_tracks(
        tracks.begin() + (group - first), tracks.begin() + (group_end - first));
    const auto decoded_tracks = writer->DequantizeTransforms(group_tracks);
    std::vector<std::vector<float>> displacements(group_end - group);
    auto detail_start = Clock::now();
    for (int t = group; t < group_end; ++t) {
      if (!ReportProgress(progress, "detail", t - first, frames)) {
        return CancelledError("encode cancelled");
      }
      MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, source.LoadFrame(t));
      PoseVertices(motion, decoded_tracks[t - group], writer->decoded_base().positions, &posed);
      MESHVID_ASSIGN_OR_RETURN(std::size_t frame_hits,
                               MeasureDisplacements(lattice, posed, views, detail,
                                                    &displacements[t - group]));
      hits += frame_hits;
    }
    filled += FillDisplacementGroup(graph, &last_measured, &displacements);
    summary.seconds_detail += SecondsSince(detail_start);
    auto coding_start = Clock::now();
    MESHVID_RETURN_IF_ERROR(writer->WriteGroup(group_tracks, displacements));
    summary.seconds_coding += SecondsSince(coding_start);
  }
  MESHVID_RETURN_IF_ERROR(writer->Finish());
  ReportProgress(progress, "detail", frames, frames);
  const double total = double(summary.samples_per_frame) * frames;
  summary.filled_share = total > 0 ? double(filled) / total : 0;
  summary.hit_share = total > 0 ? double(hits) / total : 0;
  summary.stats = writer->stats();
  return summary;
}

}  // namespace meshvid
