// The capture simulator: turns ground truth (an animated mesh) into the files a multi-view
// range-camera rig would produce: one range mesh per view per frame, a manifest with the
// calibration, and the ground truth of the simulated frames beside them.
#ifndef MESHVID_TOOLS_SIM_SIMULATOR_H_
#define MESHVID_TOOLS_SIM_SIMULATOR_H_

#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/progress.h"
#include "format/status.h"
#include "tools/io/mesh_sequence.h"
#include "tools/sim/range_sensor.h"
#include "tools/sim/rig.h"

namespace meshvid {

/// Everything `meshvid simulate` can set.
struct SimulateOptions {
  RigOptions rig;
  SensorOptions sensor;
  /// Ground-truth frames first_frame .. end_frame-1 become capture frames 0..; end_frame < 0
  /// means the end of the sequence.
  int first_frame = 0;
  int end_frame = -1;
  /// How the ground truth was given (recorded in simulate.json).
  std::string ground_truth_spec;
  /// Units of the ground truth, recorded in the manifest.
  std::string units = "m";
  /// Simulate colour: the ground truth's own vertex colours where it has them, else (fixed
  /// connectivity) the albedo PaintAlbedo gives source frame 0, carried by each vertex
  /// through the animation. The views see it through the sensor's colour model, and the
  /// ground truth is written with it. Off: no colour anywhere.
  bool colour = true;
};

/// Where a simulation's colour came from.
enum class ColourSource {
  kNone,         ///< colour off, or ground truth of changing connectivity without colours
  kGroundTruth,  ///< the ground truth's own vertex colours
  kAlbedo,       ///< PaintAlbedo of source frame 0
};

/// "none", "ground truth" or "albedo".
const char* ColourSourceName(ColourSource source);

/// What a simulation produced.
struct SimulateSummary {
  int frames = 0;
  int views = 0;
  long long pixels = 0;         ///< rays cast (frames x views x width x height)
  long long hit_pixels = 0;     ///< rays that met the surface
  long long samples = 0;        ///< samples kept after the sensor's defects
  long long output_bytes = 0;   ///< size of every file written
  double seconds = 0;           ///< wall time of the whole simulation
  std::string manifest_path;
  /// Where the rig looks from: the unit direction from the subject to the rig's centre
  /// (RigCentreDirection), and the subject's depth over width seen from there
  /// (DepthOverWidth of the box over every simulated frame).
  Eigen::Vector3d rig_direction = Eigen::Vector3d::Zero();
  double depth_over_width = 0;
  ColourSource colour_source = ColourSource::kNone;
  /// Each view's exposure gain (ViewExposureGain), when there is colour.
  std::vector<double> exposure_gains;
};

/// The view file name of capture frame `frame`, view `view`: "f0007_v2.ply".
std::string SimulatedViewFileName(int frame, int view);

/// Simulates frames [first_frame, end_frame) of `ground_truth` into `out_dir` (created if
/// missing): `f{frame:04}_v{view}.ply` (binary PLY, world coordinates), `manifest.json`
/// (calibration, for CaptureSequence::Open), `simulate.json` (the options and the source
/// frame offset) and the ground truth of those frames: `ground_truth.obj` + `.pc2` for fixed
/// connectivity, else `ground_truth/f{frame:04}.obj`, with vertex colours when colour is
/// simulated (SimulateOptions::colour). Cameras aim at the centre of the
/// bounding box over the simulated frames. Reports progress per frame ("simulating").
StatusOr<SimulateSummary> SimulateCapture(MeshSequence& ground_truth, const std::string& out_dir,
                                          const SimulateOptions& options,
                                          const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_SIMULATOR_H_
