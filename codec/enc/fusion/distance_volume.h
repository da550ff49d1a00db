// A sparse truncated signed-distance volume integrated from oriented surface points: the
// implicit surface of the view fusion. Only voxels near the data exist, so memory follows the
// surface's area, and a voxel knows whether the data supports it, so surfaces the data leaves
// open stay open when the volume is contoured.
#ifndef MESHVID_CODEC_ENC_FUSION_DISTANCE_VOLUME_H_
#define MESHVID_CODEC_ENC_FUSION_DISTANCE_VOLUME_H_

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace meshvid {

/// A point of a range surface with its unit normal (pointing out of the object, towards the
/// sensor that saw it).
struct OrientedPoint {
  Eigen::Vector3f position;
  Eigen::Vector3f normal;
};

/// Integer coordinates of a voxel (a grid corner).
using VoxelIndex = Eigen::Vector3i;

/// How points write into the volume.
struct DistanceVolumeSettings {
  float voxel_size = 1;  ///< grid step, scene units; > 0
  /// A point writes the voxels within this many voxel sizes of it (the truncation band);
  /// (0, 7]: narrower than the volume's blocks.
  float truncation_voxels = 3;
  /// A voxel is supported (may carry the surface) when some point lies within this many voxel
  /// sizes of it across that point's normal: the surface stops about this far past the edge of
  /// the data instead of running on along the truncation band.
  float support_voxels = 1;
};

/// The sparse volume. Each voxel holds the weighted mean of the points' signed distances
/// n . (x - p) (positive outside), with Gaussian weights of the distance |x - p| (sigma: one
/// voxel), so the nearest data dominates and the two sides of a thin part keep their signs.
class DistanceVolume {
 public:
  /// An empty volume with its grid anchored at `origin` (any point near the data).
  DistanceVolume(const Eigen::Vector3f& origin, const DistanceVolumeSettings& settings);

  /// Adds every point's contribution (in parallel; the sums, and so the volume, do not depend
  /// on the number of threads).
  void Integrate(std::span<const OrientedPoint> points);

  /// The signed distances at the 8 corners of the cube whose lowest corner is voxel `v`,
  /// corner c at v + (c & 1, c >> 1 & 1, c >> 2 & 1); false unless all 8 are supported.
  bool CubeDistances(const VoxelIndex& v, float distances[8]) const;

  /// World position of voxel `v`.
  Eigen::Vector3f Position(const VoxelIndex& v) const {
    return origin_ + settings_.voxel_size * v.cast<float>();
  }

  /// Calls `visit(VoxelIndex)` for every voxel held (supported or not), block by block.
  template <class Visit>
  void ForEachVoxel(Visit&& visit) const;

  /// Voxels held (memory is about 12 bytes each).
  std::size_t voxel_count() const { return blocks_.size() * kBlockVoxels; }

 private:
  static constexpr int kBlockSide = 8;  // the shifts in distance_volume.cc assume 8
  static constexpr int kBlockVoxels = kBlockSide * kBlockSide * kBlockSide;
  struct Voxel {
    float weighted_distance = 0;
    float weight = 0;
    float support = 1e30f;  ///< least distance across a point's normal, in voxel sizes
  };
  struct Block {
    VoxelIndex corner;  ///< voxel index of the block's first voxel
    Voxel voxels[kBlockVoxels];
  };
  static std::uint64_t BlockKey(const VoxelIndex& block);
  /// The voxel's signed distance, if points wrote it and one lies within the support.
  bool Distance(const Voxel& voxel, float* distance) const;
  const Voxel* Find(const VoxelIndex& v) const;
  Voxel* FindOrAdd(const VoxelIndex& v);

  Eigen::Vector3f origin_;
  DistanceVolumeSettings settings_;
  std::unordered_map<std::uint64_t, std::uint32_t> block_of_key_;
  std::vector<Block> blocks_;
  std::uint64_t cached_key_ = 0;     ///< FindOrAdd's last block, which the next voxel is
  std::int64_t cached_block_ = -1;   ///< most likely in
};

template <class Visit>
void DistanceVolume::ForEachVoxel(Visit&& visit) const {
  for (const Block& block : blocks_) {
    for (int z = 0; z < kBlockSide; ++z) {
      for (int y = 0; y < kBlockSide; ++y) {
        for (int x = 0; x < kBlockSide; ++x) visit(VoxelIndex(block.corner + VoxelIndex(x, y, z)));
      }
    }
  }
}

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_DISTANCE_VOLUME_H_
