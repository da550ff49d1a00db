// Surface colour (docs/encoder-method.md section 4, colour): the views' colours at the same
// shots that measure the displacements, put on one exposure, then fused per sample with
// weights that favour views seeing the surface squarely.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_COLOUR_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_COLOUR_H_

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"

namespace meshvid {

struct SampleGraph;

/// What the views saw of one frame's colour, sample by sample: per view, a colour (0..255 per
/// channel) and a weight (0 where the view did not see the sample or its hit was an outlier).
struct ColourObservations {
  std::size_t samples = 0;
  std::vector<std::vector<Eigen::Vector3f>> colour;  ///< [view][sample]
  std::vector<std::vector<float>> weight;            ///< [view][sample]

  /// Sizes the arrays for `views` x `samples`, every weight 0.
  void Reset(std::size_t views, std::size_t samples);
};

/// The weight of a view's colour sample: the squared cosine of the angle between the view's
/// ray to the surface and the surface's normal there, so a grazing view, whose pixels
/// smear across the surface, gives way to one that sees it squarely.
inline float ViewingWeight(float abs_cos) { return abs_cos * abs_cos; }

/// Each view's exposure gain relative to the others, from the samples two or more views see:
/// the least-squares gains of luminance (the mean of the channels) against the fused
/// luminance, alternated a few times, normalised to a geometric mean of 1 over the views that
/// overlap another. A view that overlaps none keeps gain 1. A sample does not count where a
/// view sees it near black (luminance below 4) or possibly clipped (a channel above 251):
/// there it does not scale with exposure. The gains are estimated from one frame.
std::vector<double> EstimateExposureGains(const ColourObservations& observations);

/// Fuses the views' colours per sample, each divided by its view's gain (1 for a view past
/// the end of `gains`) and weighted by its weight: three channels (0..255), NaN where no view
/// saw the sample.
void FuseColours(const ColourObservations& observations, std::span<const double> gains,
                 std::array<std::vector<float>, 3>* channels);

/// The colours of a run of frames from their fused channels (`channels`: [channel][frame]
/// [sample], NaN where no view saw the sample, as FuseColours gives them; filled in place). A
/// sample no view saw takes its nearest colours in time and space, as a displacement does
/// (FillDisplacementGroup), spread from the seen samples to every other one: the frame's mean
/// where none reaches, not black, and neutral grey in a frame no view saw. `last_seen`
/// carries each channel's latest colours from one run to the next. Returns [frame][sample],
/// rounded to 8 bits.
std::vector<std::vector<Colour>> FillColours(
    const SampleGraph& graph, std::array<std::vector<std::vector<float>>, 3>* channels,
    std::array<std::vector<float>, 3>* last_seen);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_COLOUR_H_
