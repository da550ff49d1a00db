// MeshSequence: a sequence of meshes read lazily, one frame at a time. Ground-truth animations
// (template OBJ + .pc2, a folder of OBJ/PLY per frame) and mesh file patterns are all
// MeshSequences; so are the simulator's procedural scenes (tools/sim/scenes.h).
#ifndef MESHVID_TOOLS_IO_MESH_SEQUENCE_H_
#define MESHVID_TOOLS_IO_MESH_SEQUENCE_H_

#include <memory>
#include <string>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// A read-only sequence of meshes. Frame(t) loads frame t on demand; nothing requires the
/// whole sequence in memory. Not thread-safe unless an implementation says so.
class MeshSequence {
 public:
  virtual ~MeshSequence() = default;
  virtual int frame_count() const = 0;
  /// Frames per second (0 if the source does not say).
  virtual double frame_rate() const = 0;
  /// True if every frame has the same triangles (an animation of one template).
  virtual bool fixed_connectivity() const = 0;
  /// Mesh of frame t, 0 <= t < frame_count(); validated with ValidateMesh.
  virtual StatusOr<TriangleMesh> Frame(int t) = 0;
  /// Human-readable description of the source, for messages.
  virtual std::string description() const = 0;
};

/// Opens a sequence from:
///  - `NAME.obj` with `NAME.pc2` beside it (template connectivity + positions per frame);
///  - a directory of `.obj`/`.ply` files, one per frame, in lexicographic order;
///  - a pattern with a `{frame}` placeholder (`{frame:04}` zero-pads to 4 digits), frames
///    numbered contiguously from the smallest number present;
///  - a single `.obj`/`.ply` file without a `.pc2` beside it (a one-frame sequence).
/// `frame_rate` is the sequence's rate in frames per second (a .pc2's sampleRate is a frame
/// step, usually 1, not a rate, so the caller's value is used for every source).
StatusOr<std::unique_ptr<MeshSequence>> OpenMeshSequence(const std::string& spec,
                                                         double frame_rate = 25.0);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_MESH_SEQUENCE_H_
