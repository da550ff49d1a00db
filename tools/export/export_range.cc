#include "tools/export/export_range.h"

#include <string>

namespace meshvid {

StatusOr<ExportOptions> ResolveExportOptions(const MvidInfo& info, const ExportOptions& options) {
  ExportOptions resolved = options;
  if (resolved.level < 0) resolved.level = info.levels;
  if (resolved.level > info.levels) {
    return InvalidArgumentError("the file stores levels 0.." + std::to_string(info.levels) +
                                ", not " + std::to_string(resolved.level));
  }
  if (resolved.end_frame == 0) resolved.end_frame = info.frame_count;
  if (resolved.first_frame >= resolved.end_frame || resolved.end_frame > info.frame_count) {
    return InvalidArgumentError("frames " + std::to_string(resolved.first_frame) + ":" +
                                std::to_string(resolved.end_frame) + " are not within the " +
                                std::to_string(info.frame_count) + " readable frames");
  }
  return resolved;
}

StatusOr<std::vector<KeyGroupRun>> KeyGroupRuns(MvidDecoder& decoder,
                                                const ExportOptions& resolved) {
  std::vector<KeyGroupRun> runs;
  for (std::uint32_t frame = resolved.first_frame; frame < resolved.end_frame; ++frame) {
    MESHVID_ASSIGN_OR_RETURN(const std::uint32_t key_group, decoder.KeyGroupOf(frame));
    if (runs.empty() || runs.back().key_group != key_group) {
      runs.push_back({key_group, frame, frame + 1});
    } else {
      runs.back().end = frame + 1;
    }
  }
  return runs;
}

}  // namespace meshvid
