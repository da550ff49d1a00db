// MvidWriter: turns an already-computed representation (base mesh, motion model, per-frame
// segment transforms, per-frame displacement fields) into a .mvid file, in one pass.
#ifndef MESHVID_CODEC_ENC_CODING_MVID_WRITER_H_
#define MESHVID_CODEC_ENC_CODING_MVID_WRITER_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "codec/common/displacement_image.h"
#include "codec/common/motion.h"
#include "codec/common/subdivision.h"
#include "codec/dec/motion_decoder.h"
#include "codec/enc/coding/base_mesh_encoder.h"
#include "codec/enc/coding/motion_encoder.h"
#include "codec/enc/summary.h"
#include "format/container_writer.h"
#include "format/status.h"

namespace meshvid {

/// Settings of a .mvid file.
struct MvidWriterSettings {
  int levels = 3;             ///< subdivision levels of the displacement lattice (0..6)
  /// Lattice order codes fewer bytes than triangle blocks at fine quantisers (and has fewer
  /// pixels to decode); blocks win at coarse ones (bench/packing_bench).
  DisplacementPacking packing = DisplacementPacking::kLatticeOrder;
  VideoCodec codec = VideoCodec::kHevc;
  int qp = 16;                ///< video quantiser (see VideoEncoding::qp)
  int effort = 4;             ///< video encoder effort 0..9
  int threads = 0;            ///< video encoder threads, 0: automatic
  int gof_size = 32;          ///< frames per group (the random-access unit)
  double frame_rate = 25.0;
  std::uint32_t frame_count = 0;  ///< total frames if known up front (0: unknown)
  /// The transforms' steps. A key group whose track is given to StartKeyGroup may instead
  /// keep the translation step and coarsen the rotation step to its segments' reach
  /// (RotationStepForReach), its transforms rounded about their segments' pivots
  /// (FindMotionPivots), when that codes its track in fewer bytes.
  MotionQuantization motion;
  /// The base mesh coder; `base.allow_reorder` must stay false (Create refuses it).
  BaseMeshEncoding base;
  std::string metadata_json = "{}";  ///< free-form JSON object stored in the header
  /// Write a colour stream: every group then needs a colour field per frame (WriteGroup).
  bool colour = false;
  int colour_qp = 24;  ///< the colour video's quantiser (see VideoEncoding::qp)
};

/// Writes a .mvid: Create() codes the first key group's base mesh and motion model, then
/// WriteGroup() once per group of frames; StartKeyGroup() begins the next key group (a new base
/// mesh and motion); then Finish(). Everything the caller computes downstream of the base mesh
/// and transforms should use decoded_base() and DequantizeTransforms() (closed loop).
class MvidWriter {
 public:
  ~MvidWriter();
  /// `motion` has one blend per base vertex. Writes the header, base mesh and motion; `track`
  /// as StartKeyGroup's.
  static StatusOr<std::unique_ptr<MvidWriter>> Create(
      ByteSink sink, const TriangleMesh& base, const MotionModel& motion,
      const MvidWriterSettings& settings,
      const std::vector<std::vector<RigidTransform>>& track = {});

  /// Starts the next key group: codes `base` and `motion` (one blend per base vertex); the
  /// groups written after it use them. Use decoded_base() and motion() from here on: Draco may
  /// renumber the base's vertices and triangles. The current key group must hold a group
  /// already. `track` (the key group's transforms [frame][segment], or empty) chooses its
  /// transforms' quantisation (MvidWriterSettings::motion).
  Status StartKeyGroup(const TriangleMesh& base, const MotionModel& motion,
                       const std::vector<std::vector<RigidTransform>>& track = {});
  /// Key groups started so far.
  int key_group_count() const { return key_groups_; }

  /// The current key group's base mesh as a decoder reconstructs it (Draco-quantised
  /// positions, same order).
  const TriangleMesh& decoded_base() const { return decoded_base_; }
  /// The current key group's motion model in decoded_base()'s order (Draco may renumber the
  /// base: the model given to StartKeyGroup, its blends and mask moved accordingly).
  const MotionModel& motion() const { return motion_; }
  /// The current key group's transform steps, as its MOTN states them.
  const MotionQuantization& motion_quantization() const { return quantization_; }
  /// The current key group's displacement lattice; displacement fields hold samples() in its
  /// order.
  const RegularSubdivision& subdivision() const { return subdivision_; }
  const MvidWriterSettings& settings() const { return settings_; }
  /// The transforms a decoder will use for these, after quantisation.
  std::vector<std::vector<RigidTransform>> DequantizeTransforms(
      const std::vector<std::vector<RigidTransform>>& transforms) const;

  /// Writes one group: `transforms[frame][segment]` and `displacements[frame][sample]`
  /// (subdivision().samples().size() each), 1..gof_size frames; with settings().colour, also
  /// `colours[frame][sample]` (R G B per sample), else `colours` must be empty.
  Status WriteGroup(const std::vector<std::vector<RigidTransform>>& transforms,
                    const std::vector<std::vector<float>>& displacements,
                    const std::vector<std::vector<Colour>>& colours = {});
  /// Writes the index and trailer.
  Status Finish();
  const MvidWriteStats& stats() const { return stats_; }

 private:
  MvidWriter() = default;
  /// Writes the preamble and HEAD (the streams' picture size is the first key group's).
  Status BeginContainer();
  /// Codes one group's pictures in a session of their own; appends the packets.
  template <typename Picture>
  Status EncodePictures(const std::vector<Picture>& pictures, PictureFormat format, int qp,
                        std::vector<std::uint8_t>* extradata,
                        std::vector<std::vector<std::uint8_t>>* packets, std::uint64_t* bytes);
  MvidWriterSettings settings_;
  std::unique_ptr<ContainerWriter> container_;
  TriangleMesh decoded_base_;
  MotionModel motion_;
  MotionQuantization quantization_;  ///< the current key group's
  MotionPivots pivots_;              ///< the current key group's segments'
  RegularSubdivision subdivision_;
  DisplacementLayout layout_;
  MvidWriteStats stats_;
  std::uint32_t next_frame_ = 0;
  std::uint32_t next_gof_ = 0;
  std::uint32_t first_gof_of_key_group_ = 0;
  int key_groups_ = 0;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_MVID_WRITER_H_
