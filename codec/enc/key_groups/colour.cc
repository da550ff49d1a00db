#include "codec/enc/key_groups/colour.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "codec/common/colour_space.h"
#include "codec/enc/key_groups/detail.h"

namespace meshvid {
namespace {

/// Rounds of alternating between fused luminance and gains; each halves the error or better.
constexpr int kGainRounds = 6;
/// Samples darker than kDarkest (mean of the channels) are mostly noise, and a channel above
/// kBrightest may be clipped: neither scales with exposure.
constexpr float kDarkest = 4.0f;
constexpr float kBrightest = 251.0f;

/// The plain mean of the channels: the gains are one per view, for all channels alike.
float Luminance(const Eigen::Vector3f& c) { return (c.x() + c.y() + c.z()) / 3.0f; }

}  // namespace

void ColourObservations::Reset(std::size_t views, std::size_t sample_count) {
  samples = sample_count;
  colour.assign(views, std::vector<Eigen::Vector3f>(sample_count, Eigen::Vector3f::Zero()));
  weight.assign(views, std::vector<float>(sample_count, 0.0f));
}

std::vector<double> EstimateExposureGains(const ColourObservations& observations) {
  const std::size_t views = observations.colour.size();
  std::vector<double> gains(views, 1.0);
  if (views < 2) return gains;
  // The samples that count: two or more views see them, each within the linear range.
  std::vector<std::size_t> shared;
  for (std::size_t s = 0; s < observations.samples; ++s) {
    int seen = 0;
    bool linear = true;
    for (std::size_t v = 0; v < views; ++v) {
      if (!(observations.weight[v][s] > 0)) continue;
      const Eigen::Vector3f& c = observations.colour[v][s];
      linear = linear && Luminance(c) >= kDarkest && c.maxCoeff() <= kBrightest;
      ++seen;
    }
    if (seen >= 2 && linear) shared.push_back(s);
  }
  if (shared.empty()) return gains;
  std::vector<double> numerator(views), denominator(views);
  for (int round = 0; round < kGainRounds; ++round) {
    std::fill(numerator.begin(), numerator.end(), 0.0);
    std::fill(denominator.begin(), denominator.end(), 0.0);
    for (std::size_t s : shared) {
      double sum = 0, weights = 0;
      for (std::size_t v = 0; v < views; ++v) {
        const float w = observations.weight[v][s];
        if (w > 0) sum += w * Luminance(observations.colour[v][s]) / gains[v], weights += w;
      }
      const double fused = sum / weights;
      for (std::size_t v = 0; v < views; ++v) {
        const float w = observations.weight[v][s];
        if (!(w > 0)) continue;
        numerator[v] += w * Luminance(observations.colour[v][s]) * fused;
        denominator[v] += w * fused * fused;
      }
    }
    double log_sum = 0;
    int overlapping = 0;
    for (std::size_t v = 0; v < views; ++v) {
      if (denominator[v] > 0 && numerator[v] > 0) {
        gains[v] = numerator[v] / denominator[v];
        log_sum += std::log(gains[v]);
        ++overlapping;
      }
    }
    const double scale = overlapping > 0 ? std::exp(-log_sum / overlapping) : 1.0;
    for (std::size_t v = 0; v < views; ++v) {
      if (denominator[v] > 0 && numerator[v] > 0) gains[v] *= scale;
    }
  }
  return gains;
}

void FuseColours(const ColourObservations& observations, std::span<const double> gains,
                 std::array<std::vector<float>, 3>* channels) {
  const std::size_t views = observations.colour.size();
  for (auto& channel : *channels) {
    channel.assign(observations.samples, std::numeric_limits<float>::quiet_NaN());
  }
  for (std::size_t s = 0; s < observations.samples; ++s) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weights = 0;
    for (std::size_t v = 0; v < views; ++v) {
      const float w = observations.weight[v][s];
      if (!(w > 0)) continue;
      const double gain = v < gains.size() ? gains[v] : 1.0;
      sum += (w / gain) * observations.colour[v][s].cast<double>();
      weights += w;
    }
    if (!(weights > 0)) continue;
    for (int c = 0; c < 3; ++c) {
      (*channels)[c][s] = static_cast<float>(std::clamp(sum[c] / weights, 0.0, 255.0));
    }
  }
}

std::vector<std::vector<Colour>> FillColours(
    const SampleGraph& graph, std::array<std::vector<std::vector<float>>, 3>* channels,
    std::array<std::vector<float>, 3>* last_seen) {
  const UnreachedFill average_colour{
      .spread_everywhere = true, .frame_mean = true, .no_values = 128};
  for (int c = 0; c < 3; ++c) {
    FillDisplacementGroup(graph, &(*last_seen)[c], &(*channels)[c], average_colour);
  }
  const auto& [red, green, blue] = *channels;
  std::vector<std::vector<Colour>> colours(red.size());
  for (std::size_t k = 0; k < colours.size(); ++k) {
    colours[k].resize(red[k].size());
    for (std::size_t i = 0; i < colours[k].size(); ++i) {
      colours[k][i] = RoundTo8Bits({red[k][i], green[k][i], blue[k][i]});
    }
  }
  return colours;
}

}  // namespace meshvid
