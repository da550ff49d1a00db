// Ray casting of range images against a triangle mesh, with Embree 3 (BVH) and oneTBB
// (pixels in parallel).
#ifndef MESHVID_TOOLS_SIM_RAYCASTER_H_
#define MESHVID_TOOLS_SIM_RAYCASTER_H_

#include <memory>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/embree_scene.h"
#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// What one pinhole camera sees: per pixel (row-major) the depth of the first hit along the
/// camera's z axis (0 where the ray meets nothing) and |cos| of the angle between the ray and
/// the hit triangle's normal (either side of the surface counts as seen). When the mesh has
/// vertex colours, also the colour at each hit (the hit triangle's vertex colours blended by
/// the hit's barycentric coordinates, 0..255 per channel); otherwise `colour` is empty.
struct RayCastImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth;
  std::vector<float> cos_incidence;
  std::vector<Eigen::Vector3f> colour;
};

/// An Embree scene holding one triangle mesh. Cast() may be called from several threads at
/// once; SetMesh() may not run concurrently with anything else.
class RayCaster {
 public:
  /// An empty caster; SetMesh() builds its scene.
  static StatusOr<std::unique_ptr<RayCaster>> Create();
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Replaces the mesh and rebuilds the BVH (buffers are reused when the sizes match); keeps
  /// the triangles and vertex colours when the mesh has colours. Fails on an empty mesh or an
  /// Embree error.
  Status SetMesh(const TriangleMesh& mesh);

  /// Casts one ray through every pixel centre of `view` (which needs intrinsics), in
  /// parallel, into `image`. Returns the number of pixels whose ray met the mesh.
  StatusOr<long> Cast(const ViewCalibration& view, RayCastImage* image) const;

 private:
  RayCaster() = default;
  std::unique_ptr<EmbreeScene> scene_;  ///< null until SetMesh()
  std::vector<Triangle> triangles_;     ///< the mesh's triangles, kept only with colours
  std::vector<Colour> colours_;         ///< the mesh's vertex colours, or empty
};

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_RAYCASTER_H_
