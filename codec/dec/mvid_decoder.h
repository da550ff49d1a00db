// MvidDecoder: reads a .mvid file and reconstructs any frame at any level, with the same
// triangles at every frame of a level.
#ifndef MESHVID_CODEC_DEC_MVID_DECODER_H_
#define MESHVID_CODEC_DEC_MVID_DECODER_H_

#include <cstdint>
#include <istream>
#include <map>
#include <memory>
#include <string>
#include <utility>
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

/// Where a key group's frames are: a run of frames that share one base mesh, so one
/// connectivity at every level.
struct MvidKeyGroupSpan {
  std::uint32_t first_frame = 0;
  std::uint32_t frame_count = 0;
  std::uint32_t first_gof = 0;
  std::uint32_t gof_count = 0;
};

/// What one key group holds (MvidDecoder::DescribeKeyGroup).
struct MvidKeyGroupInfo {
  MvidKeyGroupSpan span;
  std::size_t base_vertices = 0;
  std::size_t base_triangles = 0;
  std::uint32_t segments = 0;
  std::uint64_t base_bytes = 0;    ///< BASE payload
  std::uint64_t motion_bytes = 0;  ///< MOTN payload
  int picture_width = 0;           ///< its displacement pictures
  int picture_height = 0;
  std::vector<std::size_t> vertices_per_level;
  std::vector<std::size_t> triangles_per_level;
};

/// What a .mvid holds. Base-mesh figures are key group 0's.
struct MvidInfo {
  double frame_rate = 0;
  std::uint32_t frame_count = 0;  ///< frames readable (all, or those before a cut)
  /// HEAD's frame_count (0: unknown); differs from frame_count when the file is cut or damaged.
  std::uint32_t declared_frame_count = 0;
  std::uint32_t gof_size = 0;
  std::uint32_t gof_count = 0;
  int levels = 0;
  VideoCodec codec = VideoCodec::kHevc;
  bool colour = false;  ///< the file has a colour stream: frames decode with vertex colours
  int picture_width = 0;
  int picture_height = 0;
  std::size_t base_vertices = 0;
  std::size_t base_triangles = 0;
  std::uint32_t segments = 0;
  std::uint64_t file_bytes = 0;
  std::uint64_t base_bytes = 0;       ///< BASE payload
  std::uint64_t motion_bytes = 0;     ///< MOTN payload
  bool indexed = false;               ///< groups located through the index (else by scanning)
  std::uint32_t format_version = 0;   ///< the container's (1: one key group; 2: key groups)
  /// The readable key groups (files and memory buffers; a stream lists those read so far).
  std::vector<MvidKeyGroupSpan> key_groups;
  std::string metadata_json;
  /// Vertices and triangles of a decoded frame at each level 0..levels.
  std::vector<std::size_t> vertices_per_level;
  std::vector<std::size_t> triangles_per_level;

  /// True when fewer frames are readable than the header promises (a cut or damaged file,
  /// opened with MvidDecoderOptions::allow_partial).
  bool partial() const { return declared_frame_count > frame_count; }
};

/// "partial file: only 8 of the 12 frames its header promises are readable", the words every
/// front end uses for a partial file (MvidInfo::partial), or "" for a whole one.
std::string PartialFileText(const MvidInfo& info);

/// Bytes of the per-group streams, summed over the readable groups.
struct MvidStreamSizes {
  std::uint64_t transform_bytes = 0;  ///< group side information (transforms, ranges)
  std::uint64_t video_bytes = 0;      ///< displacement video packets
  std::uint64_t colour_bytes = 0;     ///< colour video packets
  std::uint64_t base_bytes = 0;       ///< BASE payloads of every key group
  std::uint64_t motion_bytes = 0;     ///< MOTN payloads of every key group
  /// Per key group: its BASE, MOTN, side information and video bytes.
  std::vector<std::uint64_t> key_group_bytes;
};

/// Decoder settings.
struct MvidDecoderOptions {
  int threads = 1;  ///< video decoder threads (0: automatic)
  /// Open a file whose header promises more frames than it holds (cut or damaged), giving
  /// the frames that are readable; by default such a file is refused (corrupt). Streams are
  /// read as they come and are not checked.
  bool allow_partial = false;
};

/// Decodes frames of a .mvid. Frames may be asked for in any order; asking in order is
/// cheapest (each group of frames is decoded once and kept while its frames are asked for, and
/// each key group's base mesh once while its frames are asked for). Every frame of a key group
/// has the same triangles at a level; frames of different key groups have different ones.
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
  /// The key group holding `frame` (a stream reads up to that frame's group to know).
  StatusOr<std::uint32_t> KeyGroupOf(std::uint32_t frame);
  /// The key group whose frames were decoded last (0 after opening).
  std::uint32_t current_key_group() const;
  /// Loads key group `k` (files and memory buffers) and describes it.
  StatusOr<MvidKeyGroupInfo> DescribeKeyGroup(std::uint32_t k);
  /// The current key group's base mesh as decoded (level 0 before motion).
  const TriangleMesh& base_mesh() const;
  /// The current key group's segments and blend weights.
  const MotionModel& motion() const;
  /// The current key group's triangles at `level`, those of each of its frames.
  StatusOr<const std::vector<Triangle>*> Triangles(int level);
  /// The triangles of `frame` at `level` (those of every frame of its key group).
  StatusOr<const std::vector<Triangle>*> TrianglesOf(std::uint32_t frame, int level);
  /// Positions of frame `frame` at `level`, indexed as Triangles(level).
  Status DecodePositions(std::uint32_t frame, int level, std::vector<Eigen::Vector3f>* positions);
  /// The mesh of frame `frame` at `level` (positions + triangles, and vertex colours when the
  /// file has colour).
  StatusOr<TriangleMesh> DecodeFrame(std::uint32_t frame, int level);
  /// The vertex colours of frame `frame` at `level`, indexed as DecodePositions' positions.
  /// kInvalidArgument when the file has no colour (info().colour).
  Status DecodeColours(std::uint32_t frame, int level, std::vector<Colour>* colours);
  /// The de-quantised displacement field of a frame (all samples, finest level).
  Status DecodeDisplacements(std::uint32_t frame, std::vector<float>* displacements);
  /// Reads every group once to total the bytes of each per-group stream (files and memory
  /// buffers only).
  StatusOr<MvidStreamSizes> MeasureStreams();
  /// The segment transforms of a frame.
  StatusOr<std::vector<RigidTransform>> DecodeTransforms(std::uint32_t frame);
  /// The size of the displacement pictures of the group holding `frame`: its key group's
  /// layout in the packing the group states (HEAD gives key group 0's). Decodes that group.
  StatusOr<std::pair<int, int>> PictureSizeOf(std::uint32_t frame);
  /// The decoded displacement picture of `frame` (10-bit samples as the video gives them,
  /// before de-quantisation). Valid until a frame of another group is decoded.
  StatusOr<const GreyPicture*> DisplacementPicture(std::uint32_t frame);
  /// The decoded colour picture of `frame` (8-bit Y Cb Cr 4:4:4 as the video gives it), of a
  /// file with a colour stream. Valid until a frame of another group is decoded.
  StatusOr<const ColourPicture*> DecodedColourPicture(std::uint32_t frame);

 private:
  class GroupSource;
  class IndexedGroups;
  class StreamedGroups;
  struct Group;
  struct KeyGroup;

  MvidDecoder() = default;
  /// Checks the header and fills info_ from it.
  Status ReadHeader(const ContainerHeader& header, const std::string& name);
  /// Decodes `group`'s colour video (files with a colour stream) unless it is decoded.
  Status DecodeColourVideo(Group* group);
  /// Makes key group `k` the current one (decoding its BASE and MOTN unless it already is);
  /// fills info_'s base figures from key group 0.
  Status LoadKeyGroup(std::size_t k);
  static StatusOr<std::unique_ptr<MvidDecoder>> OpenIndexed(ContainerReader reader,
                                                            const MvidDecoderOptions& options);
  Status LoadGroupOf(std::uint32_t frame);
  Status CheckLevel(int level) const;

  MvidDecoderOptions options_;
  std::string name_;
  std::unique_ptr<GroupSource> groups_;
  MvidInfo info_;
  std::unique_ptr<KeyGroup> key_group_;           ///< the key group in use
  std::unique_ptr<Group> group_;                  ///< the decoded group in use
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_MVID_DECODER_H_
