#include "codec/enc/encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "codec/enc/coding/mvid_writer.h"
#include "codec/enc/key_groups/colour.h"
#include "codec/enc/key_groups/detail.h"
#include "codec/enc/key_groups/key_frame_ahead.h"
#include "codec/enc/key_groups/key_group_analysis.h"
#include "codec/enc/key_groups/tracking_targets.h"

namespace meshvid {
namespace {

Lengths DeriveLengths(const EncoderOptions& o, float scale) {
  auto pick = [scale](double value, double fraction) {
    return static_cast<float>(value > 0 ? value : fraction * scale);
  };
  Lengths l;
  l.scale = scale;
  l.max_distance = pick(o.tuning.max_distance, 0.08);
  l.tolerance = pick(o.tuning.tolerance, 0.005);
  // One base for the whole capture must absorb every tracking error in its displacements;
  // where key groups may be cut, a frame beyond a narrow range gets a fresh base instead.
  l.detail_max_distance = pick(o.tuning.detail_max_distance, o.max_key_groups == 1 ? 0.02 : 0.005);
  l.outlier_distance = pick(o.tuning.outlier_distance, 0.005);
  l.base_max_error = pick(o.tuning.base_max_error, 0.01);
  l.reacquire_max_distance = pick(o.tuning.reacquire_max_distance, 0.25);
  // Below quality 30 the nodes thin out with the base, by the square root of its coarsening:
  // at 4% apart a coarse base's node tracks outweigh its base and video, and as coarse as
  // the base a folding sheet is no longer followed (bench/QUALITY.md).
  l.node_spacing =
      static_cast<float>(std::sqrt(BaseCoarsening(o.quality))) * pick(o.tuning.node_spacing, 0.04);
  // Edge bounds for the deformation's nodes (4% apart) to bend the base and find data along
  // it (at quality 30 and above; below, the base coarsens with its bounds: MakeBaseMesh).
  l.base_max_edge = pick(o.tuning.base_max_edge, 0.03);
  l.proxy_max_edge = pick(o.tuning.proxy_max_edge, 0.04);
  l.farthest_growth =
      o.tuning.farthest_growth > 0 ? static_cast<float>(o.tuning.farthest_growth) : l.max_distance;
  return l;
}

/// Key frames whose bases are made ahead after a key group of one frame (base_ahead): a base
/// is mostly a decimation on one core, so two made beside the key group's own analysis keep
/// both cores busy.
constexpr int kBasesAhead = 2;

/// Translation step of the transform tracks as a fraction of the size, by default
/// (EncoderTuning::transform_step).
constexpr double kTransformStepFraction = 1.0 / 8192;

/// Finest translation step an option may set, as a fraction of the size: the quantised
/// values of a capture that moves a few sizes stay far inside 32 bits.
constexpr double kFinestTransformStepFraction = 1e-6;

/// The transform tracks' quantisation steps (EncoderTuning::transform_step) for a capture
/// whose first frame's views span `box`, of size `scale` (the box's diagonal). The rotation
/// step is the finest a key group uses: one that holds any point of the reach about the
/// origin; each key group coarsens it to its segments' own reach (MvidWriterSettings::motion).
StatusOr<MotionQuantization> TransformSteps(const EncoderOptions& o, float scale,
                                            const Eigen::AlignedBox3f& box) {
  double corner = 0;
  for (int c = 0; c < 8; ++c) {
    const auto which = static_cast<Eigen::AlignedBox3f::CornerType>(c);
    corner = std::max(corner, double(box.corner(which).norm()));
  }
  const double given =
      o.tuning.transform_step > 0 ? o.tuning.transform_step : kTransformStepFraction * scale;
  if (given < kFinestTransformStepFraction * scale) {
    return InvalidArgumentError("tuning.transform_step " + std::to_string(given) +
                                " is finer than 1e-6 of the capture's size (" +
                                std::to_string(scale) + ")");
  }
  const double translation = BaseCoarsening(o.quality) * given;
  MotionQuantization steps;
  steps.translation_step = static_cast<float>(translation);
  // Below 1 radian as MOTN requires (a step that coarse would not be useful anyway).
  steps.rotation_step = static_cast<float>(std::min(0.5, translation / (corner + scale)));
  return steps;
}

/// Measures, fills (over up to `window` frames of the key group at once, before and after
/// in time) and writes the displacement frames of one key group.
Status EncodeKeyGroupDetail(const EncodeContext& ctx, const KeyGroupAnalysis& analysis,
                            MvidWriter* writer, EncodeSummary* summary, std::size_t* filled,
                            std::size_t* hits, std::size_t* samples) {
  const EncoderOptions& options = ctx.options;
  const RegularSubdivision& lattice = writer->subdivision();
  const SampleGraph graph = SampleGraph::Build(lattice);
  DetailOptions detail;
  detail.shot.max_distance = ctx.lengths.detail_max_distance;
  detail.shot.min_abs_cos = ctx.shot.min_abs_cos;
  detail.outlier_distance = ctx.lengths.outlier_distance;
  const int first = analysis.summary.first_frame;
  const int frames = analysis.summary.frames;
  *samples += lattice.samples().size() * static_cast<std::size_t>(frames);
  // Chunks of whole groups of frames, at most about `window` frames.
  const int chunk = std::max(1, options.tuning.window / options.gof_size) * options.gof_size;
  std::vector<float> last_measured;
  std::vector<Eigen::Vector3f> posed;
  const bool colour = writer->settings().colour;
  std::array<std::vector<float>, 3> last_colour;  // per channel, as last_measured
  ColourObservations observations;
  for (int chunk_first = 0; chunk_first < frames; chunk_first += chunk) {
    const int chunk_end = std::min(frames, chunk_first + chunk);
    const std::vector<std::vector<RigidTransform>> chunk_tracks(
        analysis.tracks.begin() + chunk_first, analysis.tracks.begin() + chunk_end);
    const auto decoded_tracks = writer->DequantizeTransforms(chunk_tracks);
    std::vector<std::vector<float>> displacements(chunk_end - chunk_first);
    // Per channel, per frame, per sample: the fused colour, filled like the displacements.
    std::array<std::vector<std::vector<float>>, 3> channels;
    for (auto& channel : channels) channel.resize(colour ? chunk_end - chunk_first : 0);
    auto detail_start = Clock::now();
    for (int k = 0; k < chunk_end - chunk_first; ++k) {
      const int t = first + chunk_first + k;
      if (!ReportProgress(ctx.progress, "detail", t - ctx.options.first_frame,
                          ctx.end - ctx.options.first_frame)) {
        return Cancelled();
      }
      MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, ctx.source.LoadFrame(t));
      PoseVertices(writer->motion(), decoded_tracks[k], writer->decoded_base().positions, &posed);
      MESHVID_ASSIGN_OR_RETURN(
          std::size_t frame_hits,
          MeasureDisplacements(lattice, posed, views, detail, &displacements[k],
                               ctx.source.view_cameras(), colour ? &observations : nullptr));
      *hits += frame_hits;
      if (colour) {
        std::array<std::vector<float>, 3> fused;
        FuseColours(observations, EstimateExposureGains(observations), &fused);
        for (int c = 0; c < 3; ++c) channels[c][k] = std::move(fused[c]);
      }
    }
    *filled += FillDisplacementGroup(graph, &last_measured, &displacements);
    std::vector<std::vector<Colour>> colours;
    if (colour) colours = FillColours(graph, &channels, &last_colour);
    summary->seconds_detail += SecondsSince(detail_start);
    auto coding_start = Clock::now();
    for (int g = 0; g < chunk_end - chunk_first; g += options.gof_size) {
      const int g_end = std::min(chunk_end - chunk_first, g + options.gof_size);
      std::vector<std::vector<Colour>> group_colours;
      if (colour) group_colours.assign(colours.begin() + g, colours.begin() + g_end);
      MESHVID_RETURN_IF_ERROR(writer->WriteGroup(
          {chunk_tracks.begin() + g, chunk_tracks.begin() + g_end},
          {displacements.begin() + g, displacements.begin() + g_end}, group_colours));
    }
    summary->seconds_coding += SecondsSince(coding_start);
  }
  return Status::Ok();
}

/// The writer's settings for an encode of `frames` frames of `source`.
MvidWriterSettings WriterSettings(const EncoderOptions& options, const FrameSource& source,
                                  int frames, const MotionQuantization& transform_steps,
                                  bool capture_has_colour) {
  MvidWriterSettings settings;
  settings.levels = options.levels;
  settings.codec = options.codec;
  settings.qp = QualityToQp(options.codec, options.quality);
  settings.effort = options.effort;
  settings.base.position_bits = options.tuning.base_position_bits;
  settings.gof_size = options.gof_size;
  settings.frame_rate = source.frame_rate();
  settings.frame_count = static_cast<std::uint32_t>(frames);
  settings.metadata_json = options.metadata_json;
  settings.motion = transform_steps;
  settings.colour = capture_has_colour && options.colour;
  settings.colour_qp = QualityToQp(
      options.codec, options.colour_quality >= 0 ? options.colour_quality : options.quality);
  return settings;
}

/// What the key groups made ahead of time, on other threads or by an earlier key group, and
/// hand to the key group that starts at their frame: proxies, bases made ahead after a key
/// group of one frame (key_frame_ahead.h), and a later key frame's base that did not serve
/// (KeyGroupAnalysis::unused_base).
class MadeAhead {
 public:
  explicit MadeAhead(const EncodeContext& ctx) : ctx_(ctx), ahead_(ctx) {}

  ProxyCache& proxies() { return proxies_; }

  /// Before the key group at `start` is analysed: takes the proxies made for it and the
  /// frames its analysis looks at, and returns its base if one was made.
  std::optional<TriangleMesh> TakeFor(int start) {
    for (int next = start; next <= start + kBasesAhead; ++next) {
      if (!proxies_.count(next)) TakeProxy(next);
    }
    std::optional<TriangleMesh> base = ahead_.TakeBase(start);
    if (!base && unused_base_frame_ == start) base = std::move(unused_base_);
    return base;
  }

  /// After a key group of one frame the subject moves fast, and the next key groups likely
  /// hold one frame too: their bases are started now, beside this key group's analysis.
  Status StartAfter(int start) {
    for (int next = start + 1; next <= start + kBasesAhead && next < ctx_.end; ++next) {
      if (ahead_.Started(next)) continue;
      MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, ctx_.source.LoadFrame(next));
      ahead_.Start(next, std::move(views));
    }
    return Status::Ok();
  }

  /// A later key frame's base (tuning.deform_backward_frames) if made ahead, its proxy put in
  /// the cache.
  std::optional<TriangleMesh> TakeLaterBase(int frame) {
    if (!proxies_.count(frame)) TakeProxy(frame);
    return ahead_.TakeBase(frame);
  }

  /// Keeps the analysis' unused later base for the key group that may start at its frame.
  void KeepUnused(KeyGroupAnalysis& analysis) {
    if (!analysis.unused_base) return;
    unused_base_ = std::move(analysis.unused_base);
    unused_base_frame_ = analysis.unused_base_frame;
  }

 private:
  void TakeProxy(int frame) {
    if (std::optional<FrameProxy> proxy = ahead_.TakeProxy(frame)) {
      proxies_[frame] = *std::move(proxy);
    }
  }

  const EncodeContext& ctx_;
  ProxyCache proxies_;
  KeyFrameAhead ahead_;
  std::optional<TriangleMesh> unused_base_;
  int unused_base_frame_ = -1;
};

/// The means over the key groups and the shares of the displacement samples, once every key
/// group is written.
void Summarise(std::size_t filled, std::size_t hits, std::size_t samples, const MvidWriter& writer,
               EncodeSummary* summary) {
  const double key_groups = double(summary->key_groups.size());
  double segments = 0, rigid_groups = 0;
  for (const KeyGroupSummary& k : summary->key_groups) {
    segments += k.segments;
    rigid_groups += k.rigid_groups;
    summary->surface_share += k.surface_share / key_groups;
  }
  summary->segments = static_cast<int>(std::lround(segments / key_groups));
  summary->rigid_groups = static_cast<int>(std::lround(rigid_groups / key_groups));
  summary->base_vertices = summary->key_groups.front().base_vertices;
  const double total = double(samples);
  summary->filled_share = total > 0 ? double(filled) / total : 0;
  summary->hit_share = total > 0 ? double(hits) / total : 0;
  summary->stats = writer.stats();
}

}  // namespace

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

  // Lengths follow the first frame's size, for every key group alike.
  float scale = 0;
  MotionQuantization transform_steps;
  bool capture_has_colour = false;
  {
    MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh> views, source.LoadFrame(first));
    capture_has_colour = ViewsHaveColour(views);
    const Eigen::AlignedBox3f box = BoxOf(views);
    scale = box.isEmpty() ? 0.0f : box.diagonal().norm();
    if (!(scale > 0)) {
      return InvalidArgumentError("frame " + std::to_string(first) + " holds no surface");
    }
    MESHVID_ASSIGN_OR_RETURN(transform_steps, TransformSteps(options, scale, box));
  }
  EncodeContext ctx{source, options, progress, DeriveLengths(options, scale), {}, end, {}};
  if (options.tuning.seen_free_space) ctx.view_cameras = source.view_cameras();
  for (int v = 0; v < std::min<int>(source.view_count(), ctx.view_cameras.size()); ++v) {
    summary.free_space_views += ctx.view_cameras[v].CanProject();
  }
  summary.scale = scale;
  summary.tolerance = ctx.lengths.tolerance;
  ctx.shot.max_distance = ctx.lengths.max_distance;
  ctx.shot.min_abs_cos =
      static_cast<float>(std::cos(options.tuning.max_angle_degrees * M_PI / 180));

  const MvidWriterSettings settings =
      WriterSettings(options, source, frames, transform_steps, capture_has_colour);
  std::unique_ptr<MvidWriter> writer;
  std::size_t filled = 0, hits = 0, samples = 0;
  MadeAhead ahead(ctx);
  TrackingTargets targets(ctx, &ahead.proxies());  // after `ahead`: it keeps proxies there
  MotionHint hint;  // how the surface moved into the frame that ended the last key group
  for (int start = first; start < end;) {
    const bool may_cut = options.max_key_groups == 0 ||
                         static_cast<int>(summary.key_groups.size()) + 1 < options.max_key_groups;
    auto analysis_start = Clock::now();
    const bool after_one_frame =
        !summary.key_groups.empty() && summary.key_groups.back().frames == 1;
    std::optional<TriangleMesh> base_made_ahead = ahead.TakeFor(start);
    const double seconds_waited = SecondsSince(analysis_start);
    if (options.tuning.base_ahead && may_cut && after_one_frame && !options.base_mesh) {
      MESHVID_RETURN_IF_ERROR(ahead.StartAfter(start));
    }
    MESHVID_ASSIGN_OR_RETURN(
        KeyGroupAnalysis analysis,
        AnalyseKeyGroup(ctx, start, may_cut, hint, &targets, std::move(base_made_ahead),
                        [&ahead](int frame) { return ahead.TakeLaterBase(frame); }));
    analysis.seconds_base += seconds_waited;
    hint = std::move(analysis.hint);
    ahead.KeepUnused(analysis);
    summary.seconds_base += analysis.seconds_base;
    summary.seconds_tracking += SecondsSince(analysis_start) - analysis.seconds_base;
    if (!writer) {
      MESHVID_ASSIGN_OR_RETURN(
          writer, MvidWriter::Create(std::move(sink), analysis.base, analysis.motion, settings,
                                     analysis.tracks));
      summary.samples_per_frame = writer->subdivision().samples().size();
    } else {
      MESHVID_RETURN_IF_ERROR(
          writer->StartKeyGroup(analysis.base, analysis.motion, analysis.tracks));
    }
    MESHVID_RETURN_IF_ERROR(
        EncodeKeyGroupDetail(ctx, analysis, writer.get(), &summary, &filled, &hits, &samples));
    summary.key_groups.push_back(analysis.summary);
    start += analysis.summary.frames;
  }
  MESHVID_RETURN_IF_ERROR(writer->Finish());
  ReportProgress(progress, "detail", frames, frames);
  Summarise(filled, hits, samples, *writer, &summary);
  return summary;
}

}  // namespace meshvid
