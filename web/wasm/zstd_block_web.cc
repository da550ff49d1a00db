// DecompressBlock (codec/common/compression.h) for the WebAssembly decoder: the zstd frame is
// decoded by the JavaScript zstd decoder the page hands the module (Module.zstdDecompress,
// set by web/decoder/meshvid.mjs), with the native decoder's checks of sizes around it.
#include <emscripten.h>

#include <string>

#include "codec/common/compression.h"

namespace meshvid {
namespace {

// Decompresses [source, source + source_size) into [target, target + capacity); returns the
// bytes it expands to (which may exceed `capacity`: nothing past it is written), or -1 when it
// is not a valid zstd frame.
EM_JS(double, meshvid_zstd_decompress,
      (const std::uint8_t* source, std::size_t source_size, std::uint8_t* target,
       std::size_t capacity),
      {
        try {
          const out = Module.zstdDecompress(HEAPU8.subarray(source, source + source_size));
          HEAPU8.set(out.subarray(0, Math.min(out.length, capacity)), target);
          return out.length;
        } catch (e) {
          return -1;
        }
      });

}  // namespace

StatusOr<std::vector<std::uint8_t>> DecompressBlock(std::span<const std::uint8_t> compressed,
                                                    std::size_t expected_size,
                                                    std::string_view what) {
  // Checked before anything is allocated: the counts behind expected_size come from the file.
  if (!ZstdCanExpandTo(compressed.size(), expected_size)) {
    return CorruptError(std::string(what) + ": " + std::to_string(compressed.size()) +
                        " compressed bytes cannot expand to the " + std::to_string(expected_size) +
                        " bytes its counts say");
  }
  std::vector<std::uint8_t> out(expected_size);
  const double produced =
      meshvid_zstd_decompress(compressed.data(), compressed.size(), out.data(), out.size());
  if (produced < 0) return CorruptError(std::string(what) + ": not a valid zstd frame");
  if (produced != static_cast<double>(expected_size)) {
    return CorruptError(std::string(what) + ": expands to " +
                        std::to_string(static_cast<std::uint64_t>(produced)) + " bytes, expected " +
                        std::to_string(expected_size));
  }
  return out;
}

}  // namespace meshvid
