// What `meshvid eval` measures: every test source is a MeshSequence (one surface per frame).
// Mesh sequences are used as they are; a capture becomes the union of its views per frame.
// A new kind of source (e.g. a decoded .mvid at a chosen level) is one more MeshSequence
// adapter and one more branch in OpenEvalTestSource.
#ifndef MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_
#define MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_

#include <memory>
#include <string>

#include "format/status.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// True if `spec` names a capture rather than a mesh sequence: a `.json` manifest, a Stanford
/// `.conf` file, or a pattern with a `{view}` placeholder.
bool LooksLikeCapture(const std::string& spec);

/// The raw input scans of a capture as a MeshSequence: frame t is the union (AppendMesh) of
/// all views of frame t, in world coordinates.
class CaptureUnionSequence : public MeshSequence {
 public:
  explicit CaptureUnionSequence(std::unique_ptr<CaptureSequence> capture);
  int frame_count() const override;
  double frame_rate() const override;
  bool fixed_connectivity() const override { return false; }
  StatusOr<TriangleMesh> Frame(int t) override;
  std::string description() const override;

 private:
  std::unique_ptr<CaptureSequence> capture_;
};

/// Opens the test side of an evaluation: a capture (see LooksLikeCapture; opened with
/// CaptureSequence::Open) or anything OpenMeshSequence accepts.
StatusOr<std::unique_ptr<MeshSequence>> OpenEvalTestSource(const std::string& spec);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_
