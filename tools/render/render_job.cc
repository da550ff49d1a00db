#include "tools/render/render_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "tools/eval/eval_source.h"
#include "tools/eval/surface_distance.h"
#include "tools/io/file_pattern.h"
#include "tools/render/error_colours.h"
#include "tools/render/mp4_writer.h"
#include "tools/render/surface_renderer.h"
#include "tools/sim/ground_truth.h"

namespace meshvid {
namespace {

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// One panel: its source, renderer and whether it is coloured by error.
struct Panel {
  std::string label;
  std::unique_ptr<MeshSequence> source;
  SurfaceRenderer renderer;
  bool coloured = false;
};

/// The bounds of the first input over up to 5 frames spread over the range, so one camera
/// keeps the subject in the picture throughout.
StatusOr<Eigen::AlignedBox3f> SubjectBounds(MeshSequence& source, int first, int end) {
  Eigen::AlignedBox3f bounds;
  const int samples = std::min(5, end - first);
  for (int k = 0; k < samples; ++k) {
    const int frame = first + (samples > 1 ? k * (end - 1 - first) / (samples - 1) : 0);
    MESHVID_ASSIGN_OR_RETURN(const TriangleMesh mesh, source.Frame(frame));
    bounds.extend(BoundingBox(mesh));
  }
  return bounds;
}

/// The median of `distances`.
float Median(std::vector<float> distances) {
  if (distances.empty()) return 0;
  const std::size_t k = distances.size() / 2;
  std::nth_element(distances.begin(), distances.begin() + k, distances.end());
  return distances[k];
}

}  // namespace

float RoundUpNicely(float value) {
  if (!(value > 0)) return 1;
  const float power = std::pow(10.0f, std::floor(std::log10(value)));
  for (float step : {1.0f, 2.0f, 5.0f, 10.0f}) {
    if (step * power >= value * 0.9999f) return step * power;
  }
  return 10 * power;
}

StatusOr<std::unique_ptr<MeshSequence>> OpenRenderInput(const std::string& spec, int level,
                                                        bool allow_partial) {
  if (spec.starts_with("scene:")) return OpenGroundTruth(spec);
  return OpenEvalTestSource(spec, level, allow_partial);
}

std::string PanelLabel(const std::string& spec, int level) {
  if (LooksLikeCapture(spec)) return "input views";
  if (spec.starts_with("scene:")) return "ground truth " + spec.substr(6);
  const std::string name = std::filesystem::path(spec).filename().string();
  if (EndsWith(spec, ".mvid")) {
    return name + (level >= 0 ? " L" + std::to_string(level) : "");
  }
  const std::string stem = std::filesystem::path(spec).stem().string();
  return stem == "ground_truth" ? "ground truth" : "ground truth " + stem;
}

StatusOr<RenderJobStats> RunRenderJob(const RenderJobOptions& options,
                                      const ProgressCallback& progress) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  if (options.inputs.empty()) return InvalidArgumentError("render: no input");
  if (options.width < 16 || options.height < 16 || options.width > 8192 ||
      options.height > 8192) {
    return InvalidArgumentError("render: a panel must be 16x16 to 8192x8192 pixels");
  }
  const bool mp4 = EndsWith(options.output, ".mp4");
  StatusOr<FilePattern> pattern = FilePattern::Parse(options.output);
  if (!pattern.ok()) return pattern.status().WithContext("-o");
  const bool png_per_frame = pattern->has_frame();
  if (!mp4 && !EndsWith(options.output, ".png")) {
    return InvalidArgumentError("render: -o must end in .png or .mp4");
  }
  if (mp4 && png_per_frame) return InvalidArgumentError("render: an MP4 takes no {frame}");

  std::vector<Panel> panels(options.inputs.size());
  int frames_available = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < panels.size(); ++i) {
    MESHVID_ASSIGN_OR_RETURN(
        panels[i].source, OpenRenderInput(options.inputs[i], options.level, options.allow_partial));
    panels[i].label = PanelLabel(options.inputs[i], options.level);
    panels[i].coloured = !options.error_against.empty() && options.inputs[i] != options.error_against;
    frames_available = std::min(frames_available, panels[i].source->frame_count());
  }
  std::unique_ptr<MeshSequence> reference;
  if (!options.error_against.empty()) {
    MESHVID_ASSIGN_OR_RETURN(reference,
                             OpenRenderInput(options.error_against, -1, options.allow_partial));
    frames_available = std::min(frames_available, reference->frame_count());
  }
  const int first = options.first_frame;
  int end = options.end_frame < 0 ? frames_available : options.end_frame;
  if (!mp4 && !png_per_frame) end = std::min(end, first + 1);  // one PNG: one frame
  std::string clipped_frames;
  if (first >= 0 && first < frames_available && end > frames_available) {
    clipped_frames = "frames " + std::to_string(first) + ":" + std::to_string(end) +
                     " run past the " + std::to_string(frames_available) +
                     " frames every input has: drawing " + std::to_string(first) + ":" +
                     std::to_string(frames_available);
    end = frames_available;
  }
  if (first < 0 || first >= end || end > frames_available) {
    return InvalidArgumentError("render: frames " + std::to_string(first) + ":" +
                                std::to_string(end) + " are not within the " +
                                std::to_string(frames_available) +
                                " frames every input has");
  }
  MESHVID_ASSIGN_OR_RETURN(const Eigen::AlignedBox3f bounds,
                           SubjectBounds(*panels[0].source, first, end));
  const RenderCamera camera = FrameBounds(bounds, options.orbit, options.width, options.height);

  RenderJobStats stats;
  stats.clipped_frames = clipped_frames;
  float error_max = options.error_max_mm / 1000.0f;
  std::unique_ptr<Mp4Writer> video;
  const int scale = options.height >= 400 ? 2 : 1;
  for (int frame = first; frame < end; ++frame) {
    std::unique_ptr<SurfaceDistance> distance;
    if (reference) {
      MESHVID_ASSIGN_OR_RETURN(const TriangleMesh truth, reference->Frame(frame));
      MESHVID_ASSIGN_OR_RETURN(distance, SurfaceDistance::Build(truth));
    }
    std::vector<TriangleMesh> meshes;
    std::vector<std::vector<float>> distances(panels.size());
    float worst_median = 0;
    for (std::size_t i = 0; i < panels.size(); ++i) {
      MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, panels[i].source->Frame(frame));
      if (panels[i].coloured) {
        distances[i] = VertexDistances(mesh, *distance);
        if (!(error_max > 0)) worst_median = std::max(worst_median, Median(distances[i]));
      }
      meshes.push_back(std::move(mesh));
    }
    // The scale is fixed by the first frame, then kept: 4 times the worst panel's median
    // distance shows the typical error in mid colours and saturates only outliers.
    if (reference && !(error_max > 0)) {
      error_max = RoundUpNicely(4000.0f * worst_median) / 1000.0f;
    }
    std::size_t last_coloured = panels.size();
    for (std::size_t i = 0; i < panels.size(); ++i) {
      if (panels[i].coloured) last_coloured = i;
    }
    std::vector<RgbImage> pictures;
    for (std::size_t i = 0; i < panels.size(); ++i) {
      Panel& panel = panels[i];
      std::vector<Eigen::Vector3f> colours;
      if (panel.coloured) {
        colours = ErrorColours(distances[i], error_max);
      } else if (!meshes[i].colours.empty()) {
        // The surface's own colour (a capture's, a coloured file's or the ground truth's).
        colours.reserve(meshes[i].colours.size());
        for (const Colour& c : meshes[i].colours) colours.push_back(c.cast<float>() / 255.0f);
      }
      MESHVID_RETURN_IF_ERROR(panel.renderer.SetMesh(meshes[i], std::move(colours)));
      RgbImage picture = panel.renderer.Render(camera);
      if (options.labels) {
        DrawText(&picture, 8 * scale, 8 * scale, panel.label, {240, 240, 240}, scale);
        if (i == 0) {
          DrawText(&picture, 8 * scale, options.height - 15 * scale,
                   "frame " + std::to_string(frame), {240, 240, 240}, scale);
        }
      }
      // One colour bar explains every coloured panel: at the right of the last one.
      if (i == last_coloured) DrawColourBar(&picture, 1000.0f * error_max);
      pictures.push_back(std::move(picture));
    }
    RgbImage picture = pictures.size() == 1 ? std::move(pictures[0]) : SideBySide(pictures);
    if (mp4) {
      picture = PadToEven(picture);
      if (!video) {
        MESHVID_ASSIGN_OR_RETURN(video, Mp4Writer::Create(options.output, picture.width,
                                                          picture.height,
                                                          panels[0].source->frame_rate(),
                                                          options.crf));
        stats.video_codec = video->codec_name();
      }
      MESHVID_RETURN_IF_ERROR(video->AddFrame(picture));
    } else {
      MESHVID_RETURN_IF_ERROR(WritePng(pattern->Expand(frame), picture));
    }
    stats.width = picture.width;
    stats.height = picture.height;
    ++stats.frames;
    if (!ReportProgress(progress, "rendering", frame - first + 1, end - first)) {
      return CancelledError("render cancelled");
    }
  }
  if (video) MESHVID_RETURN_IF_ERROR(video->Finish());
  stats.error_max_mm = 1000.0f * error_max;
  stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return stats;
}

}  // namespace meshvid
