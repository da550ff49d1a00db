// MvidDecoder: reads a .mvid file and reconstructs any frame at any level, with the same
// triangles at every frame of a level.
#ifndef MESHVID_CODEC_DEC_MVID_DECODER_H_
#define MESHVID_CODEC_DEC_MVID_DECODER_H_

#include <cstdint>
#include <istream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "codec/common/displacement_image.h"
#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/subdivision.h"
#include "codec/common/video_codec.h"
#include "codec/dec/motion_decoder.h"
#include "format/container_reader.h"
#include "format/status.h"

namespace meshvid {

/// What a .mvid holds.
struct MvidInfo {
  double frame_rate = 0;
  std::uint32_t frame_count = 0;  ///< frames readable (all, or those before a cut)
  std::uint32_t gof_size = 0;
  std::uint32_t gof_count = 0;
  int levels = 0;
  VideoCodec codec = VideoCodec::kHevc;
  int picture_width = 0;
  int picture_height = 0;
  std::size_t base_vertices = 0;
  std::size_t base_triangles = 0;
  std::uint32_t segments = 0;
  std::uint64_t file_bytes = 0;
  std::uint64_t base_bytes = 0;       ///< BASE payload
  std::uint64_t motion_bytes = 0;     ///< MOTN payload
  bool indexed = false;               ///< groups located through the index (else by scanning)
  std::string metadata_json;
  /// Vertices and triangles of a decoded frame at each level 0..levels.
  std::vector<std::size_t> vertices_per_level;
  std::vector<std::size_t> triangles_per_level;
};

/// Bytes of the per-group streams, summed over the readable groups.
struct MvidStreamSizes {
  std::uint64_t transform_bytes = 0;  ///< group side information (transforms, ranges)
  std::uint64_t video_bytes = 0;      ///< displacement video packets
};

/// Decoder settings.
struct MvidDecoderOptions {
  int threads = 1;  ///< video decoder threads (0: automatic)
};

/// Decodes frames of a .mvid. Frames may be asked for in any order; asking in order is
/// cheapest (each group of frames is decoded once and kept while its frames are asked for).
class MvidDecoder {
 public:
  ~MvidDecoder();
  static StatusOr<std::unique_ptr<MvidDecoder>> OpenFile(const std::string& path,
                                                         const MvidDecoderOptions& options = {});
  static StatusOr<std::unique_ptr<MvidDecoder>> OpenMemory(std::vector<std::uint8_t> bytes,
                                                           const MvidDecoderOptions& options = {});
  /// Reads a stream front to back (a pipe, a socket): frames must then be asked for in
  /// non-decreasing order, and `in` must outlive the decoder. info().frame_count is the
  /// header's (0 if the writer did not know it); file and stream sizes are not known.
  static StatusOr<std::unique_ptr<MvidDecoder>> OpenStream(std::istream& in,
                                                           const MvidDecoderOptions& options = {},
                                                           const std::string& name = "<stream>");

  const MvidInfo& info() const { return info_; }
  /// The base mesh as decoded (level 0 before motion).
  const TriangleMesh& base_mesh() const { return base_; }
  const MotionModel& motion() const { return motion_; }
  /// The triangles of every frame at `level` (computed once, then shared).
  StatusOr<const std::vector<Triangle>*> Triangles(int level);
  /// Positions of frame `frame` at `level`, indexed as Triangles(level).
  Status DecodePositions(std::uint32_t frame, int level, std::vector<Eigen::Vector3f>* positions);
  /// The mesh of frame `frame` at `level` (positions + triangles).
  StatusOr<TriangleMesh> DecodeFrame(std::uint32_t frame, int level);
  /// The de-quantised displacement field of a frame (all samples, finest level).
  Status DecodeDisplacements(std::uint32_t frame, std::vector<float>* displacements);
  /// Reads every group once to total the bytes of each per-group stream (files and memory
  /// buffers only).
  StatusOr<MvidStreamSizes> MeasureStreams();
  /// The segment transforms of a frame.
  StatusOr<std::vector<RigidTransform>> DecodeTransforms(std::uint32_t frame);

 private:
  class GroupSource;
  class IndexedGroups;
  class StreamedGroups;
  struct Group;

  MvidDecoder() = default;
  /// Sets up everything from the header, BASE and MOTN payloads; fills info_ but the sizes.
  Status Initialize(const ContainerHeader& header, const std::vector<std::uint8_t>& base_bytes,
                    const std::vector<std::uint8_t>& motion_bytes, const std::string& name);
  static StatusOr<std::unique_ptr<MvidDecoder>> OpenIndexed(ContainerReader reader,
                                                            const MvidDecoderOptions& options);
  Status LoadGroupOf(std::uint32_t frame);
  /// The layout of `packing` (built once), checked against the stream's picture size.
  StatusOr<const DisplacementLayout*> LayoutFor(DisplacementPacking packing);
  Status CheckLevel(int level) const;

  MvidDecoderOptions options_;
  std::unique_ptr<GroupSource> groups_;
  MvidInfo info_;
  TriangleMesh base_;
  MotionModel motion_;
  MotionQuantization quantization_;
  RegularSubdivision subdivision_;
  std::map<DisplacementPacking, DisplacementLayout> layouts_;
  std::vector<std::vector<Triangle>> triangles_;  ///< per level, filled on first use
  /// Base triangles that are surface (all unless MOTN's mask hides some).
  std::size_t SurfaceTriangleCount() const;
  std::unique_ptr<Group> group_;                  ///< the decoded group in use
  // Scratch buffers reused across frames.
  std::vector<Eigen::Vector3f> posed_, normals_, origins_, directions_;
  std::vector<float> displacements_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_MVID_DECODER_H_
