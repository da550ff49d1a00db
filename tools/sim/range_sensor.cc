#include "tools/sim/range_sensor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "codec/common/counter_random.h"

namespace meshvid {
namespace {

/// A standard normal draw from two counter-based uniforms (Box-Muller).
double Gaussian(std::uint64_t key_a, std::uint64_t key_b) {
  return std::sqrt(-2.0 * std::log(UniformOpen(SplitMix64(key_a)))) *
         std::cos(2.0 * std::numbers::pi * UniformOpen(SplitMix64(key_b)));
}

/// Keys of the colour draws: far from the depth draws' key + 1..3.
constexpr std::uint64_t kColourKeyOffset = 16;
constexpr std::uint64_t kExposureKey = 0x6578706f73757265ULL;  // "exposure"

}  // namespace

Status ValidateSensorOptions(const SensorOptions& options) {
  if (!(options.noise_sigma >= 0) || !std::isfinite(options.noise_sigma)) {
    return InvalidArgumentError("noise sigma must be finite and >= 0 (got " +
                                std::to_string(options.noise_sigma) + ")");
  }
  if (!(options.dropout >= 0 && options.dropout < 1)) {
    return InvalidArgumentError("drop-out probability must be in [0, 1) (got " +
                                std::to_string(options.dropout) + ")");
  }
  if (!(options.max_angle_deg > 0 && options.max_angle_deg <= 90)) {
    return InvalidArgumentError("maximum grazing angle must be in (0, 90] degrees (got " +
                                std::to_string(options.max_angle_deg) + ")");
  }
  if (!(options.exposure_spread >= 0 && options.exposure_spread <= 1)) {
    return InvalidArgumentError("exposure spread must be in [0, 1] (got " +
                                std::to_string(options.exposure_spread) + ")");
  }
  if (!(options.colour_noise >= 0 && options.colour_noise <= 255)) {
    return InvalidArgumentError("colour noise must be in [0, 255] 8-bit units (got " +
                                std::to_string(options.colour_noise) + ")");
  }
  if (!(options.meshing.max_depth_jump_ratio > 0)) {
    return InvalidArgumentError("depth-jump ratio must be > 0");
  }
  return Status::Ok();
}

double ViewExposureGain(const SensorOptions& options, int view) {
  if (options.exposure_spread == 0) return 1.0;
  const std::uint64_t key =
      SplitMix64(SplitMix64(options.seed ^ kExposureKey) ^ static_cast<std::uint64_t>(view));
  return std::exp(options.exposure_spread * Gaussian(key + 1, key + 2));
}

RangeScan ApplySensorModel(const RayCastImage& image, const ViewCalibration& camera,
                           const SensorOptions& options, int frame, int view) {
  RangeScan scan;
  RangeGrid& grid = scan.grid;
  grid.width = image.width;
  grid.height = image.height;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  grid.points.assign(pixels, Eigen::Vector3f::Zero());
  grid.depth.assign(pixels, 0.0f);
  if (pixels == 0 || !camera.intrinsics) return scan;
  const bool coloured = image.colour.size() == pixels;
  if (coloured) grid.colours.assign(pixels, Colour::Zero());
  const float gain = static_cast<float>(ViewExposureGain(options, view));
  const PinholeIntrinsics& k = *camera.intrinsics;
  const Eigen::Matrix3d rotation = camera.world_from_camera.linear();
  const Eigen::Vector3d origin = camera.world_from_camera.translation();
  const double min_cos = std::cos(options.max_angle_deg * std::numbers::pi / 180.0);
  const std::uint64_t view_key =
      SplitMix64(SplitMix64(SplitMix64(options.seed) ^ static_cast<std::uint64_t>(frame)) ^
          static_cast<std::uint64_t>(view));
  std::atomic<long> hits{0}, kept{0};

  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 8), [&](const auto& rows) {
    long local_hits = 0, local_kept = 0;
    for (int v = rows.begin(); v != rows.end(); ++v) {
      for (int u = 0; u < image.width; ++u) {
        const std::size_t pixel = static_cast<std::size_t>(v) * image.width + u;
        const float hit_depth = image.depth[pixel];
        if (!(hit_depth > 0)) continue;
        ++local_hits;
        // Grazing angles: tiny tolerance so an angle of exactly max_angle_deg is kept.
        if (image.cos_incidence[pixel] < min_cos - 1e-7) continue;
        const std::uint64_t key = SplitMix64(view_key ^ pixel);
        if (options.dropout > 0 && UniformOpen(SplitMix64(key + 1)) < options.dropout) continue;
        const Eigen::Vector3d ray = k.RayThrough(u, v);  // camera frame, z = 1
        double depth = hit_depth;
        if (options.noise_sigma > 0) {
          // One standard normal draw, applied along the ray.
          depth += options.noise_sigma * Gaussian(key + 2, key + 3) / ray.norm();
        }
        if (!(depth > 0)) continue;
        grid.depth[pixel] = static_cast<float>(depth);
        grid.points[pixel] = (origin + rotation * (depth * ray)).cast<float>();
        if (coloured) {
          for (int c = 0; c < 3; ++c) {
            const std::uint64_t colour_key = key + kColourKeyOffset + 2 * c;
            double value = gain * image.colour[pixel][c];
            if (options.colour_noise > 0) {
              value += options.colour_noise * Gaussian(colour_key, colour_key + 1);
            }
            grid.colours[pixel][c] =
                static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
          }
        }
        ++local_kept;
      }
    }
    hits += local_hits;
    kept += local_kept;
  });
  scan.hit_pixels = hits.load();
  scan.valid_samples = kept.load();
  return scan;
}

StatusOr<std::unique_ptr<CaptureSimulator>> CaptureSimulator::Create(
    std::vector<ViewCalibration> views, const SensorOptions& options) {
  if (views.empty()) return InvalidArgumentError("the capture rig has no views");
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (!views[i].intrinsics) {
      return InvalidArgumentError("view " + std::to_string(i) + " has no intrinsics");
    }
  }
  MESHVID_RETURN_IF_ERROR(ValidateSensorOptions(options));
  std::unique_ptr<CaptureSimulator> simulator(new CaptureSimulator);
  simulator->views_ = std::move(views);
  simulator->options_ = options;
  MESHVID_ASSIGN_OR_RETURN(simulator->caster_, RayCaster::Create());
  return simulator;
}

StatusOr<std::vector<RangeScan>> CaptureSimulator::ScanFrame(const TriangleMesh& mesh,
                                                             int frame) {
  MESHVID_RETURN_IF_ERROR(caster_->SetMesh(mesh));
  std::vector<RangeScan> scans(views_.size());
  std::vector<Status> errors(views_.size());
  tbb::parallel_for(std::size_t{0}, views_.size(), [&](std::size_t i) {
    RayCastImage image;
    StatusOr<long> hits = caster_->Cast(views_[i], &image);
    if (!hits.ok()) {
      errors[i] = hits.status();
      return;
    }
    scans[i] = ApplySensorModel(image, views_[i], options_, frame, static_cast<int>(i));
  });
  for (const Status& error : errors) MESHVID_RETURN_IF_ERROR(error);
  return scans;
}

StatusOr<std::vector<TriangleMesh>> CaptureSimulator::SimulateFrame(
    const TriangleMesh& mesh, int frame, std::vector<RangeScan>* scans_out) {
  MESHVID_ASSIGN_OR_RETURN(std::vector<RangeScan> scans, ScanFrame(mesh, frame));
  std::vector<TriangleMesh> meshes(scans.size());
  tbb::parallel_for(std::size_t{0}, scans.size(), [&](std::size_t i) {
    meshes[i] = TriangulateRangeGrid(scans[i].grid, options_.meshing);
  });
  if (scans_out != nullptr) *scans_out = std::move(scans);
  return meshes;
}

}  // namespace meshvid
