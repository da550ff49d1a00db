// An analytic .mvid representation shared by the codec tests and the decode benchmark: a
// sphere-like base mesh in two blended segments, known transforms and a known detail field.
#ifndef MESHVID_TESTS_ANALYTIC_MVID_H_
#define MESHVID_TESTS_ANALYTIC_MVID_H_

#include <cstdint>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/mvid_writer.h"
#include "format/status.h"

namespace meshvid::testing {

/// The octahedron refined `refinements` times by midpoint splits, projected onto the unit
/// sphere: 4^r * 4 + 2 vertices (18, 66, 258, 1026, 4098, ...) and 8 * 4^r triangles.
TriangleMesh SphereMesh(int refinements);

/// A unit sphere of `rings` latitude rings (poles excluded) x `segments` longitudes, plus
/// the two poles: rings * segments + 2 vertices, 2 * rings * segments triangles.
TriangleMesh LatLongSphere(int rings, int segments);

/// Upper half (y > 0.2) in segment 0, lower half (y < -0.2) in segment 1, blended between.
MotionModel TwoSegments(const TriangleMesh& base);

/// Deformation nodes about `spacing` apart over `base` (MOTN version 3), with their blends.
MotionModel DeformationNodes(const TriangleMesh& base, float spacing);

/// Frame f: segment 0 turns 0.05 f rad about y, segment 1 moves 0.01 f along x.
std::vector<RigidTransform> TransformsAt(int frame);

/// The detail at a point of the unposed base, in [-0.02, 0.02], changing with time.
float DetailAt(const Eigen::Vector3f& rest, int frame);

/// The colour at a point of the unposed base (R G B, each channel within [28, 228]), changing
/// with time; written when the settings ask for a colour stream.
Colour ColourAt(const Eigen::Vector3f& rest, int frame);

/// The largest difference of a channel between the decoded colours of frames [0, frames) at
/// `level` and the exact ColourAt.
StatusOr<int> MaxColourError(MvidDecoder& decoder, int level, int frames);

/// Writes `frames` frames of this representation with `settings` to memory (segment s of
/// `motion` moving as TransformsAt's segment s mod 2).
StatusOr<std::vector<std::uint8_t>> WriteAnalyticMvid(const TriangleMesh& base,
                                                      const MotionModel& motion, int frames,
                                                      const MvidWriterSettings& settings,
                                                      MvidWriteStats* stats = nullptr);

/// One key group of an analytic file: its base mesh (with TwoSegments motion), used from
/// frame `first_frame` until the next key group's.
struct AnalyticKeyGroup {
  TriangleMesh base;
  int first_frame = 0;
};

/// Writes `frames` frames in key groups (the first must start at frame 0); groups of frames
/// are split at key-group boundaries.
StatusOr<std::vector<std::uint8_t>> WriteAnalyticKeyGroups(
    const std::vector<AnalyticKeyGroup>& key_groups, int frames,
    const MvidWriterSettings& settings, MvidWriteStats* stats = nullptr);

/// How far a decoder's reconstruction is from the exact one (the decoded base posed with the
/// decoded transforms, displaced by the exact DetailAt), over every sample of every frame.
struct ReconstructionError {
  float max = 0;
  float rms = 0;
};

/// Decodes `frames` frames at `level` and compares them with the exact reconstruction.
StatusOr<ReconstructionError> MeasureReconstructionError(MvidDecoder& decoder, int level,
                                                         int frames);

}  // namespace meshvid::testing

#endif  // MESHVID_TESTS_ANALYTIC_MVID_H_
