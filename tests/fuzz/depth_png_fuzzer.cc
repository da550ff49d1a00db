// Fuzz target: 16-bit (and 8-bit) greyscale depth PNGs through ReadDepthPng. The reader takes
// a path: the input is written to a scratch file.
// Invariants: clean errors; an image read has width x height values.
#include "tests/fuzz/fuzz_util.h"
#include "tools/io/depth_image.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::WriteScratchFile("fuzz.png", {data, size});
  StatusOr<DepthImage> image = ReadDepthPng(path);
  if (!image.ok()) {
    fuzz::ExpectCleanError(image.status());
    return 0;
  }
  if (image->width < 1 || image->height < 1 ||
      image->values.size() != static_cast<std::size_t>(image->width) * image->height) {
    fuzz::Fail("an image whose values do not match its size");
  }
  return 0;
}
