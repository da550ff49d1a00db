// SurfaceRenderer: ray-casts a triangle mesh (EmbreeScene, packets of neighbouring pixels, rows
// in parallel) and shades it: smooth vertex normals, two-sided, a key light from above the
// camera and a fill, optional per-vertex colours.
#ifndef MESHVID_TOOLS_RENDER_SURFACE_RENDERER_H_
#define MESHVID_TOOLS_RENDER_SURFACE_RENDERER_H_

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "codec/common/embree_scene.h"
#include "codec/common/mesh.h"
#include "format/status.h"
#include "tools/render/camera.h"
#include "tools/render/rgb_image.h"

namespace meshvid {

/// Renders one mesh at a time; SetMesh() between frames reuses the BVH's buffers when the
/// sizes stay (a decoded key group).
class SurfaceRenderer {
 public:
  /// Replaces the mesh (copied) and, if given, its per-vertex colours (0..1 RGB, one per
  /// vertex; empty: the default clay colour). Fails on an empty mesh.
  Status SetMesh(const TriangleMesh& mesh, std::vector<Eigen::Vector3f> colours = {});

  /// The mesh as seen by `camera` on a background gradient.
  RgbImage Render(const RenderCamera& camera) const;

 private:
  std::unique_ptr<EmbreeScene> scene_;
  std::vector<Triangle> triangles_;
  std::vector<Eigen::Vector3f> normals_;
  std::vector<Eigen::Vector3f> colours_;
};

/// The background colour of row `y` of a picture `height` rows high.
Rgb BackgroundColour(int y, int height);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_SURFACE_RENDERER_H_
