// A simulated range sensor: ray-cast depth, then the sensor's defects (noise along the ray,
// grazing-angle rejection, random drop-outs), meshed like a real range image.
#ifndef MESHVID_TOOLS_SIM_RANGE_SENSOR_H_
#define MESHVID_TOOLS_SIM_RANGE_SENSOR_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "format/status.h"
#include "tools/io/range_grid.h"
#include "tools/sim/raycaster.h"

namespace meshvid {

/// The defects of the simulated sensor.
struct SensorOptions {
  /// Standard deviation of the Gaussian noise added along each ray, in scene units.
  double noise_sigma = 0.001;
  /// Samples whose ray meets the surface at more than this angle from its normal are lost.
  double max_angle_deg = 75.0;
  /// Probability that a sample is dropped, in [0, 1).
  double dropout = 0.0;
  /// Seeds the noise and drop-outs; each sample draws from a hash of (seed, frame, view,
  /// pixel), so results do not depend on the thread count.
  std::uint64_t seed = 1;
  /// The depth-jump rule used when meshing the range image.
  RangeGridMeshing meshing;
  /// Colour, when the ray-cast mesh has vertex colours: each view scales the surface's colour
  /// by its own exposure gain, exp(exposure_spread * g) with g a standard normal drawn once
  /// per view (fixed through the capture, as a camera's exposure is), then adds Gaussian noise
  /// of colour_noise (8-bit units) per channel and sample, and rounds to 8 bits. Colour draws
  /// are separate from the depth draws: a capture's geometry is the same with or without
  /// colour.
  double exposure_spread = 0.1;
  double colour_noise = 2.0;
};

/// Checks the sensor options; the message names the bad option.
Status ValidateSensorOptions(const SensorOptions& options);

/// One view's range image after the sensor's defects, with counts.
struct RangeScan {
  RangeGrid grid;         ///< world-coordinate samples, depth 0 where invalid; colours when
                          ///< the image has them
  long hit_pixels = 0;    ///< pixels whose ray met the surface
  long valid_samples = 0; ///< samples kept (after grazing rejection and drop-out)
};

/// Applies the sensor model to a ray-cast image of view `view` at capture frame `frame`
/// (both only seed the random draws). `camera` must be the calibration the image was cast
/// with.
RangeScan ApplySensorModel(const RayCastImage& image, const ViewCalibration& camera,
                           const SensorOptions& options, int frame, int view);

/// The exposure gain of view `view` under `options` (see SensorOptions::exposure_spread).
double ViewExposureGain(const SensorOptions& options, int view);

/// A rig of range sensors simulating one frame at a time.
class CaptureSimulator {
 public:
  /// Fails if `views` is empty, a view lacks intrinsics, or the options are invalid.
  static StatusOr<std::unique_ptr<CaptureSimulator>> Create(std::vector<ViewCalibration> views,
                                                            const SensorOptions& options);

  /// Ray-casts every view of `mesh` in parallel and applies the sensor model; `frame` is the
  /// capture frame number (it seeds the random draws).
  StatusOr<std::vector<RangeScan>> ScanFrame(const TriangleMesh& mesh, int frame);

  /// ScanFrame, then meshes each view's range image (TriangulateRangeGrid) in parallel.
  /// `scans`, if not null, receives the range images.
  StatusOr<std::vector<TriangleMesh>> SimulateFrame(const TriangleMesh& mesh, int frame,
                                                    std::vector<RangeScan>* scans = nullptr);

  const std::vector<ViewCalibration>& views() const { return views_; }
  const SensorOptions& options() const { return options_; }

 private:
  CaptureSimulator() = default;
  std::vector<ViewCalibration> views_;
  SensorOptions options_;
  std::unique_ptr<RayCaster> caster_;
};

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_RANGE_SENSOR_H_
