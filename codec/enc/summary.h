// What an encode produced: per key group and in total, for the summary a tool prints.
// Included by the stages that fill it (it includes no other encoder header).
#ifndef MESHVID_CODEC_ENC_SUMMARY_H_
#define MESHVID_CODEC_ENC_SUMMARY_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshvid {

/// Bytes written per stream so far.
struct MvidWriteStats {
  std::uint64_t base_bytes = 0;       ///< BASE, summed over key groups
  std::uint64_t motion_bytes = 0;     ///< MOTN: segments and blend weights, summed
  std::uint64_t transform_bytes = 0;  ///< group side information: transforms and ranges
  std::uint64_t video_bytes = 0;      ///< displacement video packets
  std::uint64_t colour_bytes = 0;     ///< colour video packets (0 without colour)
  std::uint64_t total_bytes = 0;      ///< everything, container overhead included
  std::uint32_t frames = 0;
};

/// A frame a key group kept although its tracked base no longer explained it (a fresh base
/// would have been due), because max_key_groups allowed no new key group.
struct HeldFrame {
  int frame = 0;                  ///< the capture's frame number
  double loss_db = 0;             ///< estimated D1 a fresh base would have gained (dB)
  double unexplained_share = 0;   ///< share of its points beyond the displacements' reach
  double seen_through_share = 0;  ///< share of the tracked surface a camera saw through
};

/// One key group of an encode.
struct KeyGroupSummary {
  int first_frame = 0;          ///< the capture's frame number of its first frame
  /// The capture's frame number of its key frame (whose fused views its base is): the first
  /// frame, or a later one tracked backwards to it (EncoderTuning::deform_backward_frames).
  int key_frame = 0;
  int frames = 0;
  std::size_t base_vertices = 0;
  int segments = 0;  ///< the deformation's nodes (the file's motion segments)
  /// The groups of nodes moving together as one rigid body (EncoderTuning::
  /// deform_rigid_group_factor; the nodes when they are not joined).
  int rigid_groups = 0;
  /// Lost parts found again over the frames the key group kept (EncoderTuning::
  /// deform_reacquire).
  int reacquired_parts = 0;
  double surface_share = 0;     ///< base triangles seen by some view
  double key_frame_unexplained = 0;  ///< share of the key frame's points the base cannot reach
  /// Share of the key frame's base surface in front of what a camera saw (as cut_seen_through).
  double key_frame_seen_through = 0;
  double worst_unexplained = 0;      ///< the same, at the worst frame kept in the key group
  /// The largest estimated D1 loss (dB) of a frame kept against a fresh base's
  /// (TrackingLossDb): what the key group saved bases for.
  double worst_loss_db = 0;
  /// At the frame that ended the key group (the next key frame), the estimated D1 a fresh base
  /// gains there (dB; TrackingLossDb with the surface it would lose), or where that stayed
  /// within the gain, the loss at the data alone, which the lost surface may offset only so
  /// far (rebase_forgotten_excuse_db); -1 when the capture (or max_key_groups) ended it.
  double cut_loss_db = -1;
  /// At that frame, the share of its points beyond the displacements' reach, or -1 as above.
  double cut_unexplained = -1;
  /// At that frame, the share of the tracked surface lying where a camera saw through
  /// (DataFit::seen_through_share), or -1 as above.
  double cut_seen_through = -1;
  /// At that frame, how much farther the tracked surface's farthest part lies from every data
  /// point than at the key frame (DataFit::farthest_from_data; data units; the rule of
  /// EncoderTuning::farthest_growth), or -1 as above.
  double cut_farthest_growth = -1;
  /// Frames kept that the tracked base does not explain, in frame order: only in the last
  /// key group max_key_groups allows (embedded deformation tracking), where the data needs
  /// more key groups than the limit gives.
  std::vector<HeldFrame> held_frames;
};

/// What an encode produced, for the summary a tool prints.
struct EncodeSummary {
  int frames = 0;
  int views = 0;
  /// Views whose calibrated camera (intrinsics and pose) the encoder used to find space they
  /// saw through (EncoderTuning::seen_free_space; 0: none).
  int free_space_views = 0;
  std::vector<KeyGroupSummary> key_groups;
  // Key group 0's base and lattice; node figures are means over the key groups.
  std::size_t base_vertices = 0;
  std::size_t samples_per_frame = 0;  ///< displacement samples at the finest level
  int segments = 0;                   ///< the deformation's nodes
  int rigid_groups = 0;               ///< rigid groups the nodes were joined into
  double surface_share = 0;     ///< base triangles seen by some view (the rest are hidden)
  double filled_share = 0;      ///< displacement samples filled by interpolation
  double hit_share = 0;         ///< samples with a fused measurement
  double frame_rate = 25.0;
  MvidWriteStats stats;
  double scale = 0;             ///< frame 0's bounding-box diagonal
  double tolerance = 0;         ///< tolerances actually used (scene units)
  double seconds_base = 0, seconds_tracking = 0, seconds_detail = 0, seconds_coding = 0;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_SUMMARY_H_
