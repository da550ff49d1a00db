// Fuzz target: Point Cache 2 files (.pc2, ground-truth animation) through Pc2Reader: the
// header checks, then the first and last samples. The reader takes a path: the input is
// written to a scratch file first.
// Invariants: clean errors; a sample read has num_points finite positions.
#include "tests/fuzz/fuzz_util.h"
#include "tools/io/pc2.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::WriteScratchFile("fuzz.pc2", {data, size});
  StatusOr<std::unique_ptr<Pc2Reader>> reader = Pc2Reader::Open(path);
  if (!reader.ok()) {
    fuzz::ExpectCleanError(reader.status());
    return 0;
  }
  const Pc2Header& header = (*reader)->header();
  for (const int index : {0, header.num_samples - 1, header.num_samples}) {
    StatusOr<std::vector<Eigen::Vector3f>> frame = (*reader)->ReadFrame(index);
    if (!frame.ok()) {
      fuzz::ExpectCleanError(frame.status());
      continue;
    }
    if (frame->size() != static_cast<std::size_t>(header.num_points)) {
      fuzz::Fail("a sample with the wrong number of points");
    }
  }
  return 0;
}
