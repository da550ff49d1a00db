// How well a tracked base mesh explains a frame's captured data: the encoder's rule for
// starting a new key group (a fresh base) where tracking has lost the subject.
#ifndef MESHVID_CODEC_ENC_TRACKING_DATA_FIT_H_
#define MESHVID_CODEC_ENC_TRACKING_DATA_FIT_H_

#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"

namespace meshvid {

/// The fit of captured points to a surface given by dense samples of it.
struct DataFit {
  /// Share of the points farther than the representable distance from the surface: data the
  /// surface's displacements cannot reach, 0..1.
  double unexplained_share = 0;
  double rms_distance = 0;  ///< root mean square point-to-surface distance (sample-based)
  /// Mean over the points of the squared distance by which each lies beyond what the
  /// surface's displacements reach (along the normal past the representable distance, or
  /// across past the surface's edge; 0 for a point within): the error the decoded surface
  /// keeps at the data, whatever the displacements code.
  double excess_mean_square = 0;
  std::size_t points = 0;   ///< points measured (0: the frame had no data)
  /// Share of the surface samples farther than the stray distance from every data point:
  /// surface the motion threw where no data is (a closed body's unseen side stays nearer).
  double stray_share = 0;
  /// The farthest any surface sample is from the data (0 without data).
  double farthest_from_data = 0;
  /// Share of the surface samples some camera can judge (SeenFreeSpace::Judge) that lie in
  /// space a camera saw through, farther in front of what it saw than a displacement reaches
  /// (0 without cameras): a sheet's tracked surface running past its moving edge.
  double seen_through_share = 0;
};

/// Measures how far `data_points` lie from the surface sampled by `surface_samples` (nearest
/// sample, k-d tree). A point is unexplained when it is farther than `representable_distance`
/// from its nearest sample; with `sample_normals` (one per sample), when it is farther than
/// that along the sample's normal (what a displacement can reach) or farther across it than
/// that plus the samples' spacing (beyond the surface's edge), so samples need not be denser
/// than the distance. The spacing is the median distance between neighbouring samples, or per
/// sample the larger of that and `sample_reach[i]` when given (SampleReach: a sliver's samples
/// are far apart along it). A surface sample strays when it is farther than `stray_distance`
/// from every data point.
DataFit MeasureDataFit(std::span<const Eigen::Vector3f> surface_samples,
                       std::span<const Eigen::Vector3f> data_points,
                       float representable_distance, float stray_distance,
                       std::span<const Eigen::Vector3f> sample_normals = {},
                       std::span<const float> sample_reach = {});

/// Per sample of a triangulated sampling (`triangles` over `samples`), how far across the
/// surface a point may lie from it and still be nearest to it: half the longest edge of the
/// triangles around it.
std::vector<float> SampleReach(std::span<const Eigen::Vector3f> samples,
                               std::span<const Triangle> triangles);

/// The share of a key frame's points its own base may leave unexplained: beyond it the fusion
/// failed (a surface that lost most of the subject). Working fusions leave under a tenth, a
/// failed one most (bench/DESIGN-NOTES.md).
inline constexpr double kMostUnexplainedAtKeyFrame = 0.25;

/// The decoded surface's error at data the displacements reach, as a share of the
/// displacement range: sensor noise and the video's quantisation (about 1 mm on a 1 cm range
/// on the shared captures). It keeps the loss estimate below finite where a frame's data all
/// lie within reach.
inline constexpr double kDecodedErrorFloor = 0.1;

/// The mean square error the decoded surface is estimated to keep at a frame's data when
/// posed as `fit` measured it, with displacements reaching `representable_distance`: the data
/// beyond their reach (DataFit::excess_mean_square), the surface lying where a camera saw
/// through (each such sample at least one range off), and the floor (kDecodedErrorFloor).
double DecodedMeanSquare(const DataFit& fit, double representable_distance);

/// Surface a fresh base fused from one frame would lose: what the key group's tracked base
/// holds from earlier frames and the frame's own views do not show, lying away from the
/// frame's fused surface where no camera saw through it.
struct ForgottenSurface {
  /// Share of the key group's observed base vertices, posed at the frame, lying farther than
  /// the displacement range from the frame's fused surface and not in seen free space.
  double share = 0;
  /// Mean square of their distances to the fused surface (each capped), in scene units
  /// squared: a fresh base's error there if the tracked surface is where the subject is.
  double mean_square = 0;
};

/// The estimated D1 loss, in dB, of coding a frame with the key group's tracked base (`frame`,
/// its fit) rather than with a fresh base fused from the frame itself, which is estimated to
/// fit its frame as the key frame's base fits the key frame (`key_frame`): 10 log10 of the
/// ratio of their DecodedMeanSquare. With `forgotten`, that share of the surface is weighed
/// apart: the fresh base errs there by its mean square and the tracked base by the floor
/// (kDecodedErrorFloor). 0 for a frame without data (nothing contradicts the motion); never
/// negative.
double TrackingLossDb(const DataFit& key_frame, const DataFit& frame, double representable_distance,
                      const ForgottenSurface& forgotten = {});

/// Whether a tracked frame stays in its key group: its estimated loss against a fresh base
/// (TrackingLossDb) is at most `allowed_loss_db`, the D1 a fresh base would have to gain to be
/// worth its bytes; and no part of the surface is farther from the data than the key frame's
/// farthest plus `farthest_growth` (a patch the motion threw away, however small, which the
/// sample-based estimate does not see). The surface a fresh base would lose (`forgotten`)
/// enters the loss, but may offset at most `most_excused_db` of the loss at the data alone
/// beyond `allowed_loss_db`. A frame without data stays.
bool StillExplains(const DataFit& key_frame, const DataFit& frame, double representable_distance,
                   double allowed_loss_db, double farthest_growth,
                   const ForgottenSurface& forgotten = {}, double most_excused_db = 0);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_DATA_FIT_H_
