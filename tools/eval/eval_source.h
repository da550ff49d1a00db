// What `meshvid eval` measures: every test source is a MeshSequence (one surface per frame).
// Mesh sequences are used as they are; a capture becomes the union of its views per frame.
// A decoded .mvid is one at a chosen level. A new kind of source is one more MeshSequence
// adapter and one more branch in OpenEvalTestSource.
#ifndef MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_
#define MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_

#include <memory>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "format/status.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// True if `spec` names a capture rather than a mesh sequence: a `.json` manifest, a folder
/// holding a manifest.json, a Stanford `.conf` file, or a pattern with a `{view}` placeholder.
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

/// A decoded .mvid at one level as a MeshSequence (same triangles at every frame).
class MvidSequence : public MeshSequence {
 public:
  /// Opens `path` and checks `level` (-1: the finest level stored); a partial file (cut or
  /// damaged) is refused unless `allow_partial`, then gives its readable frames.
  static StatusOr<std::unique_ptr<MvidSequence>> Open(const std::string& path, int level,
                                                      bool allow_partial = false);
  int frame_count() const override;
  double frame_rate() const override;
  bool fixed_connectivity() const override { return true; }
  StatusOr<TriangleMesh> Frame(int t) override;
  std::string description() const override;

 private:
  MvidSequence() = default;
  std::string path_;
  int level_ = 0;
  std::unique_ptr<MvidDecoder> decoder_;
};

/// Opens the test side of an evaluation: a .mvid decoded at `level` (-1: finest), a capture
/// (see LooksLikeCapture; opened with CaptureSequence::Open) or anything OpenMeshSequence
/// accepts. A partial .mvid is refused unless `allow_partial` (MvidSequence::Open).
StatusOr<std::unique_ptr<MeshSequence>> OpenEvalTestSource(const std::string& spec, int level = -1,
                                                           bool allow_partial = false);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_EVAL_SOURCE_H_
