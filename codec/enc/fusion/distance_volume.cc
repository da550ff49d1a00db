#include "codec/enc/fusion/distance_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

// One function of ~90 lines: the sort into runs, the blocks made beforehand and the parallel
// writing share the points' order and home blocks, and the writing loop is the fusion's
// innermost (kept inline for speed).
void DistanceVolume::Integrate(std::span<const OrientedPoint> points) {
  const float h = settings_.voxel_size;
  const float band = settings_.truncation_voxels;
  const float band_squared = band * band;
  const GaussianTable gaussian(band_squared);
  auto in_voxels = [&](const OrientedPoint& p) -> Eigen::Vector3f {
    return (p.position - origin_) / h;
  };
  // Points in order of their home block (the block holding them), each home block's points a
  // contiguous run.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(points.size());
  std::vector<VoxelIndex> home(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    home[i] = BlockOf(in_voxels(points[i]).array().floor().cast<int>());
    order[i] = {BlockKey(home[i]), i};
  }
  std::sort(order.begin(), order.end());
  struct Run {
    std::size_t begin, end;
  };
  // Runs by class of home block (coordinates modulo 3): a point writes only into its home
  // block and the 26 around it (the band is narrower than a block), so two runs of one class
  // never write the same block and may run in parallel.
  std::array<std::vector<Run>, 27> runs_of_class;
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin;
    while (end < order.size() && order[end].first == order[begin].first) ++end;
    const VoxelIndex& b = home[order[begin].second];
    const int cls = ((b.x() % 3 + 3) % 3) * 9 + ((b.y() % 3 + 3) % 3) * 3 + (b.z() % 3 + 3) % 3;
    runs_of_class[cls].push_back({begin, end});
    // Every block a point of the run writes exists before the parallel writing starts.
    for (std::size_t k = begin; k < end; ++k) {
      const Eigen::Vector3f q = in_voxels(points[order[k].second]);
      const VoxelIndex low = BlockOf((q.array() - band).ceil().cast<int>());
      const VoxelIndex high = BlockOf((q.array() + band).floor().cast<int>());
      for (int z = low.z(); z <= high.z(); ++z) {
        for (int y = low.y(); y <= high.y(); ++y) {
          for (int x = low.x(); x <= high.x(); ++x) FindOrAdd(VoxelIndex(x, y, z) * kBlockSide);
        }
      }
    }
    begin = end;
  }
  auto write_run = [&](const Run& run) {
    const VoxelIndex centre = home[order[run.begin].second];
    std::array<Block*, 27> around{};  // the blocks at centre + (-1..1)^3, if they exist
    for (int c = 0; c < 27; ++c) {
      const VoxelIndex b = centre + VoxelIndex(c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1);
      const auto it = block_of_key_.find(BlockKey(b));
      around[c] = it == block_of_key_.end() ? nullptr : &blocks_[it->second];
    }
    for (std::size_t k = run.begin; k < run.end; ++k) {
      const OrientedPoint& point = points[order[k].second];
      const Eigen::Vector3f q = in_voxels(point);
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
            const VoxelIndex v(x, y, z);
            const VoxelIndex offset = BlockOf(v) - centre;
            Block* block = around[(offset.z() + 1) * 9 + (offset.y() + 1) * 3 + offset.x() + 1];
            const float along = point.normal.x() * dx + point.normal.y() * dy +
                                point.normal.z() * dz;
            const float across = std::sqrt(std::max(0.0f, squared - along * along));
            const float weight = gaussian(squared);
            Voxel& voxel = block->voxels[PlaceInBlock(v)];
            voxel.weighted_distance += weight * along;
            voxel.weight += weight;
            voxel.support = std::min(voxel.support, across);
          }
        }
      }
    }
  };
  for (const std::vector<Run>& runs : runs_of_class) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size()),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t r = range.begin(); r < range.end(); ++r) {
                          write_run(runs[r]);
                        }
                      });
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
    if (voxel == nullptr || !Distance(*voxel, &distances[c])) return false;
  }
  return true;
}

bool DistanceVolume::Distance(const Voxel& voxel, float* distance) const {
  if (!(voxel.weight > 0) || voxel.support > settings_.support_voxels) return false;
  *distance = settings_.voxel_size * voxel.weighted_distance / voxel.weight;
  return true;
}

}  // namespace meshvid
