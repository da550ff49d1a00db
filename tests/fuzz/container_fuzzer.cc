// Fuzz target: the .mvid container layer on a whole file: ValidateContainer, the random-access
// reader (index or forward scan, every chunk it offers), and the progressive stream reader.
// Invariants: clean errors; a valid report implies the reader used the index and can read
// every group; the reader's groups are contiguous from frame 0.
#include <sstream>
#include <string>

#include "format/container_reader.h"
#include "format/stream_reader.h"
#include "format/validate.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  const ValidationReport report = ValidateContainer(bytes, "fuzz.mvid");
  for (const std::string& error : report.errors) {
    if (error.empty()) fuzz::Fail("an empty validation error");
  }
  StatusOr<ContainerReader> reader =
      ContainerReader::OpenMemory(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), "fuzz");
  if (report.ok() && !reader.ok()) fuzz::Fail("a valid file does not open");
  if (!reader.ok()) {
    fuzz::ExpectCleanError(reader.status());
  } else {
    if (report.ok() && !reader->used_index()) fuzz::Fail("a valid file's index is not used");
    std::uint64_t next = 0;
    for (const IndexEntry& entry : reader->gofs()) {
      if (entry.first_frame != next || entry.frame_count == 0) fuzz::Fail("GOFs not contiguous");
      next += entry.frame_count;
    }
    if (next > kMaxFrameEnd) fuzz::Fail("frame count past the last frame number");
    for (std::size_t k = 0; k < reader->key_groups().size(); ++k) {
      fuzz::ExpectCleanError(reader->ReadBase(k).status());
      fuzz::ExpectCleanError(reader->ReadMotion(k).status());
    }
    for (std::size_t g = 0; g < reader->gof_count(); ++g) {
      const Status status = reader->ReadGof(g).status();
      if (report.ok() && !status.ok()) fuzz::Fail("a valid file's group does not read");
      fuzz::ExpectCleanError(status);
    }
    (void)reader->FindGof(0);
    (void)reader->FindGof(next);
  }
  // The same bytes as a stream, front to back.
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  StreamReader stream(in, "fuzz-stream");
  StatusOr<ContainerHeader> header = stream.ReadHeader();
  fuzz::ExpectCleanError(header.status());
  if (header.ok()) {
    for (int items = 0; items < 100000; ++items) {
      StatusOr<StreamItem> item = stream.Next();
      if (!item.ok()) {
        fuzz::ExpectCleanError(item.status());
        break;
      }
      if (item->kind == StreamItem::Kind::kEnd) break;
    }
  }
  return 0;
}
