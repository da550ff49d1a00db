// DecimateMesh: OpenMesh's decimater (halfedge collapses, so the result's vertices are a
// subset of the input's) with a boundary-aware quadric priority and optional bounds.
#include "codec/enc/fusion/decimation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

// TriMesh first: QuadricT.hh relies on the vector traits it brings in.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>

#include "codec/enc/fusion/removed_vertex_bound.h"

namespace meshvid {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// OpenMesh's triangle mesh with faster versions of the topology queries the decimater makes
// for every candidate collapse (BaseDecimaterT::is_collapse_legal calls them on its Mesh type,
// so these hide the library's). Debian's libOpenMeshCore is built with assertions and its
// is_collapse_ok allocates, which makes those calls most of a range-image proxy's decimation
// time (bench/DESIGN-NOTES.md). The tests are OpenMesh's TriConnectivity::is_collapse_ok ones.
class DecimationMesh : public OpenMesh::TriMesh_ArrayKernelT<> {
 public:
  using OpenMesh::TriMesh_ArrayKernelT<>::valence;

  /// Prepares the one-ring marks; call after the last vertex is added.
  void PrepareMarks() { mark_.assign(n_vertices(), 0); }

  /// True if collapsing v0v1 (v0 into v1) keeps the mesh a manifold with the same topology.
  bool is_collapse_ok(HalfedgeHandle v0v1) {
    const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
    const VertexHandle v0 = to_vertex_handle(v1v0);
    const VertexHandle v1 = to_vertex_handle(v0v1);
    if (status(edge_handle(v0v1)).deleted() || status(v0).deleted() || status(v1).deleted()) {
      return false;
    }
    VertexHandle vl, vr;
    if (!is_boundary(v0v1)) {  // the edges v1-vl and vl-v0 must not both be boundary edges
      const HalfedgeHandle h1 = next_halfedge_handle(v0v1);
      const HalfedgeHandle h2 = next_halfedge_handle(h1);
      vl = to_vertex_handle(h1);
      if (is_boundary(opposite_halfedge_handle(h1)) && is_boundary(opposite_halfedge_handle(h2))) {
        return false;
      }
    }
    if (!is_boundary(v1v0)) {  // nor v0-vr and vr-v1
      const HalfedgeHandle h1 = next_halfedge_handle(v1v0);
      const HalfedgeHandle h2 = next_halfedge_handle(h1);
      vr = to_vertex_handle(h1);
      if (is_boundary(opposite_halfedge_handle(h1)) && is_boundary(opposite_halfedge_handle(h2))) {
        return false;
      }
    }
    if (vl == vr) return false;
    // An edge between two boundary vertices must be a boundary edge.
    if (is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0)) {
      return false;
    }
    // Link condition: the one-rings of v0 and v1 share only vl and vr.
    if (++stamp_ == 0) {
      std::fill(mark_.begin(), mark_.end(), 0);
      stamp_ = 1;
    }
    for (HalfedgeHandle h : voh_range(v1)) mark_[to_vertex_handle(h).idx()] = stamp_;
    for (HalfedgeHandle h : voh_range(v0)) {
      const VertexHandle v = to_vertex_handle(h);
      if (mark_[v.idx()] == stamp_ && v != vl && v != vr) return false;
    }
    return true;
  }

  /// The halfedge from `from` to `to`, or an invalid handle.
  HalfedgeHandle find_halfedge(VertexHandle from, VertexHandle to) const {
    for (HalfedgeHandle h : voh_range(from)) {
      if (to_vertex_handle(h) == to) return h;
    }
    return HalfedgeHandle();
  }

  /// Number of edges at `v`.
  unsigned int valence(VertexHandle v) const {
    unsigned int count = 0;
    for ([[maybe_unused]] HalfedgeHandle h : voh_range(v)) ++count;
    return count;
  }

 private:
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
};
using OmMesh = DecimationMesh;

// The priority module: OpenMesh's area-weighted plane quadrics (ModQuadricT) plus, for every
// boundary edge, a plane through the edge perpendicular to its face (Garland & Heckbert's
// boundary constraint), so open meshes (range images) keep their outline instead of eroding.
// It also refuses collapses that fold a face over (ModNormalFlippingT's test, done here
// without renormalising every normal: that module took a third of the proxy time).
template <class MeshT>
class ModBoundaryQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModBoundaryQuadricT, MeshT, BoundaryQuadric);

  explicit ModBoundaryQuadricT(MeshT& mesh) : Base(mesh, /*is_binary=*/false) {
    Base::mesh().add_property(quadrics_);
  }
  ~ModBoundaryQuadricT() override { Base::mesh().remove_property(quadrics_); }

  void initialize() override {
    using Quadric = OpenMesh::Geometry::Quadricd;
    using OpenMesh::Vec3d;
    MeshT& m = Base::mesh();
    for (auto v : m.vertices()) m.property(quadrics_, v).clear();
    for (auto f : m.faces()) {
      auto fv = m.cfv_begin(f);
      const Vec3d p0 = OpenMesh::vector_cast<Vec3d>(m.point(*fv));
      const auto v0 = *fv;
      const auto v1 = *++fv;
      const auto v2 = *++fv;
      const Vec3d p1 = OpenMesh::vector_cast<Vec3d>(m.point(v1));
      const Vec3d p2 = OpenMesh::vector_cast<Vec3d>(m.point(v2));
      Vec3d n = (p1 - p0) % (p2 - p0);
      const double twice_area = n.norm();
      if (twice_area <= 0) continue;
      n /= twice_area;
      Quadric q(n[0], n[1], n[2], -(p0 | n));
      q *= 0.5 * twice_area;
      m.property(quadrics_, v0) += q;
      m.property(quadrics_, v1) += q;
      m.property(quadrics_, v2) += q;
    }
    for (auto h : m.halfedges()) {
      if (!m.is_boundary(h)) continue;
      const auto inner = m.opposite_halfedge_handle(h);
      const auto face = m.face_handle(inner);
      const auto a = m.from_vertex_handle(inner);
      const auto b = m.to_vertex_handle(inner);
      const Vec3d pa = OpenMesh::vector_cast<Vec3d>(m.point(a));
      const Vec3d pb = OpenMesh::vector_cast<Vec3d>(m.point(b));
      const Vec3d edge = pb - pa;
      const Vec3d n = OpenMesh::vector_cast<Vec3d>(m.calc_face_normal(face));
      Vec3d side = edge % n;
      const double length = side.norm();
      if (length <= 0) continue;
      side /= length;
      Quadric q(side[0], side[1], side[2], -(pa | side));
      q *= kBoundaryWeight * edge.sqrnorm();
      m.property(quadrics_, a) += q;
      m.property(quadrics_, b) += q;
    }
  }

  /// Collapses that turn a remaining face's normal by more than `degrees` (or make it
  /// degenerate) become illegal; the same test as OpenMesh's ModNormalFlippingT, cheaper.
  void set_max_face_turn(double degrees) {
    min_cos_ = static_cast<float>(std::cos(degrees * M_PI / 180.0));
  }

  /// Collapses that leave an edge longer than `length` (> 0) become illegal.
  void set_max_edge_length(double length) {
    max_squared_edge_ = length > 0 ? static_cast<float>(length * length) : 0;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    MeshT& m = Base::mesh();
    for (auto h : m.voh_range(ci.v0)) {
      if (max_squared_edge_ > 0 && m.to_vertex_handle(h) != ci.v1 &&
          (m.point(m.to_vertex_handle(h)) - ci.p1).sqrnorm() > max_squared_edge_) {
        return Base::ILLEGAL_COLLAPSE;
      }
      const auto face = m.face_handle(h);
      if (!face.is_valid() || face == ci.fl || face == ci.fr) continue;
      const auto next = m.next_halfedge_handle(h);
      const auto& b = m.point(m.to_vertex_handle(h));
      const auto& c = m.point(m.to_vertex_handle(next));
      const auto normal = (b - ci.p1) % (c - ci.p1);
      const float length = normal.norm();
      if (!((normal | m.normal(face)) > min_cos_ * length) || length == 0) {
        return Base::ILLEGAL_COLLAPSE;
      }
    }
    return Cost(ci.v0, ci.v1);
  }

  /// The quadric error of collapsing v0 into v1, without the legality tests.
  float Cost(typename MeshT::VertexHandle v0, typename MeshT::VertexHandle v1) {
    const MeshT& m = Base::mesh();
    OpenMesh::Geometry::Quadricd q = m.property(quadrics_, v0);
    q += m.property(quadrics_, v1);
    return static_cast<float>(q(m.point(v1)));
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    Base::mesh().property(quadrics_, ci.v1) += Base::mesh().property(quadrics_, ci.v0);
  }

 private:
  // Boundary planes weigh like a face of the edge's squared length, a few times over.
  static constexpr double kBoundaryWeight = 4.0;
  float min_cos_ = 0;  // 90 degrees: no face may flip
  float max_squared_edge_ = 0;  // 0: unbounded
  OpenMesh::VPropHandleT<OpenMesh::Geometry::Quadricd> quadrics_;
};

// A max-heap (by operator<, as std::push_heap's) with four children a node: half the levels
// of a binary heap, and a node's children share a cache line. The decimation's queue holds
// hundreds of thousands of candidates, and sifting through it was most of its own loop.
constexpr std::size_t kHeapArity = 4;

template <class T>
void SiftDown(std::vector<T>& heap, std::size_t i) {
  const std::size_t n = heap.size();
  T item = heap[i];
  while (true) {
    const std::size_t first = kHeapArity * i + 1;
    if (first >= n) break;
    std::size_t best = first;
    const std::size_t last = std::min(first + kHeapArity, n);
    for (std::size_t c = first + 1; c < last; ++c) {
      if (heap[best] < heap[c]) best = c;
    }
    if (!(item < heap[best])) break;
    heap[i] = heap[best];
    i = best;
  }
  heap[i] = item;
}

/// Restores the heap after an item was appended.
template <class T>
void PushHeap(std::vector<T>& heap) {
  std::size_t i = heap.size() - 1;
  T item = heap[i];
  while (i > 0) {
    const std::size_t parent = (i - 1) / kHeapArity;
    if (!(heap[parent] < item)) break;
    heap[i] = heap[parent];
    i = parent;
  }
  heap[i] = item;
}

/// Removes and returns the top (largest) item of a non-empty heap.
template <class T>
T PopHeap(std::vector<T>& heap) {
  T top = heap.front();
  heap.front() = heap.back();
  heap.pop_back();
  if (!heap.empty()) SiftDown(heap, 0);
  return top;
}

/// Orders `heap` as a heap.
template <class T>
void MakeHeap(std::vector<T>& heap) {
  if (heap.size() < 2) return;
  for (std::size_t i = (heap.size() - 2) / kHeapArity + 1; i-- > 0;) SiftDown(heap, i);
}

// OpenMesh's decimater framework (its modules and legality tests) driven by a lazy queue of
// halfedge collapses ordered by quadric cost. DecimaterT keeps one heap entry per vertex and,
// after each collapse, runs every legality test on every outgoing halfedge of the former
// one-ring (about 40 candidates). Here a candidate's cost depends only on its two end
// vertices, so it is computed when queued (cheap) and entries whose end vertices changed since
// are skipped; the legality tests (topology, flips, bound modules) run only on the candidate
// popped. The collapse order is the same; candidates found illegal get another chance in a
// full refill when the queue runs dry, which evaluates far fewer candidates on range-image
// proxies (bench/DESIGN-NOTES.md).
class LazyDecimater : public OpenMesh::Decimater::BaseDecimaterT<OmMesh> {
 public:
  explicit LazyDecimater(OmMesh& mesh) : BaseDecimaterT<OmMesh>(mesh) {}

  /// The priority module (added to this decimater) whose cost orders the queue.
  void SetQuadric(ModBoundaryQuadricT<OmMesh>* quadric) { quadric_ = quadric; }

  /// Collapses until at most `max_vertices` vertices or `max_faces` faces remain, or no
  /// collapse is legal. Call initialize() first.
  void DecimateTo(std::size_t max_vertices, std::size_t max_faces) {
    OmMesh& m = mesh();
    cost_.assign(m.n_edges(), 0.0f);
    std::size_t vertices = m.n_vertices(), faces = m.n_faces();
    bool collapsed_since_fill = true;
    while (vertices > max_vertices && faces > max_faces) {
      if (queue_.empty()) {
        if (!collapsed_since_fill) break;
        collapsed_since_fill = false;
        for (auto e : m.edges()) PushEdge(e);
        MakeHeap(queue_);
        continue;
      }
      const Candidate candidate = PopHeap(queue_);
      const OmMesh::HalfedgeHandle h(candidate.halfedge);
      const OmMesh::EdgeHandle e = m.edge_handle(h);
      // Outdated (an end vertex changed and the edge was queued again) or gone.
      if (cost_[e.idx()] != candidate.cost || m.status(e).deleted()) continue;
      cost_[e.idx()] = -1;  // no longer queued
      CollapseInfo ci(m, h);
      if (!is_collapse_legal(ci) || collapse_priority(ci) < 0) {
        // The cheaper direction is illegal: queue the other one on its own.
        if (!candidate.one_way) Push(m.opposite_halfedge_handle(h), /*one_way=*/true);
        continue;
      }
      --vertices;
      faces -= (m.is_boundary(ci.v0v1) || m.is_boundary(ci.v1v0)) ? 1 : 2;
      preprocess_collapse(ci);
      m.collapse(h);
      for (auto f : m.vf_range(ci.v1)) m.set_normal(f, m.calc_face_normal(f));
      postprocess_collapse(ci);
      collapsed_since_fill = true;
      for (auto g : m.voh_range(ci.v1)) {  // every edge at v1 has new costs
        PushEdge(m.edge_handle(g));
        PushHeap(queue_);
      }
    }
    queue_.clear();
  }

 private:
  struct Candidate {
    float cost;
    int halfedge;   // the direction to collapse (from-vertex into to-vertex)
    bool one_way;   // the other direction was found illegal
    // std heaps put the largest first: order by decreasing cost, then by halfedge.
    bool operator<(const Candidate& o) const {
      return cost != o.cost ? cost > o.cost : halfedge > o.halfedge;
    }
  };

  // Appends a candidate for halfedge h alone (the caller restores the heap order).
  void Push(OmMesh::HalfedgeHandle h, bool one_way) {
    const OmMesh& m = mesh();
    const float cost = quadric_->Cost(m.from_vertex_handle(h), m.to_vertex_handle(h));
    cost_[m.edge_handle(h).idx()] = cost;
    queue_.push_back({cost, h.idx(), one_way});
    if (one_way) PushHeap(queue_);
  }

  // Appends the cheaper direction of edge e.
  void PushEdge(OmMesh::EdgeHandle e) {
    const OmMesh& m = mesh();
    const auto h0 = m.halfedge_handle(e, 0), h1 = m.halfedge_handle(e, 1);
    const auto a = m.to_vertex_handle(h1), b = m.to_vertex_handle(h0);
    const float cost0 = quadric_->Cost(a, b), cost1 = quadric_->Cost(b, a);
    const bool first = cost0 <= cost1;
    cost_[e.idx()] = first ? cost0 : cost1;
    queue_.push_back({first ? cost0 : cost1, (first ? h0 : h1).idx(), false});
  }

  ModBoundaryQuadricT<OmMesh>* quadric_ = nullptr;
  std::vector<Candidate> queue_;
  std::vector<float> cost_;  // per edge: the cost of its current queue entry
};

// Disjoint-set forest over triangle corners.
struct CornerSets {
  std::vector<std::uint32_t> parent;
  std::uint32_t Find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void Join(std::uint32_t a, std::uint32_t b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Builds the OpenMesh copy of `mesh`: triangles with a repeated index, or reusing a directed
// edge of an earlier triangle (a third triangle on an edge, or an inconsistent orientation),
// are dropped; a vertex where several fans of triangles meet is split into one vertex per fan,
// so that every face insertion succeeds. `origin` receives the input index of each vertex.
void BuildOpenMesh(const TriangleMesh& mesh, OmMesh* om, std::vector<std::uint32_t>* origin) {
  const std::size_t vertex_count = mesh.positions.size();
  const std::size_t face_count = mesh.triangles.size();
  // Outgoing halfedges of every vertex (CSR), in triangle order.
  std::vector<std::uint32_t> offset(vertex_count + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) ++offset[t[c] + 1];
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  std::vector<std::uint32_t> target(3 * face_count), corner_of(3 * face_count);
  {
    std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
    for (std::uint32_t f = 0; f < face_count; ++f) {
      const Triangle& t = mesh.triangles[f];
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t slot = fill[t[c]]++;
        target[slot] = t[(c + 1) % 3];
        corner_of[slot] = 3 * f + c;
      }
    }
  }
  std::vector<char> keep(face_count, 1);
  for (std::uint32_t f = 0; f < face_count; ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) keep[f] = 0;
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    for (std::uint32_t i = offset[v]; i < offset[v + 1]; ++i) {
      if (!keep[corner_of[i] / 3]) continue;
      for (std::uint32_t j = offset[v]; j < i; ++j) {
        if (target[j] == target[i] && keep[corner_of[j] / 3]) {
          keep[corner_of[i] / 3] = 0;
          break;
        }
      }
    }
  }
  // Corners around a vertex joined across shared edges form its fans.
  CornerSets sets;
  sets.parent.resize(3 * face_count);
  std::iota(sets.parent.begin(), sets.parent.end(), 0u);
  for (std::size_t a = 0; a < vertex_count; ++a) {
    for (std::uint32_t i = offset[a]; i < offset[a + 1]; ++i) {
      const std::uint32_t corner = corner_of[i];
      if (!keep[corner / 3]) continue;
      const std::uint32_t b = target[i];
      for (std::uint32_t j = offset[b]; j < offset[b + 1]; ++j) {  // the opposite b -> a
        if (target[j] != a || !keep[corner_of[j] / 3]) continue;
        const std::uint32_t back = corner_of[j];
        const std::uint32_t f = corner / 3, g = back / 3;
        sets.Join(corner, 3 * g + (back % 3 + 1) % 3);  // both corners at a
        sets.Join(3 * f + (corner % 3 + 1) % 3, back);  // both corners at b
        break;
      }
    }
  }
  // One OpenMesh vertex per fan root.
  std::vector<std::uint32_t> vertex_of_root(3 * face_count, kNone);
  origin->clear();
  om->reserve(vertex_count, 3 * face_count / 2, face_count);
  for (std::uint32_t f = 0; f < face_count; ++f) {
    if (!keep[f]) continue;
    OmMesh::VertexHandle handles[3];
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t root = sets.Find(3 * f + c);
      if (vertex_of_root[root] == kNone) {
        const Eigen::Vector3f& p = mesh.positions[mesh.triangles[f][c]];
        vertex_of_root[root] = static_cast<std::uint32_t>(om->n_vertices());
        om->add_vertex(OmMesh::Point(p.x(), p.y(), p.z()));
        origin->push_back(mesh.triangles[f][c]);
      }
      handles[c] = OmMesh::VertexHandle(static_cast<int>(vertex_of_root[root]));
    }
    om->add_face(handles[0], handles[1], handles[2]);
  }
}

/// kInvalidArgument unless `mesh` is valid and every option is in range.
Status CheckDecimationInput(const TriangleMesh& mesh, const DecimationOptions& options) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "mesh to decimate"));
  if (mesh.triangles.size() >= (std::size_t{1} << 30)) {
    return InvalidArgumentError("mesh to decimate has too many triangles (" +
                                std::to_string(mesh.triangles.size()) + ")");
  }
  if (options.target_vertices < 4 && options.target_triangles < 4) {
    return InvalidArgumentError("decimation target must be at least 4 vertices or 4 triangles");
  }
  if (!(options.max_error >= 0) || !std::isfinite(options.max_error)) {
    return InvalidArgumentError("decimation max_error must be finite and >= 0, got " +
                                std::to_string(options.max_error));
  }
  if (!(options.max_normal_deviation_degrees >= 0 &&
        options.max_normal_deviation_degrees <= 180)) {
    return InvalidArgumentError("decimation max_normal_deviation_degrees must be in [0, 180], "
                                "got " + std::to_string(options.max_normal_deviation_degrees));
  }
  if (!(options.max_edge_length >= 0) || !std::isfinite(options.max_edge_length)) {
    return InvalidArgumentError("decimation max_edge_length must be finite and >= 0, got " +
                                std::to_string(options.max_edge_length));
  }
  if (!(options.max_aspect_ratio == 0 || options.max_aspect_ratio >= 1)) {
    return InvalidArgumentError("decimation max_aspect_ratio must be 0 or >= 1, got " +
                                std::to_string(options.max_aspect_ratio));
  }

  return Status::Ok();
}

/// The decimated OpenMesh back as a TriangleMesh of the input's positions (`origin`: each
/// OpenMesh vertex's input vertex); fan copies of one input vertex become one vertex again,
/// and triangles that collapsed to no area are dropped.
TriangleMesh FromOpenMesh(const OmMesh& om, const std::vector<std::uint32_t>& origin,
                          const TriangleMesh& mesh) {
  TriangleMesh result;
  std::vector<std::uint32_t> output_index(mesh.positions.size(), kNone);
  result.triangles.reserve(om.n_faces());
  for (auto f : om.faces()) {
    Triangle t;
    int c = 0;
    for (auto v : om.fv_range(f)) {
      const std::uint32_t source = origin[v.idx()];
      if (output_index[source] == kNone) {
        output_index[source] = static_cast<std::uint32_t>(result.positions.size());
        result.positions.push_back(mesh.positions[source]);
      }
      t[c++] = output_index[source];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    const Eigen::Vector3f& a = result.positions[t[0]];
    if ((result.positions[t[1]] - a).cross(result.positions[t[2]] - a).squaredNorm() == 0.0f) {
      continue;
    }
    result.triangles.push_back(t);
  }
  return result;
}

}  // namespace

StatusOr<TriangleMesh> DecimateMesh(const TriangleMesh& mesh, const DecimationOptions& options) {
  MESHVID_RETURN_IF_ERROR(CheckDecimationInput(mesh, options));
  OmMesh om;
  om.request_vertex_status();
  om.request_edge_status();
  om.request_face_status();
  om.request_face_normals();
  std::vector<std::uint32_t> origin;
  BuildOpenMesh(mesh, &om, &origin);
  if (om.n_faces() == 0) {
    return InvalidArgumentError("mesh to decimate has no usable triangle (all degenerate)");
  }
  om.update_face_normals();
  om.PrepareMarks();
  if (options.lock_boundary) {
    for (auto v : om.vertices()) {
      if (om.is_boundary(v)) om.status(v).set_locked(true);
    }
  }

  LazyDecimater decimater(om);
  ModBoundaryQuadricT<OmMesh>::Handle quadric;
  decimater.add(quadric);
  decimater.SetQuadric(&decimater.module(quadric));
  decimater.module(quadric).set_max_edge_length(options.max_edge_length);
  if (options.max_normal_deviation_degrees > 0) {
    OpenMesh::Decimater::ModNormalDeviationT<OmMesh>::Handle deviation;
    decimater.add(deviation);
    decimater.module(deviation).set_binary(true);
    decimater.module(deviation).set_normal_deviation(
        static_cast<float>(options.max_normal_deviation_degrees));
  }
  if (options.max_error > 0) {
    ModRemovedVertexBoundT<OmMesh>::Handle bound;
    decimater.add(bound);
    decimater.module(bound).set_max_distance(static_cast<float>(options.max_error));
  }
  if (options.max_aspect_ratio > 0) {
    OpenMesh::Decimater::ModAspectRatioT<OmMesh>::Handle aspect;
    decimater.add(aspect);
    decimater.module(aspect).set_binary(true);
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(options.max_aspect_ratio));
  }
  if (!decimater.initialize()) return InternalError("OpenMesh decimater failed to initialise");
  decimater.DecimateTo(options.target_vertices, options.target_triangles);
  // No garbage collection: it would renumber the vertices `origin` is indexed by, and the
  // face range skips deleted faces anyway.

  TriangleMesh result = FromOpenMesh(om, origin, mesh);
  RemoveUnreferencedVertices(&result);
  if (result.triangles.empty()) return InternalError("decimation left no triangle");
  if (!mesh.normals.empty()) result.normals = ComputeVertexNormals(result);
  return result;
}

}  // namespace meshvid
