// A k-d tree over a span of 3D points (nanoflann), for nearest-point queries. Header only:
// a target that includes it links nanoflann::nanoflann.
#ifndef MESHVID_CODEC_COMMON_POINT_TREE_H_
#define MESHVID_CODEC_COMMON_POINT_TREE_H_

#include <cstdint>
#include <span>

#include <Eigen/Core>
#include <nanoflann.hpp>

namespace meshvid {

/// nanoflann's view of points held elsewhere (they must outlive the tree).
struct PointCloud {
  std::span<const Eigen::Vector3f> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

/// The tree: knnSearch(query, k, indices, squared_distances) finds the k nearest points.
using PointTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>,
                                        PointCloud, 3, std::uint32_t>;

/// Leaf size of the trees built here (nanoflann's recommended range is 10-50).
inline constexpr std::size_t kPointTreeLeafSize = 10;

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_POINT_TREE_H_
