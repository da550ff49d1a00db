// Motion for every base vertex (docs/encoder-method.md section 3.1, post-processing): vertices the
// segmentation left unregistered get blend weights over the segments of their registered neighbours
// (the paper's spatial interpolation of transforms, stated as skinning), and the tracks are
// smoothed over time.
#ifndef MESHVID_CODEC_ENC_MOTION_BLEND_H_
#define MESHVID_CODEC_ENC_MOTION_BLEND_H_

#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/enc/base_topology.h"

namespace meshvid {

/// Blend weights from a segmentation: a registered vertex has its segment with weight 1; an
/// unregistered one averages the weights of its mesh neighbours, spreading outwards from the
/// registered vertices (then `smoothing` Jacobi passes over the unregistered ones), keeping
/// the kMaxInfluences largest weights. Vertices in pieces of the mesh without any registered
/// vertex take the segment of the nearest registered vertex in space. Vertices of segments
/// `soft_from` and above (the patches of patch_tracking.h; -1: none) start with their segment
/// and are smoothed like the interpolated ones, so patches blend into their neighbours.
MotionModel BlendWeightsFromLabels(const BaseTopology& base, std::span<const std::int32_t> labels,
                                   int segment_count, int smoothing = 4, int soft_from = -1);

/// Per piece of `labels` (0..piece_count-1), the centroid of its vertices in `positions`; a
/// piece without vertices gets the centroid of them all.
std::vector<Eigen::Vector3f> PieceCentres(std::span<const Eigen::Vector3f> positions,
                                          std::span<const std::int32_t> labels, int piece_count);

/// Smooths tracks `transforms[frame][segment]` over time: `passes` times, each frame's
/// transform becomes the average of frames t-1, t, t+1, taken about the segment's rest centre
/// `centres[segment]` (none given: the origin): the centre goes to the mean of where the three
/// put it, turned by their mean rotation (normalised quaternion sum, signs aligned). About the
/// centre, the result does not depend on where the capture's origin lies: averaging rotation
/// and translation apart moves a piece far from the origin by its distance times the
/// rotations' spread squared.
void SmoothTracks(int passes, std::span<const Eigen::Vector3f> centres,
                  std::vector<std::vector<RigidTransform>>* transforms);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_MOTION_BLEND_H_
