// A key group's motion as an embedded deformation of its base (internal to the encoder,
// key_group_analysis.cc): the deformation's nodes tracked frame by frame from the key frame,
// backwards to the key group's first frame and forwards while the posed base explains each
// frame's data.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_DEFORMED_KEY_GROUP_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_DEFORMED_KEY_GROUP_H_

#include "codec/enc/key_groups/key_group_analysis.h"
#include "codec/enc/key_groups/tracking_targets.h"
#include "codec/enc/tracking/base_topology.h"
#include "format/status.h"

namespace meshvid {

/// The motion of a key group as an embedded deformation of its base, fused from its key
/// frame `key`: its nodes tracked frame by frame
/// backwards from the key frame to the key group's first frame `first` (tuning.
/// deform_backward_frames), then forwards while the posed base explains each frame's data (to
/// the end of the capture unless `may_cut`). Fills the analysis' motion, tracks (from `first`
/// on), frame count and node figures. The frame count is 0 when a frame between `first` and
/// the key frame is not explained: the key frame cannot start at `first`. The frames' targets come
/// from `targets` (those behind a forward run are dropped; a backward run keeps its frames for a
/// first-frame key group that may follow), each frame's successor made ahead while it is tracked.
/// Where `hint` is at the key frame, the frame after it is also solved from the hint's steps (each
/// node taking the step of the hint's position nearest it) and that start is weighed with the
/// others; where a frame after the key frame ends the key group, the analysis' hint says how the
/// surface moved into it.
Status TrackDeformedKeyGroup(const EncodeContext& ctx, const BaseTopology& topology, int first,
                             int key, bool may_cut, const MotionHint& hint,
                             TrackingTargets* targets, KeyGroupAnalysis* analysis);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_DEFORMED_KEY_GROUP_H_
