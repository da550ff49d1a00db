// SeenFreeSpace: where the views' cameras saw through. A calibrated range view records, along
// each pixel's ray, the nearest surface its sensor met; space in front of that surface (or
// anywhere along a ray that met nothing) was seen empty. A fused surface lying there is wrong
// (a sheet run on past its real edge), while surface behind a seen one is merely occluded.
#ifndef MESHVID_CODEC_ENC_FUSION_SEEN_FREE_SPACE_H_
#define MESHVID_CODEC_ENC_FUSION_SEEN_FREE_SPACE_H_

#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"

namespace meshvid {

/// Per calibrated view, the depth of the nearest captured surface at every pixel.
class SeenFreeSpace {
 public:
  /// Rasterises views[i] (world coordinates) into the image of cameras[i]. Views whose camera
  /// has no intrinsics or no pose (ViewCalibration::has_extrinsics) are left out, as are views
  /// beyond cameras.size(). Each pixel then holds the nearest depth within `margin_pixels` of
  /// it (a square window), so a point just off the edge of the data is not yet in free space.
  /// A camera speaks only for surface facing it: its normal (pointing out of the object)
  /// within acos(`min_facing_cosine`) of the direction to the camera. Sensors lose samples at
  /// grazing angles (a simulated one past 75 degrees), so a surface seen edge-on may leave its
  /// pixels empty, and the far side behind it then looks seen through.
  /// With `pixel_block` > 1 each block of that many pixels squared keeps its nearest depth
  /// only (a quarter of the memory at 2, and a coarser edge).
  SeenFreeSpace(std::span<const TriangleMesh> views, std::span<const ViewCalibration> cameras,
                int margin_pixels = 1, float min_facing_cosine = 0.5f, int pixel_block = 1);

  /// Number of views that take part (0: nothing is ever in seen free space).
  int view_count() const { return static_cast<int>(views_.size()); }

  /// What the cameras say of a surface point with unit `normal`.
  enum class Verdict {
    kUnjudged,     ///< no camera it faces has it inside its image (behind, outside, grazing)
    kSeen,         ///< the cameras facing it saw a surface at it or in front of it
    kSeenThrough,  ///< some camera facing it saw through it
  };
  /// Judges `point` by every camera the surface faces (within acos(min_facing_cosine))
  /// and has the point in front of it and inside its image: seen through when the pixel (or
  /// pixel block) it projects to saw nothing, or saw a surface more than `tolerance` behind
  /// it, measured along the normal (a depth gap seen at an angle is longer).
  /// With `across_too`, a pixel that saw nothing takes the nearest depth seen within
  /// `tolerance` of the point across the image (as many pixels as `tolerance` spans at the
  /// point's depth): a surface just past the edge of a view's data, by less than the
  /// tolerance, is not in free space either (a range sensor's last sample at a silhouette or
  /// a box's edge is up to a pixel short of the real edge).
  Verdict Judge(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, float tolerance,
                bool across_too = false) const;
  /// Whether some camera saw through `point` (Judge gives kSeenThrough).
  bool Contains(const Eigen::Vector3f& point, const Eigen::Vector3f& normal,
                float tolerance) const {
    return Judge(point, normal, tolerance) == Verdict::kSeenThrough;
  }

 private:
  struct View {
    Eigen::Isometry3f camera_from_world;
    PinholeIntrinsics intrinsics;
    /// Row-major per pixel block, +infinity where nothing was seen.
    std::vector<float> nearest_depth;
    int block_columns = 0;
  };
  std::vector<View> views_;
  float min_facing_cosine_;
  int pixel_block_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_SEEN_FREE_SPACE_H_
