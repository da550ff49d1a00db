#include "codec/enc/options.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "codec/common/subdivision.h"

namespace meshvid {

double RebaseGainDb(const EncoderOptions& options) {
  return options.rebase_gain_db * std::exp2((40.0 - options.quality) / 20.0);
}

int QualityToQp(VideoCodec codec, int quality) {
  const double fraction = 1.0 - std::clamp(quality, 0, 100) / 100.0;
  switch (codec) {
    case VideoCodec::kAv1: return static_cast<int>(std::lround(63 * fraction));
    case VideoCodec::kFfv1: return 0;
    case VideoCodec::kHevc:
    default: return static_cast<int>(std::lround(51 * fraction));
  }
}

Status CheckOptions(const EncoderOptions& o) {
  auto bad = [](const std::string& what) { return InvalidArgumentError(what); };
  if (o.levels < 0 || o.levels > RegularSubdivision::kMaxLevels) {
    return bad("levels must be in 0.." + std::to_string(RegularSubdivision::kMaxLevels));
  }
  if (o.quality < 0 || o.quality > 100) return bad("quality must be in 0..100");
  if (o.effort < 0 || o.effort > 9) return bad("effort must be in 0..9");
  if (o.gof_size < 1 || o.gof_size > 1024) return bad("gof_size must be in 1..1024");
  if (o.tuning.window < 2) return bad("tuning.window must be at least 2 frames");
  if (!(o.rebase_gain_db >= 0 && o.rebase_gain_db <= 100)) {
    return bad("rebase_gain_db must be in [0, 100] dB");
  }
  if (o.max_key_groups < 0) return bad("max_key_groups must be >= 0 (0: no limit)");
  if (o.tuning.deform_backward_frames < 0) {
    return bad("tuning.deform_backward_frames must be >= 0");
  }
  if (o.base_vertices < 4) return bad("base_vertices must be at least 4");
  if (!(o.tuning.base_max_extension >= 0) || !std::isfinite(o.tuning.base_max_extension)) {
    return bad("tuning.base_max_extension must be finite and >= 0");
  }
  if (!(o.tuning.transform_step >= 0) || !std::isfinite(o.tuning.transform_step)) {
    return bad("tuning.transform_step must be finite and >= 0 (0: from the size)");
  }
  if (!(o.tuning.base_voxel_scale >= 0.25 && o.tuning.base_voxel_scale <= 8)) {
    return bad("tuning.base_voxel_scale must be in [0.25, 8]");
  }
  if (o.tuning.base_fusion_points < 100) {
    return bad("tuning.base_fusion_points must be at least 100");
  }
  if (!(o.tuning.proxy_fraction > 0 && o.tuning.proxy_fraction <= 1)) {
    return bad("tuning.proxy_fraction must be in (0, 1]");
  }
  if (!(o.tuning.max_angle_degrees > 0 && o.tuning.max_angle_degrees < 90)) {
    return bad("tuning.max_angle_degrees must be in (0, 90) degrees");
  }
  if (o.tuning.base_position_bits < 8 || o.tuning.base_position_bits > 24) {
    return bad("tuning.base_position_bits must be in 8..24");
  }
  if (!(o.tuning.reacquire_below >= 0 && o.tuning.reacquire_below <= 1) ||
      !(o.tuning.reacquire_gain >= 0 && o.tuning.reacquire_gain <= 1)) {
    return bad("tuning.reacquire_below and tuning.reacquire_gain must be in [0, 1]");
  }
  if (!(o.tuning.base_max_edge >= 0) || !(o.tuning.proxy_max_edge >= 0)) {
    return bad("tuning.base_max_edge and tuning.proxy_max_edge must be >= 0");
  }
  if (!(o.tuning.node_spacing >= 0) || !(o.tuning.deform_rigidity > 0) ||
      !(o.tuning.deform_point_weight >= 0)) {
    return bad(
        "tuning.node_spacing and tuning.deform_point_weight must be >= 0 and "
        "tuning.deform_rigidity positive");
  }
  if (!(o.tuning.deform_rigid_group_factor >= 0)) {
    return bad("tuning.deform_rigid_group_factor must be >= 0");
  }
  if (!(o.tuning.deform_coarse_stiffness >= 1 && o.tuning.deform_coarse_stiffness <= 1000)) {
    return bad("tuning.deform_coarse_stiffness must be in [1, 1000]");
  }
  if (o.tuning.deform_iterations < 1 || o.tuning.deform_first_iterations < 1) {
    return bad("tuning.deform_iterations and tuning.deform_first_iterations must be at least 1");
  }
  if (o.tuning.reacquire_min_vertices < 3) {
    return bad("tuning.reacquire_min_vertices must be at least 3");
  }
  if (o.tuning.farthest_growth < 0) return bad("tuning.farthest_growth must not be negative");
  if (o.tuning.max_distance < 0 || o.tuning.tolerance < 0 || o.tuning.detail_max_distance < 0 ||
      o.tuning.outlier_distance < 0 || o.tuning.base_max_error < 0 ||
      o.tuning.reacquire_max_distance < 0) {
    return bad(
        "tuning.max_distance, tuning.tolerance, tuning.detail_max_distance, "
        "tuning.outlier_distance, tuning.base_max_error and tuning.reacquire_max_distance must "
        "not be negative (0 derives them from the data)");
  }
  return Status::Ok();
}

}  // namespace meshvid
