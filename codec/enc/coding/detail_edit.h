// Editing a .mvid's detail (the paper's figure 3): a frame's surface, moved in a modelling
// tool, becomes a change of the displacement field that every frame of its key group takes,
// so the edit rides the moving surface. Only the displacement video of that key group's
// groups is coded again; every base mesh, motion, transform and colour packet, and every other
// group, is copied byte for byte.
#ifndef MESHVID_CODEC_ENC_CODING_DETAIL_EDIT_H_
#define MESHVID_CODEC_ENC_CODING_DETAIL_EDIT_H_

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "codec/common/progress.h"
#include "codec/common/subdivision.h"
#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// What an edited frame asks of the displacement field.
struct DetailChange {
  /// Per sample of the finest level: the distance to add along the sample's direction.
  std::vector<float> change;
  std::size_t moved_vertices = 0;  ///< edited vertices that moved at all
  double largest_normal_move = 0;  ///< the largest move along a vertex's direction
  /// The largest move across a vertex's direction: displacements move a vertex along its
  /// direction only, so this part of an edit is not carried.
  double largest_tangential_move = 0;
};

/// The change of the displacement field that edited positions of one frame at `level` ask
/// for. `decoded` and `directions` are the frame's decoded positions at `level` and its
/// samples' unit directions (EvaluateSampleFrames on the posed base); `edited` the same
/// vertices moved. Each vertex's change is its move's component along its direction; samples
/// finer than `level` take the change interpolated over the level's triangles.
/// kInvalidArgument if the sizes differ from the level's sample count or a position is not
/// finite.
StatusOr<DetailChange> DetailChangeFromPositions(const RegularSubdivision& lattice, int level,
                                                 std::span<const Eigen::Vector3f> decoded,
                                                 std::span<const Eigen::Vector3f> directions,
                                                 std::span<const Eigen::Vector3f> edited);

/// Settings of EditDetail.
struct DetailEditOptions {
  std::uint32_t frame = 0;  ///< the edited frame
  int level = -1;           ///< the level `edited` holds (-1: the finest stored)
  /// The frame's positions at `level` as MvidDecoder::DecodePositions gives them, moved.
  std::vector<Eigen::Vector3f> edited;
  /// The video coding of the edited groups (the file does not record its quality): the input's
  /// codec, at this quality (0..100, as `meshvid encode --quality`).
  int quality = 40;
  int effort = 4;             ///< video encoder effort 0 (fastest) .. 9
  int threads = 0;            ///< video encoder threads, 0: automatic
  ProgressCallback progress;  ///< stage "editing" (groups of the key group)
};

/// What EditDetail did.
struct DetailEditSummary {
  std::uint32_t key_group = 0;                     ///< the edited key group
  std::uint32_t first_frame = 0, frame_count = 0;  ///< its frames, all edited
  std::uint32_t groups_coded = 0;                  ///< its groups, whose video was coded again
  DetailChange change;                             ///< the change (its field left empty)
  /// Groups whose displacement range had to widen to hold the edit.
  std::uint32_t ranges_widened = 0;
  std::uint64_t input_bytes = 0, output_bytes = 0;
};

/// Writes `output`: `input` with the edit applied to every frame of the edited frame's key
/// group. The output is written atomically; `input` must be whole. Errors name the file, and
/// an edited mesh that is not the frame at that level is refused (kInvalidArgument).
StatusOr<DetailEditSummary> EditDetail(const std::string& input, const std::string& output,
                                       const DetailEditOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_DETAIL_EDIT_H_
