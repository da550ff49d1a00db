#include "tools/sim/simulator.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "codec/common/progress.h"
#include "format/output_file.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_io.h"
#include "tools/io/pc2.h"
#include "tools/sim/albedo.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;

/// Ground-truth frames are kept in memory between the two passes below up to this many
/// vertices in total (~240 MB); beyond, they are read again.
constexpr long long kMaxCachedVertices = 20'000'000;

Status CreateOutputDir(const std::string& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    return InvalidArgumentError(dir + ": exists and is not a folder; choose another -o");
  }
  fs::create_directories(dir, ec);
  if (ec) return IoError("cannot create output folder " + dir + ": " + ec.message());
  return Status::Ok();
}

Status WriteSimulateJson(const std::string& path, const MeshSequence& ground_truth,
                         const SimulateOptions& options, int first, int end,
                         const std::vector<ViewCalibration>& views,
                         const SimulateSummary& summary) {
  nlohmann::ordered_json j;
  j["generator"] = "meshvid simulate";
  j["ground_truth"] = options.ground_truth_spec.empty() ? ground_truth.description()
                                                        : options.ground_truth_spec;
  j["source_first_frame"] = first;
  j["source_end_frame"] = end;
  j["frame_count"] = end - first;
  j["frame_rate"] = ground_truth.frame_rate();
  j["units"] = options.units;
  const RigOptions& rig = options.rig;
  j["rig"] = {{"views", rig.views},
              {"layout", rig.layout == RigLayout::kArc ? "arc" : "ring"},
              {"arc_step_deg", rig.arc_step_deg},
              {"azimuth_deg", rig.azimuth_deg},
              {"up", rig.up == UpAxis::kY ? "y" : "z"},
              {"width", rig.width},
              {"height", rig.height},
              {"fx", views.front().intrinsics->fx},
              {"fy", views.front().intrinsics->fy}};
  const SensorOptions& sensor = options.sensor;
  j["sensor"] = {{"noise_sigma", sensor.noise_sigma},
                 {"max_angle_deg", sensor.max_angle_deg},
                 {"dropout", sensor.dropout},
                 {"seed", sensor.seed},
                 {"max_depth_jump_ratio", sensor.meshing.max_depth_jump_ratio}};
  j["colour"] = {{"source", ColourSourceName(summary.colour_source)},
                 {"exposure_spread", sensor.exposure_spread},
                 {"colour_noise", sensor.colour_noise},
                 {"exposure_gains", summary.exposure_gains}};
  return WriteFileAtomically(path, j.dump(2) + "\n");
}

/// Writes the ground truth of the simulated frames, one frame at a time.
class GroundTruthWriter {
 public:
  static StatusOr<std::unique_ptr<GroundTruthWriter>> Create(const std::string& dir,
                                                             bool fixed_connectivity) {
    std::unique_ptr<GroundTruthWriter> writer(new GroundTruthWriter);
    writer->dir_ = dir;
    writer->fixed_ = fixed_connectivity;
    if (!fixed_connectivity) {
      std::error_code ec;
      fs::create_directories(dir + "/ground_truth", ec);
      if (ec) return IoError("cannot create " + dir + "/ground_truth: " + ec.message());
    }
    return writer;
  }

  Status Append(const TriangleMesh& mesh, int frame, double frame_rate) {
    if (!fixed_) {
      char name[32];
      std::snprintf(name, sizeof(name), "/ground_truth/f%04d.obj", frame);
      paths_.push_back(dir_ + name);
      return WriteMesh(paths_.back(), mesh, {.write_normals = false});
    }
    if (pc2_ == nullptr) {
      paths_.push_back(dir_ + "/ground_truth.obj");
      paths_.push_back(dir_ + "/ground_truth.pc2");
      MESHVID_RETURN_IF_ERROR(WriteMesh(paths_[0], mesh, {.write_normals = false}));
      MESHVID_ASSIGN_OR_RETURN(pc2_, Pc2Writer::Create(paths_[1],
                                                       static_cast<std::int32_t>(
                                                           mesh.vertex_count()),
                                                       0.0f, 1.0f));
    }
    return pc2_->AppendFrame(mesh.positions);
  }

  Status Finish() { return pc2_ != nullptr ? pc2_->Finish() : Status::Ok(); }
  const std::vector<std::string>& paths() const { return paths_; }

 private:
  GroundTruthWriter() = default;
  std::string dir_;
  bool fixed_ = true;
  std::unique_ptr<Pc2Writer> pc2_;
  std::vector<std::string> paths_;
};

/// Decides where the simulated colour comes from (summary->colour_source) and returns the
/// albedo to paint on every frame: empty unless the source is "albedo".
StatusOr<std::vector<Colour>> ChooseColour(MeshSequence& ground_truth, int first,
                                           const SimulateOptions& options,
                                           SimulateSummary* summary) {
  summary->colour_source = ColourSource::kNone;
  if (!options.colour) return std::vector<Colour>();
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh first_mesh, ground_truth.Frame(first));
  if (!first_mesh.colours.empty()) {
    summary->colour_source = ColourSource::kGroundTruth;
    return std::vector<Colour>();
  }
  if (!ground_truth.fixed_connectivity()) return std::vector<Colour>();
  // Source frame 0, whatever the simulated range, so a frame's colour does not depend on it.
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh reference, ground_truth.Frame(0));
  summary->colour_source = ColourSource::kAlbedo;
  return PaintAlbedo(reference);
}

/// Gives `mesh` (source frame `frame`) the colour `source` calls for.
Status ApplyColour(const std::vector<Colour>& albedo, ColourSource source, int frame,
                   TriangleMesh* mesh) {
  if (source == ColourSource::kAlbedo) {
    if (albedo.size() != mesh->vertex_count()) {
      return InvalidArgumentError("ground-truth frame " + std::to_string(frame) + " has " +
                                  std::to_string(mesh->vertex_count()) +
                                  " vertices where frame 0 has " + std::to_string(albedo.size()) +
                                  ": a fixed-connectivity sequence keeps its vertex count");
    }
    mesh->colours = albedo;
  } else if (source == ColourSource::kNone) {
    mesh->colours.clear();
  } else if (mesh->colours.empty()) {
    return InvalidArgumentError("ground-truth frame " + std::to_string(frame) +
                                " has no vertex colours where the first simulated frame has "
                                "them; give every frame colours, or simulate with --no-colour");
  }
  return Status::Ok();
}

long long FileSize(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : static_cast<long long>(size);
}

}  // namespace

const char* ColourSourceName(ColourSource source) {
  switch (source) {
    case ColourSource::kGroundTruth:
      return "ground truth";
    case ColourSource::kAlbedo:
      return "albedo";
    case ColourSource::kNone:
      break;
  }
  return "none";
}

std::string SimulatedViewFileName(int frame, int view) {
  char name[48];
  std::snprintf(name, sizeof(name), "f%04d_v%d.ply", frame, view);
  return name;
}

StatusOr<SimulateSummary> SimulateCapture(MeshSequence& ground_truth, const std::string& out_dir,
                                          const SimulateOptions& options,
                                          const ProgressCallback& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  const int first = options.first_frame;
  const int end = options.end_frame < 0 ? ground_truth.frame_count() : options.end_frame;
  if (first < 0 || end > ground_truth.frame_count() || first >= end) {
    return InvalidArgumentError("frame range " + std::to_string(first) + ":" +
                                std::to_string(end) + " is empty or outside the " +
                                std::to_string(ground_truth.frame_count()) + " frames of " +
                                ground_truth.description());
  }
  MESHVID_RETURN_IF_ERROR(ValidateSensorOptions(options.sensor));
  MESHVID_RETURN_IF_ERROR(CreateOutputDir(out_dir));

  // Pass 1: the bounding box over every simulated frame, which the cameras aim at.
  const int frames = end - first;
  std::vector<TriangleMesh> cache;
  long long cached_vertices = 0;
  bool caching = true;
  Eigen::AlignedBox3d box;
  for (int t = first; t < end; ++t) {
    if (!ReportProgress(progress, "reading ground truth", t - first, frames)) {
      return CancelledError("simulation cancelled");
    }
    MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, ground_truth.Frame(t));
    const Eigen::AlignedBox3f frame_box = BoundingBox(mesh);
    box.extend(frame_box.min().cast<double>());
    box.extend(frame_box.max().cast<double>());
    cached_vertices += static_cast<long long>(mesh.vertex_count());
    caching = caching && cached_vertices <= kMaxCachedVertices;
    if (caching) {
      cache.push_back(std::move(mesh));
    } else {
      cache.clear();
    }
  }
  MESHVID_ASSIGN_OR_RETURN(std::vector<ViewCalibration> views,
                           PlaceCameras(box, options.rig));
  SimulateSummary summary;
  summary.frames = frames;
  summary.views = static_cast<int>(views.size());
  summary.rig_direction = RigCentreDirection(options.rig);
  summary.depth_over_width = DepthOverWidth(box, summary.rig_direction, options.rig.up);
  MESHVID_ASSIGN_OR_RETURN(std::vector<Colour> albedo,
                           ChooseColour(ground_truth, first, options, &summary));
  if (summary.colour_source != ColourSource::kNone) {
    for (int v = 0; v < summary.views; ++v) {
      summary.exposure_gains.push_back(ViewExposureGain(options.sensor, v));
    }
  }
  MESHVID_RETURN_IF_ERROR(WriteSimulateJson(out_dir + "/simulate.json", ground_truth, options,
                                            first, end, views, summary));
  MESHVID_ASSIGN_OR_RETURN(auto simulator, CaptureSimulator::Create(views, options.sensor));
  MESHVID_ASSIGN_OR_RETURN(auto truth_writer, GroundTruthWriter::Create(
                                                  out_dir, ground_truth.fixed_connectivity()));

  // Pass 2: simulate and write every frame.
  const int view_count = summary.views;
  std::vector<std::vector<std::string>> paths(frames, std::vector<std::string>(view_count));
  const double frame_rate = ground_truth.frame_rate() > 0 ? ground_truth.frame_rate() : 25.0;
  for (int f = 0; f < frames; ++f) {
    if (!ReportProgress(progress, "simulating", f, frames)) {
      return CancelledError("simulation cancelled after " + std::to_string(f) + " frames");
    }
    TriangleMesh loaded;
    if (cache.empty()) {
      MESHVID_ASSIGN_OR_RETURN(loaded, ground_truth.Frame(first + f));
    }
    TriangleMesh& mesh = cache.empty() ? loaded : cache[f];
    MESHVID_RETURN_IF_ERROR(ApplyColour(albedo, summary.colour_source, first + f, &mesh));
    std::vector<RangeScan> scans;
    MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> meshes,
                             simulator->SimulateFrame(mesh, f, &scans));
    std::vector<Status> errors(view_count);
    tbb::parallel_for(0, view_count, [&](int v) {
      paths[f][v] = SimulatedViewFileName(f, v);
      errors[v] = WriteMesh(out_dir + "/" + paths[f][v], meshes[v]);
    });
    for (const Status& error : errors) MESHVID_RETURN_IF_ERROR(error);
    for (int v = 0; v < view_count; ++v) {
      summary.pixels += static_cast<long long>(scans[v].grid.width) * scans[v].grid.height;
      summary.hit_pixels += scans[v].hit_pixels;
      summary.samples += scans[v].valid_samples;
      summary.output_bytes += FileSize(out_dir + "/" + paths[f][v]);
    }
    MESHVID_RETURN_IF_ERROR(truth_writer->Append(mesh, f, frame_rate));
    if (!cache.empty()) cache[f] = TriangleMesh();  // free as we go
  }
  MESHVID_RETURN_IF_ERROR(truth_writer->Finish());
  ReportProgress(progress, "simulating", frames, frames);

  CaptureInfo info;
  info.frame_rate = frame_rate;
  info.units = options.units;
  info.frame_count = frames;
  info.camera_coordinates = false;
  info.meshing = options.sensor.meshing;
  for (int v = 0; v < view_count; ++v) {
    CaptureView view;
    view.name = "v" + std::to_string(v);
    view.calibration = views[v];
    info.views.push_back(view);
  }
  summary.manifest_path = out_dir + "/manifest.json";
  MESHVID_RETURN_IF_ERROR(WriteCaptureManifest(summary.manifest_path, info, paths));
  for (const std::string& path : truth_writer->paths()) summary.output_bytes += FileSize(path);
  summary.output_bytes += FileSize(summary.manifest_path) + FileSize(out_dir + "/simulate.json");
  summary.seconds = SecondsSince(start_time);
  return summary;
}

}  // namespace meshvid

