#include "format/container_copy.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace meshvid {

Status CheckWholeContainer(const ContainerReader& reader, const std::string& name) {
  if (!reader.used_index()) {
    return CorruptError(name + ": truncated or damaged (" + reader.index_status().message() +
                        "); `meshvid info --check` says more");
  }
  const std::uint32_t declared = reader.header().frame_count;
  if (declared != 0 && reader.frame_count() != declared) {
    return CorruptError(name + ": its groups hold " + std::to_string(reader.frame_count()) +
                        " frames, its header promises " + std::to_string(declared));
  }
  if (reader.gof_count() == 0) return CorruptError(name + ": holds no frame");
  return Status::Ok();
}

Status CheckJoinable(const ContainerHeader& first, const ContainerHeader& next,
                     const std::string& next_name) {
  auto differs = [&](const std::string& what, const std::string& a, const std::string& b) {
    return InvalidArgumentError(next_name + ": " + what + " " + b + " where the first file has " +
                                a + "; files join only when they were encoded alike");
  };
  // Rates compared as fractions: 25/1 and 25025/1001 are the same rate.
  if (std::uint64_t{first.frame_rate_numerator} * next.frame_rate_denominator !=
      std::uint64_t{next.frame_rate_numerator} * first.frame_rate_denominator) {
    return differs("frame rate",
                   std::to_string(first.frame_rate_numerator) + "/" +
                       std::to_string(first.frame_rate_denominator),
                   std::to_string(next.frame_rate_numerator) + "/" +
                       std::to_string(next.frame_rate_denominator));
  }
  if (first.level_count != next.level_count) {
    return differs("level count", std::to_string(first.level_count),
                   std::to_string(next.level_count));
  }
  if (first.gof_size != next.gof_size) {
    return differs("group size", std::to_string(first.gof_size), std::to_string(next.gof_size));
  }
  if (first.streams.size() != next.streams.size()) {
    return differs("stream count", std::to_string(first.streams.size()),
                   std::to_string(next.streams.size()));
  }
  for (std::size_t s = 0; s < first.streams.size(); ++s) {
    const StreamInfo& a = first.streams[s];
    const StreamInfo& b = next.streams[s];
    if (a.codec != b.codec || a.bit_depth != b.bit_depth || a.name != b.name) {
      return differs("stream " + std::to_string(s),
                     a.name + " " + a.codec + " " + std::to_string(a.bit_depth) + "-bit",
                     b.name + " " + b.codec + " " + std::to_string(b.bit_depth) + "-bit");
    }
  }
  return Status::Ok();
}

Status CopyGofs(ContainerReader& in, std::size_t first_gof, std::size_t end_gof,
                ContainerWriter& out, const GofRewrite& rewrite) {
  if (first_gof >= end_gof || end_gof > in.gof_count()) {
    return InvalidArgumentError("groups " + std::to_string(first_gof) + ".." +
                                std::to_string(end_gof) + " are not a range of the file's " +
                                std::to_string(in.gof_count()));
  }
  const ContainerIndex& held = out.index();
  auto next_frame = [&]() -> std::uint32_t {
    if (held.gofs.empty()) return 0;
    return held.gofs.back().first_frame + held.gofs.back().frame_count;
  };
  std::size_t key_group = in.key_groups().size();  // none copied yet
  for (std::size_t g = first_gof; g < end_gof; ++g) {
    const std::size_t k = in.KeyGroupOfGof(g);
    if (k != key_group) {
      key_group = k;
      const KeyGroupEntry& entry = in.key_groups()[k];
      if (entry.base_offset == 0 && entry.motion_offset == 0 && !held.gofs.empty()) {
        return InvalidArgumentError(
            "key group " + std::to_string(k) +
            " has no BASE or MOTN chunk, so it cannot start a key group after other groups");
      }
      if (entry.base_offset != 0) {
        MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> base, in.ReadBase(k));
        MESHVID_RETURN_IF_ERROR(out.WriteBase(base));
      }
      if (entry.motion_offset != 0) {
        MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> motion, in.ReadMotion(k));
        MESHVID_RETURN_IF_ERROR(out.WriteMotion(motion));
      }
    }
    MESHVID_ASSIGN_OR_RETURN(GroupOfFrames gof, in.ReadGof(g));
    if (rewrite) {
      const std::uint32_t frame_count = gof.frame_count;
      MESHVID_RETURN_IF_ERROR(rewrite(g, &gof));
      if (gof.frame_count != frame_count) {
        return InvalidArgumentError("group " + std::to_string(g) +
                                    ": a rewrite may not change its frame count");
      }
    }
    gof.gof_index = static_cast<std::uint32_t>(held.gofs.size());
    gof.first_frame = next_frame();
    MESHVID_RETURN_IF_ERROR(out.WriteGof(gof));
  }
  return Status::Ok();
}

}  // namespace meshvid
