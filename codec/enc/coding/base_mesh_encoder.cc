#include "codec/enc/coding/base_mesh_encoder.h"

#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <string>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "codec/common/point_tree.h"
#include "codec/dec/base_mesh_decoder.h"

namespace meshvid {

namespace {

/// Adds one attribute of 3 components per vertex (identity mapping), vertex i's taken from
/// values[i] (a 3-vector of the type `data_type` names).
template <typename Vector3>
void AddVertexAttribute(draco::GeometryAttribute::Type type, draco::DataType data_type,
                        bool normalized, std::span<const Vector3> values, draco::Mesh* draco_mesh) {
  using Scalar = typename Vector3::Scalar;
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, 3, data_type, normalized, sizeof(Scalar) * 3, 0);
  const int id = draco_mesh->AddAttribute(attribute, /*identity_mapping=*/true, values.size());
  draco::PointAttribute* added = draco_mesh->attribute(id);
  for (std::size_t i = 0; i < values.size(); ++i) {
    added->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)),
                             values[i].data());
  }
}

/// Codes `mesh` with one Draco method and decodes the result.
StatusOr<EncodedBaseMesh> EncodeWith(const TriangleMesh& mesh, const BaseMeshEncoding& settings,
                                     bool edgebreaker) {
  draco::Mesh draco_mesh;
  draco_mesh.set_num_points(static_cast<std::uint32_t>(mesh.vertex_count()));
  AddVertexAttribute(draco::GeometryAttribute::POSITION, draco::DT_FLOAT32, /*normalized=*/false,
                     std::span<const Eigen::Vector3f>(mesh.positions), &draco_mesh);
  if (settings.code_colours && !mesh.colours.empty()) {
    AddVertexAttribute(draco::GeometryAttribute::COLOR, draco::DT_UINT8, /*normalized=*/true,
                       std::span<const Colour>(mesh.colours), &draco_mesh);
  }
  draco_mesh.SetNumFaces(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(mesh.triangles[t][c]);
    draco_mesh.SetFace(draco::FaceIndex(static_cast<std::uint32_t>(t)), face);
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, settings.position_bits);
  encoder.SetSpeedOptions(settings.encoding_speed, settings.encoding_speed);
  encoder.SetEncodingMethod(edgebreaker ? draco::MESH_EDGEBREAKER_ENCODING
                                        : draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(draco_mesh, &buffer);
  if (!status.ok()) return InternalError("Draco cannot encode the base mesh: " +
                                         status.error_msg_string());

  EncodedBaseMesh result;
  result.position_bits = settings.position_bits;
  result.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  MESHVID_ASSIGN_OR_RETURN(
      result.decoded, DecodeBaseMesh(result.bytes, settings.code_colours ? VertexColours::kRead
                                                                         : VertexColours::kIgnore));
  return result;
}

Status CheckSettings(const TriangleMesh& mesh, const BaseMeshEncoding& settings) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "base mesh"));
  if (mesh.triangle_count() > kMaxBaseMeshTriangles ||
      mesh.vertex_count() > 3 * std::size_t{kMaxBaseMeshTriangles}) {
    return InvalidArgumentError("a base mesh may have at most " +
                                std::to_string(kMaxBaseMeshTriangles) + " triangles, got " +
                                std::to_string(mesh.triangle_count()));
  }
  if (settings.position_bits < 1 || settings.position_bits > 30) {
    return InvalidArgumentError("base mesh position bits must be in 1..30, got " +
                                std::to_string(settings.position_bits));
  }
  return Status::Ok();
}

constexpr std::uint32_t kUnplaced = ~0u;

/// The state of MatchVertices: each input vertex's decoded vertex (kUnplaced until found),
/// which decoded vertices are taken, and the candidates of those not yet placed.
struct VertexMatch {
  std::vector<std::uint32_t>& vertex_in_decoded;
  std::vector<char> taken;
  std::map<std::uint32_t, std::vector<std::uint32_t>> candidates;  // of the ambiguous ones
  /// Decoded directed edge -> the third corner of its triangle.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> third;

  void Place(std::uint32_t v, std::uint32_t w) {
    taken[w] = 1;
    vertex_in_decoded[v] = w;
  }
};

/// Places the vertices with one decoded vertex within `step`, and lists the candidates of the
/// others. False when a vertex has none, or its one is taken.
bool PlaceUnambiguous(const TriangleMesh& mesh, const TriangleMesh& decoded, float step,
                      VertexMatch* match) {
  const PointCloud cloud{decoded.positions};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  std::vector<std::pair<std::uint32_t, float>> near;  // (index, squared distance)
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    near.clear();
    tree.radiusSearch(mesh.positions[v].data(), step * step, near, nanoflann::SearchParams());
    if (near.empty()) return false;
    if (near.size() == 1) {
      if (match->taken[near[0].first]) return false;
      match->Place(static_cast<std::uint32_t>(v), near[0].first);
      continue;
    }
    auto& list = match->candidates[static_cast<std::uint32_t>(v)];
    for (const auto& item : near) list.push_back(item.first);
  }
  return true;
}

/// Places ambiguous vertices by the triangles around them (an input triangle whose other two
/// corners are placed names the decoded triangle, and so its third corner) and by
/// elimination (one candidate left untaken), until neither places more. False on a
/// contradiction.
bool PlaceByNeighbours(const TriangleMesh& mesh, VertexMatch* match) {
  std::vector<std::uint32_t>& placed = match->vertex_in_decoded;
  for (bool progress = true; progress && !match->candidates.empty();) {
    progress = false;
    for (const Triangle& tri : mesh.triangles) {
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = tri[(c + 2) % 3];
        const std::uint32_t a = placed[tri[c]];
        const std::uint32_t b = placed[tri[(c + 1) % 3]];
        if (placed[v] != kUnplaced || a == kUnplaced || b == kUnplaced) continue;
        const auto edge = match->third.find({a, b});
        if (edge == match->third.end()) return false;
        const std::vector<std::uint32_t>& list = match->candidates.at(v);
        const std::uint32_t w = edge->second;
        if (match->taken[w] || std::find(list.begin(), list.end(), w) == list.end()) {
          return false;
        }
        match->Place(v, w);
        match->candidates.erase(v);
        progress = true;
      }
    }
    // A vertex with one candidate left untaken has it.
    for (auto it = match->candidates.begin(); it != match->candidates.end();) {
      std::uint32_t free_count = 0, last_free = 0;
      for (std::uint32_t w : it->second) {
        if (!match->taken[w]) ++free_count, last_free = w;
      }
      if (free_count != 1) {
        ++it;
        continue;
      }
      match->Place(it->first, last_free);
      it = match->candidates.erase(it);
      progress = true;
    }
  }
  return true;
}

/// Places what is left: clusters of coincident vertices no placed neighbour tells apart (a
/// sliver whose corners all share one quantised position). Any untaken candidates decode to
/// the same place; a search over them keeps each triangle's orientation. False when it finds
/// none within its budget.
bool PlaceBySearch(const TriangleMesh& mesh, VertexMatch* match) {
  std::vector<std::uint32_t>& placed = match->vertex_in_decoded;
  std::vector<std::uint32_t> left;
  std::map<std::uint32_t, std::vector<std::uint32_t>> triangles_of;  // of the left vertices
  for (const auto& entry : match->candidates) left.push_back(entry.first);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      if (match->candidates.count(mesh.triangles[t][c])) {
        triangles_of[mesh.triangles[t][c]].push_back(t);
      }
    }
  }
  auto consistent = [&](std::uint32_t v) {
    for (std::uint32_t t : triangles_of[v]) {
      const Triangle& tri = mesh.triangles[t];
      const std::uint32_t a = placed[tri[0]], b = placed[tri[1]], c = placed[tri[2]];
      if (a == kUnplaced || b == kUnplaced || c == kUnplaced) continue;
      const auto edge = match->third.find({a, b});
      if (edge == match->third.end() || edge->second != c) return false;
    }
    return true;
  };
  // Depth-first over `left` with an explicit stack (a recursion as deep as `left` is long
  // overflows the stack on large ambiguous meshes): next_choice[i] is the index of the next
  // candidate of left[i] to try.
  int budget = 100000;  // assignments tried before giving up (the sequential coder then)
  std::vector<std::size_t> next_choice(left.size(), 0);
  std::size_t i = 0;
  while (i < left.size()) {
    const std::uint32_t v = left[i];
    const std::vector<std::uint32_t>& choices = match->candidates.at(v);
    if (placed[v] != kUnplaced) {  // back here after a failure further on
      match->taken[placed[v]] = 0;
      placed[v] = kUnplaced;
    }
    bool found = false;
    while (next_choice[i] < choices.size() && !found) {
      const std::uint32_t w = choices[next_choice[i]++];
      if (match->taken[w]) continue;
      if (--budget < 0) return false;
      match->Place(v, w);
      found = consistent(v);
      if (!found) {
        match->taken[w] = 0;
        placed[v] = kUnplaced;
      }
    }
    if (found) {
      ++i;
      continue;
    }
    if (i == 0) return false;
    next_choice[i] = 0;
    --i;
  }
  return true;
}

/// Where Draco put each input vertex: the one decoded vertex within a quantisation step.
/// Vertices that share a position with others (a contour's coincident vertices) have several
/// candidates; they are told apart by the triangles around them or by elimination
/// (PlaceByNeighbours); coincident vertices nothing tells apart take free candidates that
/// keep their triangles' orientation (PlaceBySearch). False when that fails.
bool MatchVertices(const TriangleMesh& mesh, const TriangleMesh& decoded, int position_bits,
                   std::vector<std::uint32_t>* vertex_in_decoded) {
  const float step = BoundingBox(mesh).sizes().maxCoeff() / float((1u << position_bits) - 1);
  vertex_in_decoded->assign(mesh.vertex_count(), kUnplaced);
  VertexMatch match{*vertex_in_decoded, std::vector<char>(decoded.vertex_count(), 0), {}, {}};
  if (!PlaceUnambiguous(mesh, decoded, step, &match)) return false;
  if (match.candidates.empty()) return true;
  for (const Triangle& tri : decoded.triangles) {
    for (int c = 0; c < 3; ++c) match.third[{tri[c], tri[(c + 1) % 3]}] = tri[(c + 2) % 3];
  }
  return PlaceByNeighbours(mesh, &match) && PlaceBySearch(mesh, &match);
}

/// Finds where Draco put every input vertex and triangle (MatchVertices), and checks that the
/// triangles are the same up to order and rotation. False (nothing filled) otherwise.
bool MatchDecodedOrder(const TriangleMesh& mesh, int position_bits, EncodedBaseMesh* coded) {
  const TriangleMesh& decoded = coded->decoded;
  if (decoded.vertex_count() != mesh.vertex_count() ||
      decoded.triangle_count() != mesh.triangle_count()) {
    return false;
  }
  std::vector<std::uint32_t> vertex_in_decoded;
  if (!MatchVertices(mesh, decoded, position_bits, &vertex_in_decoded)) return false;
  // Triangles as rotated to start at their smallest decoded vertex.
  auto key = [](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (b < a && b < c) return std::array<std::uint32_t, 3>{b, c, a};
    if (c < a && c < b) return std::array<std::uint32_t, 3>{c, a, b};
    return std::array<std::uint32_t, 3>{a, b, c};
  };
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> decoded_triangles;
  for (std::size_t t = 0; t < decoded.triangle_count(); ++t) {
    const Triangle& tri = decoded.triangles[t];
    decoded_triangles[key(tri[0], tri[1], tri[2])] = static_cast<std::uint32_t>(t);
  }
  std::vector<std::uint32_t> triangle_in_decoded(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const auto it = decoded_triangles.find(key(vertex_in_decoded[tri[0]],
                                               vertex_in_decoded[tri[1]],
                                               vertex_in_decoded[tri[2]]));
    if (it == decoded_triangles.end()) return false;
    triangle_in_decoded[t] = it->second;
  }
  coded->vertex_in_decoded = std::move(vertex_in_decoded);
  coded->triangle_in_decoded = std::move(triangle_in_decoded);
  return true;
}

}  // namespace

StatusOr<EncodedBaseMesh> EncodeBaseMesh(const TriangleMesh& mesh,
                                         const BaseMeshEncoding& settings) {
  MESHVID_RETURN_IF_ERROR(CheckSettings(mesh, settings));
  if (settings.allow_reorder) return EncodeWith(mesh, settings, /*edgebreaker=*/true);
  if (settings.try_edgebreaker) {
    // A finer step parts vertices that one step could not tell apart.
    const int finest = std::min(30, settings.position_bits + kEdgebreakerExtraBits);
    for (BaseMeshEncoding finer = settings; finer.position_bits <= finest;
         ++finer.position_bits) {
      StatusOr<EncodedBaseMesh> small = EncodeWith(mesh, finer, /*edgebreaker=*/true);
      if (small.ok() && MatchDecodedOrder(mesh, finer.position_bits, &*small)) return small;
    }
  }
  return EncodeWith(mesh, settings, /*edgebreaker=*/false);
}

}  // namespace meshvid
