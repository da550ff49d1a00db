#include "codec/enc/distance_volume.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace meshvid {
namespace {

// Block coordinates are stored in 21 bits each, offset so that negative ones fit.
constexpr int kKeyBits = 21;
constexpr int kKeyOffset = 1 << (kKeyBits - 1);

// exp(-s / 2) for s = squared distance in voxel sizes (a Gaussian of sigma one voxel),
// tabulated: the integration evaluates it for every point and voxel of its band.
class GaussianTable {
 public:
  explicit GaussianTable(float max_squared) : step_(max_squared / (kSize - 1)) {
    for (int i = 0; i < kSize; ++i) values_[i] = std::exp(-0.5f * static_cast<float>(i) * step_);
  }
  float operator()(float squared) const {
    const int i = static_cast<int>(squared / step_ + 0.5f);
    return values_[std::min(i, kSize - 1)];
  }

 private:
  static constexpr int kSize = 1024;
  float step_;
  std::array<float, kSize> values_;
};

// The block holding voxel v, and v's place in it (blocks are 8 voxels a side; C++20's >> on
// a negative int is an arithmetic shift, i.e. a floor division).
VoxelIndex BlockOf(const VoxelIndex& v) { return VoxelIndex(v.x() >> 3, v.y() >> 3, v.z() >> 3); }
int PlaceInBlock(const VoxelIndex& v) { return ((v.z() & 7) * 8 + (v.y() & 7)) * 8 + (v.x() & 7); }

}  // namespace

DistanceVolume::DistanceVolume(const Eigen::Vector3f& origin,
                               const DistanceVolumeSettings& settings)
    : origin_(origin), settings_(settings) {}

std::uint64_t DistanceVolume::BlockKey(const VoxelIndex& block) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    key = (key << kKeyBits) |
          (static_cast<std::uint64_t>(block[a] + kKeyOffset) & ((1u << kKeyBits) - 1));
  }
  return key;
}

const DistanceVolume::Voxel* DistanceVolume::Find(const VoxelIndex& v) const {
  const auto it = block_of_key_.find(BlockKey(BlockOf(v)));
  if (it == block_of_key_.end()) return nullptr;
  return &blocks_[it->second].voxels[PlaceInBlock(v)];
}

DistanceVolume::Voxel* DistanceVolume::FindOrAdd(const VoxelIndex& v) {
  const VoxelIndex block = BlockOf(v);
  const std::uint64_t key = BlockKey(block);
  if (key != cached_key_ || cached_block_ < 0) {
    const auto [it, added] =
        block_of_key_.try_emplace(key, static_cast<std::uint32_t>(blocks_.size()));
    if (added) {
      blocks_.emplace_back();
      blocks_.back().corner = block * kBlockSide;
    }
    cached_key_ = key;
    cached_block_ = static_cast<std::int64_t>(it->second);
  }
  return &blocks_[cached_block_].voxels[PlaceInBlock(v)];
}

void DistanceVolume::Integrate(std::span<const OrientedPoint> points) {
  const float h = settings_.voxel_size;
  const float band = settings_.truncation_voxels;
  const float band_squared = band * band;
  const GaussianTable gaussian(band_squared);
  for (const OrientedPoint& point : points) {
    const Eigen::Vector3f q = (point.position - origin_) / h;  // in voxel sizes
    const VoxelIndex low = (q.array() - band).ceil().cast<int>();
    const VoxelIndex high = (q.array() + band).floor().cast<int>();
    for (int z = low.z(); z <= high.z(); ++z) {
      for (int y = low.y(); y <= high.y(); ++y) {
        const float dz = static_cast<float>(z) - q.z();
        const float dy = static_cast<float>(y) - q.y();
        const float dyz = dy * dy + dz * dz;
        if (dyz > band_squared) continue;
        for (int x = low.x(); x <= high.x(); ++x) {
          const float dx = static_cast<float>(x) - q.x();
          const float squared = dx * dx + dyz;
          if (squared > band_squared) continue;
          const float along = point.normal.x() * dx + point.normal.y() * dy +
                              point.normal.z() * dz;
          const float across = std::sqrt(std::max(0.0f, squared - along * along));
          const float weight = gaussian(squared);
          Voxel* voxel = FindOrAdd(VoxelIndex(x, y, z));
          voxel->weighted_distance += weight * along;
          voxel->weight += weight;
          voxel->support = std::min(voxel->support, across);
        }
      }
    }
  }
}

bool DistanceVolume::CubeDistances(const VoxelIndex& v, float distances[8]) const {
  const bool inside_one_block = (v.x() & 7) < 7 && (v.y() & 7) < 7 && (v.z() & 7) < 7;
  const Voxel* base = inside_one_block ? Find(v) : nullptr;
  if (inside_one_block && base == nullptr) return false;
  for (int c = 0; c < 8; ++c) {
    const VoxelIndex offset(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    const Voxel* voxel =
        inside_one_block ? base + (offset.z() * kBlockSide + offset.y()) * kBlockSide + offset.x()
                         : Find(v + offset);
    if (voxel == nullptr || !(voxel->weight > 0) || voxel->support > settings_.support_voxels) {
      return false;
    }
    distances[c] = settings_.voxel_size * voxel->weighted_distance / voxel->weight;
  }
  return true;
}

bool DistanceVolume::SupportedDistance(const VoxelIndex& v, float* distance) const {
  const Voxel* voxel = Find(v);
  if (voxel == nullptr || !(voxel->weight > 0) || voxel->support > settings_.support_voxels) {
    return false;
  }
  *distance = settings_.voxel_size * voxel->weighted_distance / voxel->weight;
  return true;
}

}  // namespace meshvid
