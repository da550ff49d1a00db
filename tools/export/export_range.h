// What an export covers: a level and a run of frames of a .mvid, split by key group.
#ifndef MESHVID_TOOLS_EXPORT_EXPORT_RANGE_H_
#define MESHVID_TOOLS_EXPORT_EXPORT_RANGE_H_

#include <cstdint>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "format/status.h"

namespace meshvid {

/// The frames and level an export writes.
struct ExportOptions {
  int level = -1;                ///< resolution level (-1: the finest stored)
  std::uint32_t first_frame = 0;
  std::uint32_t end_frame = 0;   ///< one past the last frame (0: to the end)
};

/// The frames [first, end) of one key group that an export covers.
struct KeyGroupRun {
  std::uint32_t key_group = 0;
  std::uint32_t first = 0;
  std::uint32_t end = 0;
};

/// Resolves `options` against `info` (level -1 to the finest, end 0 to the frame count) and
/// checks the level and frames exist.
StatusOr<ExportOptions> ResolveExportOptions(const MvidInfo& info, const ExportOptions& options);

/// The key-group runs of the resolved frames, in frame order.
StatusOr<std::vector<KeyGroupRun>> KeyGroupRuns(MvidDecoder& decoder,
                                                const ExportOptions& resolved);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EXPORT_EXPORT_RANGE_H_
