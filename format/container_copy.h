// Copying groups of frames from one .mvid container into another without decoding them: the
// key groups' BASE and MOTN chunks byte for byte, the GOFs with their packets and transforms
// untouched and only their numbering (gof_index, first_frame) rewritten to follow what the
// output already holds. `meshvid concat` and `meshvid cut` are built on it
// (spec/mvid-container.md, "Joining and cutting files").
#ifndef MESHVID_FORMAT_CONTAINER_COPY_H_
#define MESHVID_FORMAT_CONTAINER_COPY_H_

#include <cstddef>
#include <functional>
#include <string>

#include "format/container_reader.h"
#include "format/container_writer.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// Ok when `reader` found every group its header promises through the file's index; otherwise
/// kCorrupt naming `name`: a truncated or damaged file, whose groups cannot all be copied.
Status CheckWholeContainer(const ContainerReader& reader, const std::string& name);

/// Ok when a file with header `next` can follow one with header `first` in one container: the
/// same frame rate, level count, nominal group size and streams (codec, bit depth and name;
/// the picture size may differ, as it does between key groups). Otherwise kInvalidArgument
/// naming `next_name` and what differs.
Status CheckJoinable(const ContainerHeader& first, const ContainerHeader& next,
                     const std::string& next_name);

/// Changes a GOF read from the input (given its index there) before it is written: its
/// packets and transforms, never its frames. CopyGofs renumbers it afterwards.
using GofRewrite = std::function<Status(std::size_t input_gof, GroupOfFrames* gof)>;

/// Appends GOFs [first_gof, end_gof) of `in` to `out` (which must have begun): before the
/// first GOF copied from each key group, that key group's BASE and MOTN, so every key group of
/// the output starts with the chunks it needs. The GOFs are renumbered to follow the GOFs and
/// frames `out` holds; `rewrite`, when given, changes each GOF's content first (`meshvid
/// transcode` codes its video again). kInvalidArgument when the range is empty or out of
/// bounds, or when a key group would have to start without a BASE or MOTN chunk after `out`'s
/// GOFs (a version-1 file without either); a rewrite's error stops the copy.
Status CopyGofs(ContainerReader& in, std::size_t first_gof, std::size_t end_gof,
                ContainerWriter& out, const GofRewrite& rewrite = {});

}  // namespace meshvid

#endif  // MESHVID_FORMAT_CONTAINER_COPY_H_
