// KeyGroupGeometry: one key group's surface as a decoder rebuilds it from its decoded base mesh,
// its MOTN payload and a frame's transforms and displacement picture. MvidDecoder and the
// WebAssembly decoder (web/wasm) share it; neither the video nor the Draco decoder is in it.
#ifndef MESHVID_CODEC_DEC_KEY_GROUP_GEOMETRY_H_
#define MESHVID_CODEC_DEC_KEY_GROUP_GEOMETRY_H_

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "codec/common/displacement_image.h"
#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/subdivision.h"
#include "codec/common/video_codec.h"
#include "codec/dec/motion_decoder.h"
#include "format/status.h"

namespace meshvid {

/// A key group's base mesh, motion and what is derived from them: the subdivision, the layouts
/// of its displacement pictures and the triangles of each level (the same at every frame).
class KeyGroupGeometry {
 public:
  /// From the key group's decoded base mesh and its MOTN payload, for `levels` subdivision
  /// levels. Errors are the MOTN payload's (kCorrupt) or the subdivision's.
  static StatusOr<KeyGroupGeometry> Create(TriangleMesh base,
                                           std::span<const std::uint8_t> motion_payload,
                                           int levels);

  const TriangleMesh& base() const { return base_; }
  const MotionModel& motion() const { return motion_; }
  const MotionQuantization& quantization() const { return quantization_; }
  const RegularSubdivision& subdivision() const { return subdivision_; }
  int levels() const { return levels_; }
  /// Base triangles that are surface (all unless MOTN's mask hides some).
  std::size_t SurfaceTriangleCount() const;
  /// Vertices of a decoded frame at `level`.
  std::size_t VertexCount(int level) const { return subdivision_.sample_count(level); }
  /// Triangles of a decoded frame at `level` (0..levels()), surface ones only; built once.
  const std::vector<Triangle>& Triangles(int level);
  /// The layout of `packing` for this base (built once).
  const DisplacementLayout& Layout(DisplacementPacking packing);
  /// Layout(packing), checked against the picture size a file's HEAD declares when this is its
  /// first key group (HEAD gives key group 0's size; later ones have their layout's):
  /// kCorrupt when they differ.
  StatusOr<const DisplacementLayout*> CheckedLayout(DisplacementPacking packing,
                                                    bool first_key_group, int header_width,
                                                    int header_height);
  /// Positions of a frame at `level` (0..levels()), indexed as Triangles(level): the base posed
  /// by `transforms`, subdivided, and displaced along its normals by `picture`'s samples
  /// de-quantised with `range` in `layout`.
  void Positions(std::span<const RigidTransform> transforms, const GreyPicture& picture,
                 const DisplacementLayout& layout, const DisplacementRange& range, int level,
                 std::vector<Eigen::Vector3f>* positions);

 private:
  KeyGroupGeometry() = default;

  TriangleMesh base_;
  MotionModel motion_;
  MotionQuantization quantization_;
  RegularSubdivision subdivision_;
  int levels_ = 0;
  std::map<DisplacementPacking, DisplacementLayout> layouts_;
  std::vector<std::vector<Triangle>> triangles_;  ///< per level, filled on first use
  // Scratch buffers reused across frames.
  std::vector<Eigen::Vector3f> posed_, normals_, origins_, directions_;
  std::vector<float> displacements_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_KEY_GROUP_GEOMETRY_H_
