// Depth images: 16-bit greyscale PNG files holding a range sensor's z-depth per pixel, and
// their meshing with the sensor's calibration.
//
// Convention: pixel (u, v) with value d > 0 is the camera-frame point
//   z = d * depth_scale,  x = (u - cx) / fx * z,  y = (v - cy) / fy * z
// i.e. the value is the z coordinate along the optical axis (as Kinect/RealSense/OpenCV
// store it), not the length of the ray. A value of 0 means "no sample".
#ifndef MESHVID_TOOLS_IO_DEPTH_IMAGE_H_
#define MESHVID_TOOLS_IO_DEPTH_IMAGE_H_

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "format/status.h"
#include "tools/io/range_grid.h"

namespace meshvid {

/// A width x height image of 16-bit depth values, row-major, 0 = no sample.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint16_t> values;

  std::uint16_t at(int u, int v) const { return values[static_cast<std::size_t>(v) * width + u]; }
};

/// A width x height colour image, row-major, registered to its view's depth image (pixel
/// (u, v) is the colour of the depth image's sample (u, v)).
struct ColourImage {
  int width = 0;
  int height = 0;
  std::vector<Colour> pixels;
};

/// Writes `image` as a 16-bit greyscale PNG. Fails if the size and values disagree.
Status WriteDepthPng(const std::string& path, const DepthImage& image);

/// Reads a 16-bit greyscale PNG (8-bit greyscale is widened). Fails, naming the file, on a
/// missing or damaged file or a colour image.
StatusOr<DepthImage> ReadDepthPng(const std::string& path);

/// Writes `image` as an 8-bit RGB PNG. Fails if the size and pixels disagree.
Status WriteColourPng(const std::string& path, const ColourImage& image);

/// Reads any PNG as 8-bit RGB (greyscale copied to the channels, 16 bits reduced to 8, alpha
/// dropped). Fails, naming the file, on a missing or damaged file.
StatusOr<ColourImage> ReadColourPng(const std::string& path);

/// Back-projects every pixel to the camera frame (see the convention above); the grid's
/// depth is the z-depth, 0 for pixels without a sample.
RangeGrid DepthImageToRangeGrid(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                                double depth_scale);

/// Meshes a depth image: back-projection, TriangulateRangeGrid with `meshing`, then
/// `world_from_camera`; with `colour`, each vertex takes its pixel's colour. Fails if the
/// image size differs from the intrinsics' or the colour image's, or if no triangle
/// survives; `what` and `colour_what` name the images in messages.
StatusOr<TriangleMesh> MeshDepthImage(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                                      double depth_scale,
                                      const Eigen::Isometry3d& world_from_camera,
                                      const RangeGridMeshing& meshing, const std::string& what,
                                      const ColourImage* colour = nullptr,
                                      const std::string& colour_what = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_DEPTH_IMAGE_H_
