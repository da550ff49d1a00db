// Fuzz target: PNGs through ReadDepthPng (16- and 8-bit greyscale depth images) and
// ReadColourPng (any PNG as 8-bit RGB, the colour beside a depth image). The readers take a
// path: the input is written to a scratch file.
// Invariants: clean errors; an image read has width x height values (pixels).
#include "tests/fuzz/fuzz_util.h"
#include "tools/io/depth_image.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::WriteScratchFile("fuzz.png", {data, size});
  StatusOr<DepthImage> image = ReadDepthPng(path);
  if (!image.ok()) {
    fuzz::ExpectCleanError(image.status());
  } else if (image->width < 1 || image->height < 1 ||
             image->values.size() != static_cast<std::size_t>(image->width) * image->height) {
    fuzz::Fail("a depth image whose values do not match its size");
  }
  StatusOr<ColourImage> colour = ReadColourPng(path);
  if (!colour.ok()) {
    fuzz::ExpectCleanError(colour.status());
  } else if (colour->width < 1 || colour->height < 1 ||
             colour->pixels.size() != static_cast<std::size_t>(colour->width) * colour->height) {
    fuzz::Fail("a colour image whose pixels do not match its size");
  }
  return 0;
}
