#include "codec/common/mesh.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace meshvid {

Status ValidateMesh(const TriangleMesh& mesh, std::string_view what) {
  const std::string name(what);
  if (mesh.positions.empty()) return CorruptError(name + ": mesh has no vertices");
  if (mesh.triangles.empty()) return CorruptError(name + ": mesh has no triangles");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!mesh.positions[i].allFinite()) {
      return CorruptError(name + ": vertex " + std::to_string(i) +
                          " has a NaN or infinite coordinate");
    }
  }
  const auto n = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      if (mesh.triangles[t][c] >= n) {
        return CorruptError(name + ": triangle " + std::to_string(t) + " uses vertex index " +
                            std::to_string(mesh.triangles[t][c]) + " but there are only " +
                            std::to_string(n) + " vertices");
      }
    }
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    return CorruptError(name + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                        std::to_string(n) + " vertices");
  }
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
    if (!mesh.normals[i].allFinite()) {
      return CorruptError(name + ": normal " + std::to_string(i) +
                          " has a NaN or infinite component");
    }
  }
  if (!mesh.colours.empty() && mesh.colours.size() != mesh.positions.size()) {
    return CorruptError(name + ": " + std::to_string(mesh.colours.size()) + " colours for " +
                        std::to_string(n) + " vertices");
  }
  return Status::Ok();
}

Eigen::AlignedBox3f BoundingBox(const TriangleMesh& mesh) {
  Eigen::AlignedBox3f box;
  for (const auto& p : mesh.positions) box.extend(p);
  return box;
}

bool ViewsHaveColour(std::span<const TriangleMesh> views) {
  bool any = false;
  for (const TriangleMesh& view : views) {
    if (!view.empty() && view.colours.size() != view.vertex_count()) return false;
    any = any || !view.colours.empty();
  }
  return any;
}

void AppendMesh(const TriangleMesh& src, TriangleMesh* dst) {
  const bool keep_normals = (dst->positions.empty() || !dst->normals.empty()) &&
                            !src.normals.empty();
  const bool keep_colours =
      (dst->positions.empty() || !dst->colours.empty()) && !src.colours.empty();
  const auto offset = static_cast<std::uint32_t>(dst->positions.size());
  if (keep_colours) {
    dst->colours.insert(dst->colours.end(), src.colours.begin(), src.colours.end());
  } else {
    dst->colours.clear();
  }
  dst->positions.insert(dst->positions.end(), src.positions.begin(), src.positions.end());
  if (keep_normals) {
    dst->normals.insert(dst->normals.end(), src.normals.begin(), src.normals.end());
  } else {
    dst->normals.clear();
  }
  dst->triangles.reserve(dst->triangles.size() + src.triangles.size());
  for (const auto& t : src.triangles) dst->triangles.push_back(t.array() + offset);
}

Eigen::Vector3f TriangleNormal(const TriangleMesh& mesh, std::size_t t) {
  const Triangle& tri = mesh.triangles[t];
  const Eigen::Vector3f n = (mesh.positions[tri[1]] - mesh.positions[tri[0]])
                                .cross(mesh.positions[tri[2]] - mesh.positions[tri[0]]);
  const float len = n.norm();
  return len > 0 ? Eigen::Vector3f(n / len) : Eigen::Vector3f::Zero();
}

void ComputeVertexNormals(std::span<const Eigen::Vector3f> positions,
                          std::span<const Triangle> triangles,
                          std::vector<Eigen::Vector3f>* normals) {
  normals->assign(positions.size(), Eigen::Vector3f::Zero());
  for (const auto& tri : triangles) {
    // The unnormalised cross product weighs each face by twice its area.
    const Eigen::Vector3f n =
        (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
    for (int c = 0; c < 3; ++c) (*normals)[tri[c]] += n;
  }
  for (auto& n : *normals) {
    const float len = n.norm();
    if (len > 0) n /= len;
  }
}

std::vector<Eigen::Vector3f> ComputeVertexNormals(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3f> normals;
  ComputeVertexNormals(mesh.positions, mesh.triangles, &normals);
  return normals;
}

double SurfaceArea(const TriangleMesh& mesh) {
  double area = 0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[tri[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[tri[2]].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

void TransformMesh(const Eigen::Affine3d& transform, TriangleMesh* mesh) {
  const Eigen::Affine3f tf = transform.cast<float>();
  for (auto& p : mesh->positions) p = tf * p;
  if (!mesh->normals.empty()) {
    const Eigen::Matrix3f normal_matrix = tf.linear().inverse().transpose();
    for (auto& n : mesh->normals) n = (normal_matrix * n).normalized();
  }
}

void RemoveUnreferencedVertices(TriangleMesh* mesh) {
  constexpr std::uint32_t kUnused = ~std::uint32_t{0};
  std::vector<std::uint32_t> remap(mesh->positions.size(), kUnused);
  std::uint32_t next = 0;
  for (auto& tri : mesh->triangles) {
    for (int c = 0; c < 3; ++c) {
      if (remap[tri[c]] == kUnused) remap[tri[c]] = next++;
      tri[c] = remap[tri[c]];
    }
  }
  std::vector<Eigen::Vector3f> positions(next);
  std::vector<Eigen::Vector3f> normals(mesh->normals.empty() ? 0 : next);
  std::vector<Colour> colours(mesh->colours.empty() ? 0 : next);
  for (std::size_t i = 0; i < remap.size(); ++i) {
    if (remap[i] == kUnused) continue;
    positions[remap[i]] = mesh->positions[i];
    if (!normals.empty()) normals[remap[i]] = mesh->normals[i];
    if (!colours.empty()) colours[remap[i]] = mesh->colours[i];
  }
  mesh->positions = std::move(positions);
  mesh->normals = std::move(normals);
  mesh->colours = std::move(colours);
}

std::size_t SplitNonManifoldVertices(TriangleMesh* mesh) {
  // Corners of each vertex: (triangle, corner) pairs.
  const std::size_t vertex_count = mesh->positions.size();
  std::vector<std::uint32_t> offsets(vertex_count + 1, 0);
  for (const Triangle& tri : mesh->triangles) {
    for (int c = 0; c < 3; ++c) ++offsets[tri[c] + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
  std::vector<std::uint32_t> corners(offsets.back()), fill(offsets.begin(), offsets.end() - 1);
  for (std::uint32_t t = 0; t < mesh->triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) corners[fill[mesh->triangles[t][c]]++] = 3 * t + c;
  }
  std::size_t added = 0;
  std::vector<std::uint32_t> fan;  // per corner of the vertex: its fan (union-find parent)
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    const std::uint32_t begin = offsets[v], count = offsets[v + 1] - begin;
    if (count < 2) continue;
    fan.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) fan[i] = i;
    auto root = [&](std::uint32_t i) {
      while (fan[i] != i) i = fan[i] = fan[fan[i]];
      return i;
    };
    // Two corners of v are in one fan when their triangles share an edge at v.
    for (std::uint32_t i = 0; i < count; ++i) {
      const Triangle& a = mesh->triangles[corners[begin + i] / 3];
      const int ca = corners[begin + i] % 3;
      for (std::uint32_t j = i + 1; j < count; ++j) {
        const Triangle& b = mesh->triangles[corners[begin + j] / 3];
        const int cb = corners[begin + j] % 3;
        const std::uint32_t a1 = a[(ca + 1) % 3], a2 = a[(ca + 2) % 3];
        const std::uint32_t b1 = b[(cb + 1) % 3], b2 = b[(cb + 2) % 3];
        const bool shared = a1 == b1 || a1 == b2 || a2 == b1 || a2 == b2;
        if (shared) fan[root(i)] = root(j);
      }
    }
    // Fans after the first one met get a copy of the vertex.
    const std::uint32_t first_fan = root(0);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;  // (fan root, new vertex)
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t r = root(i);
      if (r == first_fan) continue;
      std::uint32_t copy = 0;
      auto it = std::find_if(copies.begin(), copies.end(),
                             [r](const auto& p) { return p.first == r; });
      if (it == copies.end()) {
        copy = static_cast<std::uint32_t>(mesh->positions.size());
        mesh->positions.push_back(mesh->positions[v]);
        if (!mesh->normals.empty()) mesh->normals.push_back(mesh->normals[v]);
        if (!mesh->colours.empty()) mesh->colours.push_back(mesh->colours[v]);
        copies.emplace_back(r, copy);
        ++added;
      } else {
        copy = it->second;
      }
      mesh->triangles[corners[begin + i] / 3][corners[begin + i] % 3] = copy;
    }
  }
  return added;
}

std::vector<std::vector<std::uint32_t>> VertexNeighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> neighbours(mesh.vertex_count());
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      neighbours[t[c]].push_back(t[(c + 1) % 3]);
      neighbours[t[c]].push_back(t[(c + 2) % 3]);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace meshvid
