#include "codec/enc/tracking/data_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "codec/common/point_tree.h"

namespace meshvid {
namespace {

struct Sums {
  double squares = 0;
  double excess_squares = 0;
  std::size_t unexplained = 0;
};

/// The median distance from a sample to its nearest other sample (over at most 1024 of them).
float SampleSpacing(const PointTree& tree, std::span<const Eigen::Vector3f> samples) {
  const std::size_t stride = std::max<std::size_t>(1, samples.size() / 1024);
  std::vector<float> spacings;
  for (std::size_t i = 0; i < samples.size(); i += stride) {
    std::uint32_t nearest[2] = {0, 0};
    float squared[2] = {0, 0};
    if (tree.knnSearch(samples[i].data(), 2, nearest, squared) == 2) {
      spacings.push_back(std::sqrt(squared[1]));
    }
  }
  if (spacings.empty()) return 0;
  std::nth_element(spacings.begin(), spacings.begin() + spacings.size() / 2, spacings.end());
  return spacings[spacings.size() / 2];
}

}  // namespace

// One function of ~90 lines: the tree, the limits and the per-point pass that every figure of
// the fit is summed in together (one search per data point).
DataFit MeasureDataFit(std::span<const Eigen::Vector3f> surface_samples,
                       std::span<const Eigen::Vector3f> data_points,
                       float representable_distance, float stray_distance,
                       std::span<const Eigen::Vector3f> sample_normals,
                       std::span<const float> sample_reach) {
  DataFit fit;
  fit.points = data_points.size();
  if (data_points.empty()) return fit;
  if (surface_samples.empty()) {
    fit.unexplained_share = 1;
    fit.rms_distance = fit.excess_mean_square = std::numeric_limits<double>::infinity();
    return fit;
  }
  const PointCloud cloud{surface_samples};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  const float limit_squared = representable_distance * representable_distance;
  const bool along_normals = sample_normals.size() == surface_samples.size();
  const float across_limit =
      along_normals ? representable_distance + SampleSpacing(tree, surface_samples) : 0;
  const bool reach_per_sample = sample_reach.size() == surface_samples.size();
  // Deterministic: the sums feed the key-group decision, which must not depend on the threads.
  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, data_points.size(), 2048), Sums{},
      [&](const tbb::blocked_range<std::size_t>& range, Sums partial) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          std::uint32_t nearest = 0;
          float squared = 0;
          tree.knnSearch(data_points[i].data(), 1, &nearest, &squared);
          partial.squares += squared;
          if (along_normals) {
            const Eigen::Vector3f offset = data_points[i] - surface_samples[nearest];
            const float along = std::abs(sample_normals[nearest].dot(offset));
            const float across = std::sqrt(std::max(0.0f, squared - along * along));
            const float limit =
                reach_per_sample
                    ? std::max(across_limit, representable_distance + sample_reach[nearest])
                    : across_limit;
            partial.unexplained += along > representable_distance || across > limit;
            const float beyond_along = std::max(0.0f, along - representable_distance);
            const float beyond_across = std::max(0.0f, across - limit);
            partial.excess_squares += beyond_along * beyond_along + beyond_across * beyond_across;
          } else {
            partial.unexplained += squared > limit_squared;
            const float beyond = std::max(0.0f, std::sqrt(squared) - representable_distance);
            partial.excess_squares += beyond * beyond;
          }
        }
        return partial;
      },
      [](Sums a, const Sums& b) {
        a.squares += b.squares;
        a.excess_squares += b.excess_squares;
        a.unexplained += b.unexplained;
        return a;
      });
  fit.unexplained_share = double(sums.unexplained) / double(data_points.size());
  fit.rms_distance = std::sqrt(sums.squares / double(data_points.size()));
  fit.excess_mean_square = sums.excess_squares / double(data_points.size());
  // The other way: surface samples with no data point within the stray distance.
  const PointCloud data{data_points};
  const PointTree data_tree(3, data,
                            nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  const float stray_squared = stray_distance * stray_distance;
  struct Strays {
    std::size_t count = 0;
    float farthest_squared = 0;
  };
  const Strays strays = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, surface_samples.size(), 2048), Strays{},
      [&](const tbb::blocked_range<std::size_t>& range, Strays partial) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          std::uint32_t nearest = 0;
          float squared = 0;
          data_tree.knnSearch(surface_samples[i].data(), 1, &nearest, &squared);
          partial.count += squared > stray_squared;
          partial.farthest_squared = std::max(partial.farthest_squared, squared);
        }
        return partial;
      },
      [](Strays a, const Strays& b) {
        a.count += b.count;
        a.farthest_squared = std::max(a.farthest_squared, b.farthest_squared);
        return a;
      });
  fit.stray_share = double(strays.count) / double(surface_samples.size());
  fit.farthest_from_data = std::sqrt(double(strays.farthest_squared));
  return fit;
}

std::vector<float> SampleReach(std::span<const Eigen::Vector3f> samples,
                               std::span<const Triangle> triangles) {
  std::vector<float> reach(samples.size(), 0.0f);
  for (const Triangle& t : triangles) {
    float longest = 0;
    for (int c = 0; c < 3; ++c) {
      longest = std::max(longest, (samples[t[c]] - samples[t[(c + 1) % 3]]).norm());
    }
    for (int c = 0; c < 3; ++c) reach[t[c]] = std::max(reach[t[c]], 0.5f * longest);
  }
  return reach;
}

namespace {

/// The square of the decoded error's floor (kDecodedErrorFloor of the range).
double FloorSquare(double representable_distance) {
  const double floor = kDecodedErrorFloor * representable_distance;
  return floor * floor;
}

}  // namespace

double DecodedMeanSquare(const DataFit& fit, double representable_distance) {
  const double range_squared = representable_distance * representable_distance;
  return FloorSquare(representable_distance) + fit.excess_mean_square +
         fit.seen_through_share * range_squared;
}

double TrackingLossDb(const DataFit& key_frame, const DataFit& frame, double representable_distance,
                      const ForgottenSurface& forgotten) {
  if (frame.points == 0) return 0;
  const double lost = std::clamp(forgotten.share, 0.0, 1.0);
  const double tracked = (1 - lost) * DecodedMeanSquare(frame, representable_distance) +
                         lost * FloorSquare(representable_distance);
  const double fresh = (1 - lost) * DecodedMeanSquare(key_frame, representable_distance) +
                       lost * forgotten.mean_square;
  if (!std::isfinite(tracked)) return std::numeric_limits<double>::infinity();
  if (!std::isfinite(fresh) || tracked <= fresh) return 0;
  return 10 * std::log10(tracked / fresh);
}

bool StillExplains(const DataFit& key_frame, const DataFit& frame, double representable_distance,
                   double allowed_loss_db, double farthest_growth,
                   const ForgottenSurface& forgotten, double most_excused_db) {
  if (frame.points == 0) return true;
  const double at_data = TrackingLossDb(key_frame, frame, representable_distance);
  return TrackingLossDb(key_frame, frame, representable_distance, forgotten) <= allowed_loss_db &&
         at_data <= allowed_loss_db + most_excused_db &&
         frame.farthest_from_data <= key_frame.farthest_from_data + farthest_growth;
}

}  // namespace meshvid
