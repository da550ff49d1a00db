// The encoder's settings: EncoderOptions, the few a user chooses, and EncoderTuning, the
// internals. Included by every stage of the encoder (it includes no other encoder header).
#ifndef MESHVID_CODEC_ENC_OPTIONS_H_
#define MESHVID_CODEC_ENC_OPTIONS_H_

#include <cstddef>
#include <optional>
#include <string>

#include "codec/common/mesh.h"
#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// The encoder's internals: every default was chosen by measurement (bench/ENCODE.md,
/// bench/RESULTS.md); change them to experiment, not to use the codec. Lengths are in scene
/// units; 0 means "derived from the data's size" (a fraction of frame 0's bounding-box
/// diagonal, given beside each).
struct EncoderTuning {
  // --- base mesh
  /// Points the first fusion of a key frame's views keeps (thinned on a grid; fewer: faster,
  /// a coarser voxel). A base that explains less than 75% of its own frame's points is fused
  /// again from up to SurfaceFusionOptions::max_points (150,000) and the better kept.
  std::size_t base_fusion_points = 40000;
  /// Voxel of a key frame's fusion, as a multiple of the size the fusion derives from the data
  /// (SurfaceFusionOptions::voxel_scale). Decimating the fused surface is most of a key
  /// frame's cost; a coarser one decimates faster but gives a coarser base. Measured at 2
  /// (60 frames, HEVC q40): samba 3-arc encodes at 1.46 frames/s instead of 0.72 (D1 39.01
  /// against 38.76 dB), but samba 6-ring's accuracy falls from 0.64 to 0.93 mm (3/60 frames
  /// within 1.25x of the baseline's, from 59/60); so 1 by default.
  double base_voxel_scale = 1.0;
  /// After a key group of one frame (the subject moving fast), the next two frames' proxies
  /// and bases are made on threads of their own while this key group is analysed
  /// (key_frame_ahead.h; bench/ENCODE.md: 9-26% faster on 2 cores where most key groups hold
  /// a frame). The file is the same either way; false makes every base in turn.
  bool base_ahead = true;
  /// A key frame's fused surface ends at most this many of the views' sample spacings past
  /// the edge of the data (SurfaceFusionOptions::max_extension_spacings; 0: where the coarse
  /// fusion's volume ends it).
  double base_max_extension = 1.5;
  /// Use the views' cameras where the capture has them (FrameSource::view_cameras): a key
  /// frame's fused surface ends where a camera saw through it (SurfaceFusionOptions::
  /// view_cameras; a sheet's open edge, which the trim above leaves too long), and a key group
  /// ends where its tracked surface lies in space a camera saw through (DataFit::
  /// seen_through_share).
  bool seen_free_space = true;
  /// Decimation bounds that keep the displacement mapping one-to-one (0: 1% of the diagonal).
  double base_max_error = 0;
  double base_max_normal_deviation_degrees = 30;
  /// Longest edge the base decimation leaves (0: 3% of the diagonal, under the nodes'
  /// spacing). Quadrics alone collapse a straight tube into slivers along its whole length:
  /// they lie on the straight tube but cannot bend with it (a 60-frame swing of a bending
  /// cylinder made 13 key groups unbounded, one at 3%; 4% left 1.5% of its points
  /// unexplained at 60 degrees).
  double base_max_edge = 0;
  /// Draco position quantisation of the base meshes, bits per coordinate of the bounding box
  /// (the displacements correct what it moves along the normals). Samba, 3 views, 30 frames:
  /// 12 bits code each base in 39% fewer bytes than 16 for 0.01 mm more RMS error. 10 bits
  /// (bench/ENCODE.md, seven pairs at 60 frames, HEVC q40): bases 21-25% and files 7-9%
  /// smaller than at 12, the same key groups, D1 within 0.01 dB; 9 and 8 bits gain nothing.
  int base_position_bits = 10;
  /// Quantisation step of the transform tracks' translations (0: kTransformStepFraction of
  /// the size). The rotation step is the translation step over the reach (the first frame's
  /// farthest bounding-box corner from the origin, plus the size): a rotation step moves no
  /// point within the reach by more than a translation step. The encoder measures the
  /// displacements from the quantised tracks, so the steps trade transform bytes against
  /// the displacement video's. Measured (60 frames, HEVC q40; bench/TRANSFORMS.md),
  /// 1/8192 and the byte planes take 0.6-8.9% off the file, D1 within 0.002 dB; 1/2048
  /// 2% more, with the video growing and the accuracy giving 0.002 mm.
  double transform_step = 0;

  // --- correspondence (docs/encoder-method.md eq. 4)
  double proxy_fraction = 0.05;   ///< share of each view's triangles kept in its proxy
  /// Longest edge a proxy's decimation leaves (0: 4% of the diagonal): its vertices are the
  /// key-group fit's data points, and a straight stretch decimated without bound keeps points
  /// only at its ends (its middle then looks like surface thrown far from the data).
  double proxy_max_edge = 0;
  double max_distance = 0;        ///< farthest correspondence along a normal (0: 8%)
  double max_angle_degrees = 60;  ///< largest angle between base normal and data normal

  // --- tracking (deformation_tracking.h; docs/encoder-method.md section 3)
  double tolerance = 0;  ///< the tracker's finest correspondence radius is 2x this (0: 0.5%)
  /// With deform_reacquire, a part with fewer of its nodes' vertices finding data (within
  /// the finest radius) after the solve is searched for again; a new pose must reach this
  /// share too.
  double reacquire_below = 0.5;
  /// A re-acquired pose is kept when this share more of the part's vertices find data.
  double reacquire_gain = 0.2;
  int reacquire_min_vertices = 12;  ///< smaller parts are not searched for alone
  /// Widest closest-point radius a lost part is searched for within (0: 25%).
  double reacquire_max_distance = 0;
  // A key group's base is tracked as an embedded deformation: nodes over the base surface,
  // every vertex blended over its nearest nodes, solved frame by frame to the data with
  // neighbouring nodes held together; the file stores the nodes (MOTN version 3). It keeps
  // key groups longer at the same D1 than the piecewise-rigid segmentation it replaced on
  // every shared pair (bench/KEYGROUPS.md).
  /// Distance between the deformation's nodes along the base surface (0: 4% of the size,
  /// about 220 nodes on samba's 2,500-vertex base). Measured on samba 6-ring (60 frames,
  /// key groups ended by the former share rule at 0.005): 2.6% made 20 key groups but 53/60
  /// frames within 1.25x of the baseline's accuracy, 4% 29 and 57/60, 5.2% 30 and 55/60.
  double node_spacing = 0;
  /// Weight of neighbouring nodes agreeing on each other's positions, against the data
  /// (DeformationTrackingOptions::rigidity). Measured on samba 6-ring as above: 0.03 made 21
  /// key groups and 49/60 frames within 1.25x, 0.1 29 and 57/60, 0.3 33 and 57/60; on a tube
  /// bending 10 degrees a frame, 1 left 24% of the data beyond the tolerance at 60 degrees.
  double deform_rigidity = 0.1;
  /// On a key group's second frame (no velocity to predict from), the rigidity's multiplier at
  /// the coarsest correspondence radius, falling geometrically to 1 at the finest
  /// (DeformationTrackingOptions::coarse_stiffness): a part that moved far first moves as a
  /// whole, then bends. Measured (60 frames, HEVC q40; bench/DEFORM.md): arm-block 6-ring 26
  /// key groups at 1, 22 at 30, 20-21 at 100, 21 at 300, samba 6-ring 19 at 1, 20-21 at 100
  /// (D1 within 0.05 dB), cloth 6-ring 18 at 1, 23 at 100 (+0.12 dB); applied on every frame,
  /// not just the second, cloth 6-ring took 29. Above 1 the second frame is also solved at 1
  /// throughout, and the solution whose next frame is explained better is kept: cloth 6-ring
  /// 17 key groups, cloth 3-arc 17 (27 stiff alone), the other pairs within one of stiff alone.
  double deform_coarse_stiffness = 100;
  /// Weight of the point-to-point distance beside the point-to-plane one. Measured (60 frames,
  /// HEVC q40; bench/DEFORM.md): 0.03 and 0.3 each lose on one of samba 6-ring and cloth 3-arc
  /// (D1, accuracy or key groups), and move the key groups by at most 2 of 16-20.
  double deform_point_weight = 0.1;
  /// Neighbouring nodes are joined into rigid groups while one
  /// rigid transform per frame stays within this many tolerances of each node's own (RMS over
  /// the vertices it moves, in every frame of the key group), and carry the group's transform
  /// (rigid_node_groups.h; 0: each node keeps its own). Measured (60 frames, HEVC q40;
  /// bench/DEFORM.md): at 1 scene:arm-block's block, upper arm, forearm and hand are each
  /// 96-100% in one group (16 frames, 3-view arc) and arm-block 6-ring gains 0.08 dB for 7%
  /// fewer bytes, but samba 6-ring's accuracy is above 1.25x on 8 of 60 frames; at 0.5, over
  /// every shared pair, D1 holds or rises, bytes fall by up to 16%, and one frame in 456 is
  /// above 1.25x (1.26x), while arm-block's pieces are 18-98% in one group.
  double deform_rigid_group_factor = 0.5;
  int deform_iterations = 3;  ///< Gauss-Newton steps per correspondence radius
  /// Steps per radius on a key group's second frame, which has no velocity to predict from
  /// (its start is the key frame's pose): arm-block's parts move up to 5.1 cm a frame, and 3
  /// steps leave 4.5% of its first tracked frame's points beyond the displacement range, 10
  /// leave 0.03%; over 60 frames of arm-block 6-ring, 29 key groups instead of 35
  /// (bench/DEFORM.md).
  int deform_first_iterations = 10;
  /// Track each frame to its views fused into a closed surface (as a key frame's base is
  /// fused) rather than to its views' proxy: where no view sees the subject, the surface is
  /// pulled where per-frame fusion would close it. Measured (60 frames, HEVC q40, key-group
  /// threshold 0.005), fused against proxy: samba 6-ring D1 56.38 against 56.21 dB (28 and
  /// 29 key groups), arm-block 6-ring 52.61 against 52.51 dB (35 and 31).
  bool deform_track_fused = true;
  /// A part the solve leaves without data near it is searched for
  /// again over the whole frame as one rigid body (DeformationTrackingOptions::
  /// reacquire_max_distance, with reacquire_below, reacquire_gain, reacquire_min_vertices and
  /// reacquire_max_distance above). Measured (60 frames, horse-gallop 48, HEVC q40;
  /// bench/DEFORM.md): horse-gallop 41 key groups instead of 42 (3-arc) and 32 instead of 34
  /// (6-ring) at equal D1, arm-block 6-ring 22 instead of 21 (-0.03 dB), the other pairs the
  /// same key groups within 0.02 dB; but 7 of 456 frames, all in key groups where a part was
  /// found again, 1.5-2.4x as far from the truth (accuracy RMS). Off by default: fidelity
  /// first.
  bool deform_reacquire = false;
  /// Where a key group may be cut: its key frame is this many
  /// frames after its first frame (or the capture's last), and the frames between are tracked
  /// backwards from it, so a key group extends both ways from its key frame. Where a frame
  /// between is lost, the key frame is the first frame after all (its later base was made in
  /// vain). 0: every key group starts at its key frame. Measured in bench/DEFORM.md.
  int deform_backward_frames = 0;

  // --- detail (docs/encoder-method.md section 4)
  /// Farthest hit along a sample normal, and the displacement range a key group must keep its
  /// frame's data within (0: 0.5% of the diagonal; 2% with max_key_groups 1, where one base
  /// must absorb every tracking error). Measured over 60 frames of samba on the 3-view arc:
  /// 0.5% decodes at 0.71 mm RMS accuracy, 1% at 1.35 mm, 2% at 3.47 mm (its far hits at the
  /// surface's open edges land on the wrong side), for 1.9x and 1.4x the bytes.
  double detail_max_distance = 0;
  double outlier_distance = 0;     ///< hits this far from the views' median are dropped (0: 0.5%)

  // --- analysis window
  /// Most displacement frames measured and filled together (before and after in time);
  /// rounded to whole groups of frames (gof_size).
  int window = 256;

  // --- key groups
  /// How much farther from every data point than at the key frame any part of the tracked
  /// surface may lie before a new key group starts: a piece the motion threw where no view
  /// contradicts it, however small its share (0: max_distance).
  double farthest_growth = 0;
};

/// The default of EncoderOptions::rebase_gain_db (bench/KEYGROUPS.md).
inline constexpr double kDefaultRebaseGainDb = 2.0;

/// Every setting of the encoder: the few a user chooses, and the internals in `tuning`.
struct EncoderOptions {
  // --- base mesh
  /// A user base mesh (an animator's control model), rigidly fitted to frame 0. Empty: fuse
  /// frame 0's views and decimate.
  std::optional<TriangleMesh> base_mesh;
  std::size_t base_vertices = 2000;  ///< automatic base: target vertex count after decimation
  // --- detail
  /// Subdivision levels of the displacement lattice. Measured on samba: level 3 costs 8x the
  /// bytes of level 2 at quality 40 and gains no accuracy while the motion errs by centimetres.
  int levels = 2;
  /// Leave out of the decoded surface the base triangles no view saw in any frame (the
  /// method's unfilled pixels). Off by default: the whole base surface is decoded, its
  /// unseen parts carried by the motion and filled detail, as per-frame fusion closes holes.
  bool hide_unseen = false;

  // --- coding
  VideoCodec codec = VideoCodec::kHevc;
  int quality = 40;              ///< 0 (smallest) .. 100 (lossless for FFV1, finest QP otherwise)
  int effort = 4;                ///< video encoder effort 0..9
  int gof_size = 32;             ///< frames per group (random-access unit)
  // --- key groups (a fresh base where it is worth its bytes)
  /// The D1 (dB) a fresh base must be estimated to gain over the tracked one at a frame for a
  /// new key group to start there, at quality 40; it doubles every 20 quality steps below and
  /// halves every 20 above (RebaseGainDb), as a video encoder's lambda follows its quantiser.
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

/// The gain a fresh base must bring at `quality` (EncoderOptions::rebase_gain_db at 40).
double RebaseGainDb(const EncoderOptions& options);

/// The video quantiser `quality` maps to for `codec` (HEVC QP 0..51, AV1 CRF 0..63).
int QualityToQp(VideoCodec codec, int quality);

/// Checks every setting of `options`: kInvalidArgument naming the first one out of range.
Status CheckOptions(const EncoderOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_OPTIONS_H_
