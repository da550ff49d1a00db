// Mesh decimation with OpenMesh's decimater: the automatic base mesh (method.md "Base mesh")
// and the encoder's correspondence proxies (a few per cent of each view's triangles).
#ifndef MESHVID_CODEC_ENC_DECIMATION_H_
#define MESHVID_CODEC_ENC_DECIMATION_H_

#include <cstddef>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Settings of one decimation.
struct DecimationOptions {
  /// Stop at this many vertices (or earlier if a bound below forbids further collapses).
  std::size_t target_vertices = 1000;
  /// Largest distance (scene units) a collapse may move the surface (quadric error bound);
  /// 0: unbounded.
  double max_error = 0;
  /// Largest change of a face normal a collapse may cause, in degrees; 0: unbounded. Keeps
  /// the displacement mapping between the decimated mesh and the original one-to-one.
  double max_normal_deviation_degrees = 0;
  /// Keep boundary vertices of open meshes (range images) in place.
  bool lock_boundary = false;
};

/// Decimates `mesh` by edge collapses (quadric error, with the bounds above). The result has
/// no unreferenced vertices and no degenerate triangles.
StatusOr<TriangleMesh> DecimateMesh(const TriangleMesh& mesh, const DecimationOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_DECIMATION_H_
