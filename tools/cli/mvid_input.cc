#include "tools/cli/mvid_input.h"

#include <cstdint>
#include <cstdio>

#include "format/container_reader.h"

namespace meshvid::cli {

void AddAllowPartialFlag(CLI::App* cmd, bool* allow_partial) {
  cmd->add_flag("--allow-partial", *allow_partial,
                "Read a cut or damaged .mvid's readable frames (with a warning) instead of\n"
                "failing on it");
}

void WarnIfPartial(const std::string& path, const MvidInfo& info) {
  if (info.partial()) {
    std::fprintf(stderr, "meshvid: warning: %s: %s; reading frames 0..%u\n", path.c_str(),
                 PartialFileText(info).c_str(), info.frame_count == 0 ? 0 : info.frame_count - 1);
  } else if (info.declared_frame_count > 0 && info.frame_count > info.declared_frame_count) {
    std::fprintf(stderr,
                 "meshvid: warning: %s: its groups hold %u frames, its header promises %u (the "
                 "file is damaged)\n",
                 path.c_str(), info.frame_count, info.declared_frame_count);
  }
}

void WarnIfPartial(const std::string& spec) {
  if (!spec.ends_with(".mvid")) return;
  StatusOr<ContainerReader> reader = ContainerReader::OpenFile(spec);
  if (!reader.ok()) return;  // the command's own opening reports it
  MvidInfo counts;
  counts.frame_count = static_cast<std::uint32_t>(reader->frame_count());
  counts.declared_frame_count = reader->header().frame_count;
  WarnIfPartial(spec, counts);
}

}  // namespace meshvid::cli
