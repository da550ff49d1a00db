#include "tests/analytic_mvid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "codec/common/deformation_graph.h"
#include "codec/common/subdivision.h"

namespace meshvid::testing {

TriangleMesh SphereMesh(int refinements) {
  TriangleMesh mesh;
  mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int r = 0; r < refinements; ++r) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = midpoints.emplace(key, mesh.positions.size());
      if (added) mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : mesh.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                          ca = midpoint(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    mesh.triangles = std::move(finer);
  }
  return mesh;
}

TriangleMesh LatLongSphere(int rings, int segments) {
  TriangleMesh mesh;
  mesh.positions.emplace_back(0.0f, 1.0f, 0.0f);
  for (int r = 1; r <= rings; ++r) {
    const double theta = M_PI * r / (rings + 1);
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      mesh.positions.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta),
                                  -std::sin(theta) * std::sin(phi));
    }
  }
  mesh.positions.emplace_back(0.0f, -1.0f, 0.0f);
  const auto at = [segments](int r, int s) {
    return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.emplace_back(0, at(1, s), at(1, s + 1));
    for (int r = 1; r < rings; ++r) {
      mesh.triangles.emplace_back(at(r, s), at(r + 1, s), at(r + 1, s + 1));
      mesh.triangles.emplace_back(at(r, s), at(r + 1, s + 1), at(r, s + 1));
    }
    mesh.triangles.emplace_back(at(rings, s), south, at(rings, s + 1));
  }
  return mesh;
}

MotionModel TwoSegments(const TriangleMesh& base) {
  MotionModel model;
  model.segment_count = 2;
  for (const auto& p : base.positions) {
    VertexBlend blend;
    const float w = std::clamp(0.5f + p.y() / 0.4f, 0.0f, 1.0f);  // weight of segment 0
    if (w >= 1.0f || w <= 0.0f) {
      blend.count = 1;
      blend.influences[0] = {w >= 1.0f ? 0u : 1u, 1.0f};
    } else {
      blend.count = 2;
      blend.influences[0] = {0, w};
      blend.influences[1] = {1, 1.0f - w};
    }
    model.blends.push_back(blend);
  }
  return model;
}

MotionModel DeformationNodes(const TriangleMesh& base, float spacing) {
  StatusOr<MotionModel> model = SampleNodeMotion(base, VertexNeighbours(base), spacing);
  return model.ok() ? std::move(*model) : MotionModel{};
}

std::vector<RigidTransform> TransformsAt(int frame) {
  RigidTransform upper, lower;
  upper.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.05f * frame, Eigen::Vector3f::UnitY()));
  lower.translation = Eigen::Vector3f(0.01f * frame, 0, 0);
  return {upper, lower};
}

float DetailAt(const Eigen::Vector3f& rest, int frame) {
  return 0.02f * std::sin(5 * rest.x()) * std::cos(3 * rest.y() + 0.2f * frame);
}

Colour ColourAt(const Eigen::Vector3f& rest, int frame) {
  const Eigen::Vector3f rgb(128 + 100 * std::sin(4 * rest.x() + 0.3f * frame),
                            128 + 100 * std::cos(3 * rest.y()),
                            128 + 80 * std::sin(2 * rest.z() + rest.x()));
  return rgb.array().round().cast<std::uint8_t>().matrix();
}

namespace {

/// Writes frames [first, end) with the writer's current key group, in groups of gof_size.
Status WriteAnalyticFrames(MvidWriter& writer, int first_frame, int end) {
  // The detail is a function of where each sample sits on the decoded, unposed base.
  const RegularSubdivision& lattice = writer.subdivision();
  std::vector<Eigen::Vector3f> rest_points, rest_directions;
  EvaluateSampleFrames(lattice, lattice.levels(), writer.decoded_base().positions,
                       ComputeVertexNormals(writer.decoded_base()), &rest_points,
                       &rest_directions);
  const int gof_size = writer.settings().gof_size;
  for (int first = first_frame; first < end; first += gof_size) {
    std::vector<std::vector<RigidTransform>> transforms;
    std::vector<std::vector<float>> displacements;
    std::vector<std::vector<Colour>> colours;
    for (int f = first; f < std::min(end, first + gof_size); ++f) {
      // Segment s moves as TransformsAt's segment s mod 2 (deformation nodes alternate).
      const std::vector<RigidTransform> two = TransformsAt(f);
      auto& frame = transforms.emplace_back();
      for (std::uint32_t s = 0; s < writer.motion().segment_count; ++s) {
        frame.push_back(two[s % 2]);
      }
      auto& field = displacements.emplace_back();
      for (const auto& p : rest_points) field.push_back(DetailAt(p, f));
      if (!writer.settings().colour) continue;
      auto& colour = colours.emplace_back();
      for (const auto& p : rest_points) colour.push_back(ColourAt(p, f));
    }
    MESHVID_RETURN_IF_ERROR(writer.WriteGroup(transforms, displacements, colours));
  }
  return Status::Ok();
}

}  // namespace

StatusOr<std::vector<std::uint8_t>> WriteAnalyticMvid(const TriangleMesh& base,
                                                      const MotionModel& motion, int frames,
                                                      const MvidWriterSettings& settings,
                                                      MvidWriteStats* stats) {
  std::vector<std::uint8_t> bytes;
  MESHVID_ASSIGN_OR_RETURN(auto writer, MvidWriter::Create(
                                            [&bytes](std::span<const std::uint8_t> b) {
                                              bytes.insert(bytes.end(), b.begin(), b.end());
                                              return Status::Ok();
                                            },
                                            base, motion, settings));
  MESHVID_RETURN_IF_ERROR(WriteAnalyticFrames(*writer, 0, frames));
  MESHVID_RETURN_IF_ERROR(writer->Finish());
  if (stats != nullptr) *stats = writer->stats();
  return bytes;
}

StatusOr<std::vector<std::uint8_t>> WriteAnalyticKeyGroups(
    const std::vector<AnalyticKeyGroup>& key_groups, int frames,
    const MvidWriterSettings& settings, MvidWriteStats* stats) {
  if (key_groups.empty() || key_groups[0].first_frame != 0) {
    return InvalidArgumentError("the first key group must start at frame 0");
  }
  std::vector<std::uint8_t> bytes;
  std::unique_ptr<MvidWriter> writer;
  for (std::size_t k = 0; k < key_groups.size(); ++k) {
    const TriangleMesh& base = key_groups[k].base;
    if (k == 0) {
      MESHVID_ASSIGN_OR_RETURN(writer, MvidWriter::Create(
                                           [&bytes](std::span<const std::uint8_t> b) {
                                             bytes.insert(bytes.end(), b.begin(), b.end());
                                             return Status::Ok();
                                           },
                                           base, TwoSegments(base), settings));
    } else {
      MESHVID_RETURN_IF_ERROR(writer->StartKeyGroup(base, TwoSegments(base)));
    }
    const int end = k + 1 < key_groups.size() ? key_groups[k + 1].first_frame : frames;
    MESHVID_RETURN_IF_ERROR(WriteAnalyticFrames(*writer, key_groups[k].first_frame, end));
  }
  MESHVID_RETURN_IF_ERROR(writer->Finish());
  if (stats != nullptr) *stats = writer->stats();
  return bytes;
}

namespace {

/// The exact positions of frame f at `level`.
std::vector<Eigen::Vector3f> ExactPositions(const MvidDecoder& decoder, int frame, int level,
                                            const std::vector<RigidTransform>& transforms,
                                            const RegularSubdivision& lattice) {
  const TriangleMesh& base = decoder.base_mesh();
  std::vector<Eigen::Vector3f> rest, directions, posed, origins;
  EvaluateSampleFrames(lattice, level, base.positions, ComputeVertexNormals(base), &rest,
                       &directions);
  PoseVertices(decoder.motion(), transforms, base.positions, &posed);
  std::vector<Eigen::Vector3f> posed_normals;
  ComputeVertexNormals(posed, base.triangles, &posed_normals);
  EvaluateSampleFrames(lattice, level, posed, posed_normals, &origins, &directions);
  std::vector<Eigen::Vector3f> exact;
  for (std::size_t s = 0; s < origins.size(); ++s) {
    exact.push_back(origins[s] + DetailAt(rest[s], frame) * directions[s]);
  }
  return exact;
}

}  // namespace

StatusOr<ReconstructionError> MeasureReconstructionError(MvidDecoder& decoder, int level,
                                                         int frames) {
  ReconstructionError error;
  double sum_squares = 0;
  std::size_t count = 0;
  std::vector<Eigen::Vector3f> positions;
  std::optional<RegularSubdivision> lattice;
  std::uint32_t lattice_key_group = 0;
  for (int f = 0; f < frames; ++f) {
    MESHVID_RETURN_IF_ERROR(decoder.DecodePositions(f, level, &positions));
    // The lattice of the frame's key group (decoding the frame made it current).
    if (!lattice || lattice_key_group != decoder.current_key_group()) {
      MESHVID_ASSIGN_OR_RETURN(lattice, RegularSubdivision::Create(decoder.base_mesh(),
                                                                   decoder.info().levels));
      lattice_key_group = decoder.current_key_group();
    }
    MESHVID_ASSIGN_OR_RETURN(const std::vector<RigidTransform> transforms,
                             decoder.DecodeTransforms(f));
    const auto exact = ExactPositions(decoder, f, level, transforms, *lattice);
    if (exact.size() != positions.size()) return InternalError("sample counts differ");
    for (std::size_t s = 0; s < positions.size(); ++s) {
      const float e = (positions[s] - exact[s]).norm();
      error.max = std::max(error.max, e);
      sum_squares += double(e) * e;
      ++count;
    }
  }
  error.rms = static_cast<float>(std::sqrt(sum_squares / std::max<std::size_t>(count, 1)));
  return error;
}

StatusOr<int> MaxColourError(MvidDecoder& decoder, int level, int frames) {
  int error = 0;
  std::vector<Colour> colours;
  std::vector<Eigen::Vector3f> rest_points, rest_directions;
  for (int f = 0; f < frames; ++f) {
    MESHVID_RETURN_IF_ERROR(decoder.DecodeColours(f, level, &colours));
    // The rest points of the frame's key group (decoding the frame made it current).
    MESHVID_ASSIGN_OR_RETURN(
        const RegularSubdivision lattice,
        RegularSubdivision::Create(decoder.base_mesh(), decoder.info().levels));
    EvaluateSampleFrames(lattice, level, decoder.base_mesh().positions,
                         ComputeVertexNormals(decoder.base_mesh()), &rest_points, &rest_directions);
    if (rest_points.size() != colours.size()) return InternalError("sample counts differ");
    for (std::size_t s = 0; s < colours.size(); ++s) {
      const Colour exact = ColourAt(rest_points[s], f);
      error = std::max(error, (colours[s].cast<int>() - exact.cast<int>()).cwiseAbs().maxCoeff());
    }
  }
  return error;
}

}  // namespace meshvid::testing
