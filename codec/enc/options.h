// The encoder's settings: EncoderOptions, the few a user chooses, and EncoderTuning, the
// internals. Included by every stage of the encoder (it includes no other encoder header).
#ifndef MESHVID_CODEC_ENC_OPTIONS_H_
#define MESHVID_CODEC_ENC_OPTIONS_H_

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "codec/common/mesh.h"
#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// No upper bound on a tuning knob.
inline constexpr double kNoLimit = 1e300;

/// Every internal of the encoder, declared once: MESHVID_ENCODER_TUNING(KNOB) calls
/// KNOB(type, name, default, lowest, highest, former flag, help) for each. EncoderTuning's
/// fields, CheckOptions' ranges, the `--tune` keys (`meshvid encode --tune help`) and the
/// table in docs/tuning.md are made from it. Lengths are in scene units; 0 derives a length
/// from frame 0's size (its bounding-box diagonal), as each help says. Every default was chosen
/// by measurement (bench/); change them to experiment, not to use the codec. The former flag
/// is the one `meshvid encode` took before `--tune`, named in the bench records.
#define MESHVID_ENCODER_TUNING(KNOB)                                                           \
  /* --- base mesh (docs/encoder-method.md section 1) */                                       \
  KNOB(std::size_t, base_fusion_points, 40000, 100, kNoLimit, "--base-fusion-points",          \
       "Points the first fusion of a key frame's views keeps, thinned on a grid (fewer: "      \
       "faster, a coarser voxel). A base that explains under 75% of its own frame's points "   \
       "is fused again from up to 150,000 and the better kept.")                               \
  KNOB(double, base_voxel_scale, 1.0, 0.25, 8, "--base-voxel-scale",                           \
       "Voxel of a key frame's fusion, as a multiple of the size the fusion derives from the " \
       "views: 2 is about twice as fast with a coarser, less accurate base "                   \
       "(bench/ENCODE.md).")                                                                   \
  KNOB(bool, base_ahead, true, 0, 1, "--base-ahead",                                           \
       "After a key group of one frame, make the next two frames' proxies and bases on "       \
       "threads of their own while the key group is analysed (key_frame_ahead.h). The file "   \
       "is the same either way.")                                                              \
  KNOB(double, base_max_extension, 1.5, 0, kNoLimit, "--base-extension",                       \
       "Farthest a key frame's fused surface reaches past the edge of the data, in the "       \
       "views' sample spacings (0: as far as the coarse fusion's volume reaches).")            \
  KNOB(bool, seen_free_space, true, 0, 1, "--free-space",                                      \
       "Use the capture's calibrated cameras where it has them: a key frame's base ends "      \
       "where a camera saw through it (a sheet's open edge), and a key group ends where its "  \
       "tracked surface lies in space a camera saw through.")                                  \
  KNOB(double, base_max_error, 0, 0, kNoLimit, "--base-max-error",                             \
       "Largest surface change a decimation step of the base may make, in scene units (0: 1% " \
       "of the size), so that displacements along the base's normals stay one-to-one with "    \
       "the data. Given at quality 30 and above, x4 every 15 quality steps below.")            \
  KNOB(double, base_max_normal_deviation_degrees, 30, 0, 180, "--base-max-normal-deviation",   \
       "Largest turn of a face normal a decimation step of the base may make, in degrees. "    \
       "Given at quality 30 and above, x4 every 15 quality steps below (at most 180).")        \
  KNOB(double, base_max_edge, 0, 0, kNoLimit, "--base-max-edge",                               \
       "Longest edge the base decimation leaves (0: 3% of the size, under the nodes' "         \
       "spacing): quadrics alone collapse a straight tube into slivers that cannot bend with " \
       "it. Given at quality 30 and above, x4 every 15 quality steps below.")                  \
  KNOB(int, base_position_bits, 10, 8, 24, "--base-bits",                                      \
       "Draco position quantisation of the base meshes, in bits per coordinate of the "        \
       "bounding box; the displacements correct what it moves along the normals "              \
       "(bench/ENCODE.md).")                                                                   \
  KNOB(double, transform_step, 0, 0, kNoLimit, "--transform-step",                             \
       "Quantisation step of the motion's translations (0: 1/8192 of the size); the rotation " \
       "step moves no vertex by more, rounded about the origin or, where a key group's track " \
       "codes smaller so, about each segment's centre (bench/TRANSFORMS.md). Given at "        \
       "quality 30 and above, doubled every 15 quality steps below.")                          \
  /* --- correspondence (docs/encoder-method.md section 2) */                                  \
  KNOB(double, proxy_fraction, 0.05, 0.001, 1, "--proxy-fraction",                             \
       "Share of each view's triangles kept in the frame's proxy, the data the tracker fits.") \
  KNOB(double, proxy_max_edge, 0, 0, kNoLimit, "--proxy-max-edge",                             \
       "Longest edge a proxy's decimation leaves (0: 4% of the size), so that a straight "     \
       "stretch keeps data points along its middle.")                                          \
  KNOB(double, max_distance, 0, 0, kNoLimit, "--max-distance",                                 \
       "Farthest correspondence along a normal (0: 8% of the size).")                          \
  KNOB(double, max_angle_degrees, 60, 1, 89, "--max-angle",                                    \
       "Largest angle between a base normal and the data's normal at a correspondence, in "    \
       "degrees.")                                                                             \
  /* --- tracking (docs/encoder-method.md section 3) */                                        \
  KNOB(double, tolerance, 0, 0, kNoLimit, "--tol",                                             \
       "The tracker's finest correspondence radius is twice this (0: 0.5% of the size).")      \
  KNOB(double, node_spacing, 0, 0, kNoLimit, "--node-spacing",                                 \
       "Distance between the deformation's nodes along the base surface (0: 4% of the "        \
       "size). Given at quality 30 and above; below, multiplied by 1.41 every 15 steps down.") \
  KNOB(double, deform_rigidity, 0.1, 1e-6, kNoLimit, "--rigidity",                             \
       "Weight of neighbouring nodes agreeing on each other's positions, against the data.")   \
  KNOB(double, deform_coarse_stiffness, 100, 1, 1000, "--coarse-stiffness",                    \
       "On a key group's second frame, the rigidity's multiplier at the coarsest radius, "     \
       "falling to 1 at the finest: a part that moved far first moves as a whole, then "       \
       "bends. Above 1 the frame is also solved at 1 and the start that explains the next "    \
       "frame better is kept (bench/DEFORM.md).")                                              \
  KNOB(double, deform_point_weight, 0.1, 0, kNoLimit, "--point-weight",                        \
       "Weight of the point-to-point distance beside the point-to-plane one.")                 \
  KNOB(double, deform_rigid_group_factor, 0.5, 0, kNoLimit, "--rigid-groups",                  \
       "Neighbouring nodes are joined into rigid groups while one rigid transform per frame "  \
       "stays within this many tolerances of each node's own, and carry the group's "          \
       "transform (rigid_node_groups.h; 0: each node keeps its own).")                         \
  KNOB(double, deform_join_pieces, 1.5, 0, 10, "",                                             \
       "Nodes on separate pieces of the base (a fusion leaves a hand apart from the block it " \
       "holds) are held to the nearest node of another piece within this many node "           \
       "spacings, so that a small piece moves with what it touches rather than onto "          \
       "whatever data lies near (0: pieces move apart; bench/DEFORM.md).")                     \
  KNOB(int, deform_iterations, 3, 1, 100, "--deform-iterations",                               \
       "Gauss-Newton steps per correspondence radius.")                                        \
  KNOB(int, deform_first_iterations, 10, 1, 100, "--deform-first-iterations",                  \
       "Gauss-Newton steps per radius on a key group's second frame, which has no velocity "   \
       "to predict from.")                                                                     \
  KNOB(bool, deform_track_fused, true, 0, 1, "--deform-fused",                                 \
       "Track each frame to its views fused into a closed surface (as a key frame's base is "  \
       "fused) rather than to its proxy: where no view sees the subject, the surface is "      \
       "pulled where per-frame fusion would close it.")                                        \
  KNOB(bool, deform_reacquire, false, 0, 1, "--deform-reacquire",                              \
       "Search again over the whole frame, as one rigid body, for a part the solve leaves "    \
       "without data near it. Off by default: a part found again can land farther from the "   \
       "truth (bench/DEFORM.md).")                                                             \
  KNOB(double, reacquire_below, 0.5, 0, 1, "--reacquire-below",                                \
       "With deform_reacquire, a part with fewer than this share of its vertices finding "     \
       "data after the solve is searched for again; a new pose must reach this share too.")    \
  KNOB(double, reacquire_gain, 0.2, 0, 1, "--reacquire-gain",                                  \
       "A re-acquired pose is kept when this share more of the part's vertices find data.")    \
  KNOB(int, reacquire_min_vertices, 12, 3, kNoLimit, "--reacquire-min-vertices",               \
       "Parts with fewer vertices are not searched for alone.")                                \
  KNOB(double, reacquire_max_distance, 0, 0, kNoLimit, "--reacquire-distance",                 \
       "Widest closest-point radius a lost part is searched for within (0: 25% of the size).") \
  KNOB(int, deform_backward_frames, 0, 0, 1000, "--deform-backward",                           \
       "A key group's key frame is this many frames after its first frame, and the frames "    \
       "between are tracked backwards from it (0: every key group starts at its key frame; "   \
       "docs/encoder-method.md section 3.2).")                                                 \
  /* --- key groups and detail (docs/encoder-method.md sections 3.1 and 4) */                  \
  KNOB(double, farthest_growth, 0, 0, kNoLimit, "--farthest-growth",                           \
       "A new key group starts where some part of the tracked surface lies farther from "      \
       "every data point than at the key frame by more than this, in scene units: a piece "    \
       "the motion threw where no view contradicts it (0: max_distance).")                     \
  KNOB(double, rebase_forgotten_reach, 4, 0, 100, "",                                          \
       "A fresh base holds only what its own frame's views see. Where a tracked frame's data " \
       "alone would end its key group, the surface the key group saw at earlier frames that "  \
       "lies beyond the displacement range of the frame's fused surface, where no camera saw " \
       "through it (captures with cameras only), counts against the fresh base at its "        \
       "distance from that surface, up to this many displacement ranges (0: the decision "     \
       "weighs the frame's data alone; bench/KEYGROUPS.md).")                                  \
  KNOB(double, rebase_forgotten_excuse_db, 4, 0, 100, "",                                      \
       "Most of a tracked frame's estimated loss at its data, in dB beyond the re-basing "     \
       "gain, that the surface a fresh base would lose may offset: a tracker gone astray "     \
       "also leaves surface away from the data, and past this the key group ends.")            \
  KNOB(double, detail_max_distance, 0, 0, kNoLimit, "--detail-distance",                       \
       "Farthest hit along a sample normal, and the displacement range a key group must keep " \
       "its frames' data within (0: 0.5% of the size; 2% with max_key_groups 1).")             \
  KNOB(double, outlier_distance, 0, 0, kNoLimit, "--outlier-distance",                         \
       "Hits this far from the views' median are dropped (0: 0.5% of the size).")              \
  KNOB(int, window, 256, 2, kNoLimit, "--window",                                              \
       "Most displacement frames measured and filled together (before and after in time), "    \
       "rounded to whole groups of frames (gof_size).")

/// The encoder's internals (MESHVID_ENCODER_TUNING): change them to experiment, not to use the
/// codec.
struct EncoderTuning {
#define MESHVID_DECLARE_KNOB(type, name, value, lowest, highest, flag, help) type name = value;
  MESHVID_ENCODER_TUNING(MESHVID_DECLARE_KNOB)
#undef MESHVID_DECLARE_KNOB
};

/// One internal of EncoderTuning, for tools that set or list them.
struct TuningKnob {
  const char* key;   ///< the field's name, the `--tune` key
  const char* type;  ///< "int", "double", "size" or "bool"
  double default_value;
  double lowest, highest;   ///< its range, both included (highest kNoLimit: none)
  const char* former_flag;  ///< the flag `meshvid encode` took before `--tune` ("": none)
  const char* help;
};

/// Every internal, in declaration order.
std::span<const TuningKnob> TuningKnobs();

/// Sets `tuning`'s knob `key` from `value` ("0.05", "12", "true"/"false"/"1"/"0").
/// kInvalidArgument naming the key when it is unknown, the value does not parse as the knob's
/// type or lies outside its range.
Status SetTuning(EncoderTuning& tuning, std::string_view key, std::string_view value);

/// The value of `tuning`'s knob `key` as SetTuning reads it (empty when the key is unknown).
std::string TuningValue(const EncoderTuning& tuning, std::string_view key);

/// A knob's range as the table shows it: "[0.25, 8]", ">= 0" or "true, false".
std::string TuningRangeText(const TuningKnob& knob);

/// The knobs as a Markdown table (key, default, range, former flag, what it does): the text of
/// docs/tuning.md after its heading.
std::string TuningTableMarkdown();

/// The default of EncoderOptions::rebase_gain_db (bench/KEYGROUPS.md).
inline constexpr double kDefaultRebaseGainDb = 2.0;

/// Every setting of the encoder: the few a user chooses, and the internals in `tuning`.
struct EncoderOptions {
  // --- base mesh
  /// A user base mesh (an animator's control model), rigidly fitted to frame 0. Empty: fuse
  /// frame 0's views and decimate.
  std::optional<TriangleMesh> base_mesh;
  /// Automatic base: target vertex count after decimation, at quality 30 and above; halved
  /// every 15 quality steps below (BaseCoarsening).
  std::size_t base_vertices = 2000;
  // --- detail
  /// Subdivision levels of the displacement lattice: the finest resolution a decoder can
  /// choose. A level finer than the data's detail costs bytes for no accuracy
  /// (bench/DESIGN-NOTES.md).
  int levels = 2;
  /// Leave out of the decoded surface the base triangles no view saw in any frame (the
  /// method's unfilled pixels). Off by default: the whole base surface is decoded, its
  /// unseen parts carried by the motion and filled detail, as per-frame fusion closes holes.
  bool hide_unseen = false;

  // --- coding
  /// AV1 by default: through the whole encoder at quality 40, 24-43% fewer bytes than HEVC on
  /// every shared pair with D1 within 0.2 dB, at up to 7% worse accuracy side by side
  /// (bench/CODECS.md); and the codec browsers decode in software (WebCodecs).
  VideoCodec codec = VideoCodec::kAv1;
  int quality = 40;              ///< 0 (smallest) .. 100 (lossless for FFV1, finest QP otherwise)
  /// Code the capture's colour (a colour stream) when every view of its first frame has
  /// vertex colours; false: geometry only.
  bool colour = true;
  /// Quality of the colour video, as `quality` (-1: the same as `quality`).
  int colour_quality = -1;
  int effort = 4;                ///< video encoder effort 0..9
  int gof_size = 32;             ///< frames per group (random-access unit)
  // --- key groups (a fresh base where it is worth its bytes)
  /// The D1 (dB) a fresh base must be estimated to gain over the tracked one at a frame for a
  /// new key group to start there, at quality 40; it doubles every 20 quality steps below and
  /// halves every 20 above up to 80 (RebaseGainDb), as a video encoder's lambda follows its
  /// quantiser.
  /// The gain is estimated from the frame's data (TrackingLossDb): what the tracked base's
  /// displacements cannot reach, and the surface it leaves where a camera saw through.
  double rebase_gain_db = kDefaultRebaseGainDb;
  /// Most key groups (0: no limit). 1 keeps one base and one connectivity for the whole
  /// capture, as the paper does (for editing).
  int max_key_groups = 0;
  int first_frame = 0;           ///< frames [first_frame, end_frame) are encoded
  int end_frame = -1;            ///< -1: to the end
  std::string metadata_json = "{}";
  /// The algorithm's internals (defaults measured; see EncoderTuning).
  EncoderTuning tuning;
};

/// The quality above which the gain a fresh base must bring stops falling.
inline constexpr int kFinestRebasingQuality = 80;

/// The gain a fresh base must bring at `quality` (EncoderOptions::rebase_gain_db at 40,
/// doubling every 20 steps below and halving every 20 above, up to kFinestRebasingQuality).
double RebaseGainDb(const EncoderOptions& options);

/// The quality below which the automatic base mesh and the motion coarsen (BaseCoarsening).
inline constexpr int kFinestBaseQuality = 30;

/// How much coarser than their settings the automatic base mesh (not a user's) and the
/// motion are made at `quality`: 1 at kFinestBaseQuality and above, doubling every 15 quality
/// steps below (4 at 0). The base's target vertex count is divided by it and the transforms' step
/// (tuning.transform_step) multiplied by it, the deformation's node spacing
/// (tuning.node_spacing) by its square root;
/// the base decimation's bounds (tuning.base_max_error, base_max_edge,
/// base_max_normal_deviation_degrees) are multiplied by its square, so that at low qualities
/// the target sets the base's size. From 30 up the video's quantiser is the cheaper lever;
/// below, it barely moves D1 and the base's resolution does (bench/QUALITY.md).
double BaseCoarsening(int quality);

/// The video quantiser `quality` maps to for `codec` (HEVC QP 0..51, AV1 CRF 0..63).
int QualityToQp(VideoCodec codec, int quality);

/// Checks every setting of `options`: kInvalidArgument naming the first one out of range.
Status CheckOptions(const EncoderOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_OPTIONS_H_
