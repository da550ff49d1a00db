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

void WarnIfPartial(const std::string& spec) {
  if (!spec.ends_with(".mvid")) return;
  StatusOr<ContainerReader> reader = ContainerReader::OpenFile(spec);
  if (!reader.ok()) return;  // the command's own opening reports it
  const std::uint64_t promised = reader->header().frame_count;
  const std::uint64_t readable = reader->frame_count();
  if (promised == 0 || readable == promised) return;
  if (readable < promised) {
    std::fprintf(stderr,
                 "meshvid: warning: %s: partial file: only %llu of the %llu frames its header "
                 "promises are readable; reading frames 0..%llu\n",
                 spec.c_str(), static_cast<unsigned long long>(readable),
                 static_cast<unsigned long long>(promised),
                 static_cast<unsigned long long>(readable == 0 ? 0 : readable - 1));
  } else {
    std::fprintf(stderr,
                 "meshvid: warning: %s: its groups hold %llu frames, its header promises %llu "
                 "(the file is damaged)\n",
                 spec.c_str(), static_cast<unsigned long long>(readable),
                 static_cast<unsigned long long>(promised));
  }
}

}  // namespace meshvid::cli
