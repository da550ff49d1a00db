#include "codec/enc/fusion/seen_free_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

constexpr float kNothingSeen = std::numeric_limits<float>::infinity();

/// Writes the nearest depth of `mesh` (world coordinates) at every pixel centre it covers.
void Rasterise(const TriangleMesh& mesh, const Eigen::Isometry3f& camera_from_world,
               const PinholeIntrinsics& k, std::vector<float>* depth) {
  const int width = k.width, height = k.height;
  std::vector<Eigen::Vector3f> projected(mesh.positions.size());  // (u, v, z), z <= 0: behind
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Eigen::Vector3f c = camera_from_world * mesh.positions[i];
    if (!(c.z() > 0)) {
      projected[i] = Eigen::Vector3f(0, 0, -1);
      continue;
    }
    const Eigen::Vector2f pixel = k.Project(c.cast<double>()).cast<float>();
    projected[i] = Eigen::Vector3f(pixel.x(), pixel.y(), c.z());
    // The vertex itself is a sample, whatever the triangles around it look like.
    const float x = std::round(projected[i].x()), y = std::round(projected[i].y());
    if (x >= 0 && x < float(width) && y >= 0 && y < float(height)) {
      float& d = (*depth)[static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)];
      d = std::min(d, c.z());
    }
  }
  constexpr float kInside = -1e-4f;  // barycentric slack: pixels on a shared edge are covered
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3f& a = projected[t[0]];
    const Eigen::Vector3f& b = projected[t[1]];
    const Eigen::Vector3f& c = projected[t[2]];
    if (!(a.z() > 0 && b.z() > 0 && c.z() > 0)) continue;
    const float area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(std::abs(area) > 1e-12f)) continue;
    // The pixel centres inside the triangle's box, clamped before any cast (a vertex near the
    // camera's plane projects far outside the image).
    auto first = [](float low, int size) {
      return static_cast<int>(std::ceil(std::clamp(low, -1.0f, float(size))));
    };
    auto last = [](float high, int size) {
      return static_cast<int>(std::floor(std::clamp(high, -1.0f, float(size))));
    };
    const int u0 = std::max(0, first(std::min({a.x(), b.x(), c.x()}), width));
    const int u1 = std::min(width - 1, last(std::max({a.x(), b.x(), c.x()}), width));
    const int v0 = std::max(0, first(std::min({a.y(), b.y(), c.y()}), height));
    const int v1 = std::min(height - 1, last(std::max({a.y(), b.y(), c.y()}), height));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const float wa = ((b.x() - u) * (c.y() - v) - (b.y() - v) * (c.x() - u)) / area;
        const float wb = ((c.x() - u) * (a.y() - v) - (c.y() - v) * (a.x() - u)) / area;
        const float wc = 1 - wa - wb;
        if (wa < kInside || wb < kInside || wc < kInside) continue;
        // Depth is linear in screen space as its reciprocal.
        const float z = 1 / (wa / a.z() + wb / b.z() + wc / c.z());
        float& d = (*depth)[static_cast<std::size_t>(v) * width + u];
        d = std::min(d, z);
      }
    }
  }
}

/// Replaces every pixel by the smallest value within `margin` of it (a square window).
void MinFilter(int width, int height, int margin, std::vector<float>* image) {
  if (margin <= 0) return;
  std::vector<float> rows(image->size());
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      float m = kNothingSeen;
      for (int x = std::max(0, u - margin); x <= std::min(width - 1, u + margin); ++x) {
        m = std::min(m, (*image)[static_cast<std::size_t>(v) * width + x]);
      }
      rows[static_cast<std::size_t>(v) * width + u] = m;
    }
  }
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      float m = kNothingSeen;
      for (int y = std::max(0, v - margin); y <= std::min(height - 1, v + margin); ++y) {
        m = std::min(m, rows[static_cast<std::size_t>(y) * width + u]);
      }
      (*image)[static_cast<std::size_t>(v) * width + u] = m;
    }
  }
}

}  // namespace

SeenFreeSpace::SeenFreeSpace(std::span<const TriangleMesh> views,
                             std::span<const ViewCalibration> cameras, int margin_pixels,
                             float min_facing_cosine, int pixel_block)
    : min_facing_cosine_(min_facing_cosine), pixel_block_(std::max(1, pixel_block)) {
  std::vector<std::size_t> source;  // the input view each kept view rasterises
  for (std::size_t i = 0; i < std::min(views.size(), cameras.size()); ++i) {
    const ViewCalibration& camera = cameras[i];
    if (!camera.CanProject()) continue;
    View view;
    view.camera_from_world = camera.world_from_camera.inverse().cast<float>();
    view.intrinsics = *camera.intrinsics;
    views_.push_back(std::move(view));
    source.push_back(i);
  }
  tbb::parallel_for(std::size_t{0}, views_.size(), [&](std::size_t i) {
    View& view = views_[i];
    const PinholeIntrinsics& k = view.intrinsics;
    view.nearest_depth.assign(static_cast<std::size_t>(k.width) * k.height, kNothingSeen);
    Rasterise(views[source[i]], view.camera_from_world, k, &view.nearest_depth);
    MinFilter(k.width, k.height, margin_pixels, &view.nearest_depth);
    view.block_columns = (k.width + pixel_block_ - 1) / pixel_block_;
    if (pixel_block_ > 1) {
      const int rows = (k.height + pixel_block_ - 1) / pixel_block_;
      std::vector<float> blocks(static_cast<std::size_t>(view.block_columns) * rows, kNothingSeen);
      for (int v = 0; v < k.height; ++v) {
        for (int u = 0; u < k.width; ++u) {
          float& b = blocks[static_cast<std::size_t>(v / pixel_block_) * view.block_columns +
                            u / pixel_block_];
          b = std::min(b, view.nearest_depth[static_cast<std::size_t>(v) * k.width + u]);
        }
      }
      view.nearest_depth = std::move(blocks);
    }
  });
}

SeenFreeSpace::Verdict SeenFreeSpace::Judge(const Eigen::Vector3f& point,
                                             const Eigen::Vector3f& normal, float tolerance,
                                             bool across_too) const {
  Verdict verdict = Verdict::kUnjudged;
  for (const View& view : views_) {
    const Eigen::Vector3f c = view.camera_from_world * point;
    if (!(c.z() > 0)) continue;
    const float distance = c.norm();
    // Cosine between the surface's normal and the direction to the camera. A surface facing
    // away is judged by no camera: the front surface that should hide it from this camera may
    // have been lost at a grazing angle (the far side of an arm seen edge-on).
    const float facing = -(view.camera_from_world.linear() * normal).dot(c) / distance;
    if (!(facing >= min_facing_cosine_)) continue;
    const PinholeIntrinsics& k = view.intrinsics;
    const Eigen::Vector2f pixel = k.Project(c.cast<double>()).cast<float>();
    const float x = std::round(pixel.x()), y = std::round(pixel.y());
    if (!(x >= 0 && x < float(k.width) && y >= 0 && y < float(k.height))) continue;
    // The pixel block the point projects to.
    const int bu = static_cast<int>(x) / pixel_block_, bv = static_cast<int>(y) / pixel_block_;
    auto depth_at = [&view](int bx, int by) {
      return view.nearest_depth[static_cast<std::size_t>(by) * view.block_columns + bx];
    };
    float seen = depth_at(bu, bv);
    if (across_too && seen == kNothingSeen) {
      // Nothing seen at the point's pixel: the nearest depth seen within `tolerance` of it
      // across the image.
      constexpr float kMostBlocks = 64;  // a huge tolerance does not scan the whole image
      const int reach = static_cast<int>(std::ceil(
          std::min(kMostBlocks, tolerance * float(k.fx) / (c.z() * float(pixel_block_)))));
      const int block_rows = (k.height + pixel_block_ - 1) / pixel_block_;
      for (int by = std::max(0, bv - reach); by <= std::min(block_rows - 1, bv + reach); ++by) {
        for (int bx = std::max(0, bu - reach);
             bx <= std::min(view.block_columns - 1, bu + reach); ++bx) {
          seen = std::min(seen, depth_at(bx, by));
        }
      }
    }
    // How far in front of the seen surface, along the normal: the depth gap along the ray
    // (z to ray length: distance / z), projected on the normal.
    const float in_front = (seen - c.z()) * (distance / c.z()) * facing;
    if (in_front > tolerance) return Verdict::kSeenThrough;  // +infinity: nothing seen
    verdict = Verdict::kSeen;
  }
  return verdict;
}

}  // namespace meshvid
