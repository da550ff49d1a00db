// CompressBlock and DecompressBlock (compression.h) with libzstd. The WebAssembly decoder
// (web/wasm) has its own DecompressBlock, over a JavaScript zstd decoder.
#include <algorithm>
#include <bit>
#include <memory>
#include <string>

#include <zstd.h>

#include "codec/common/compression.h"

namespace meshvid {
namespace {

static_assert(kMaxZstdExpansion == ZSTD_BLOCKSIZE_MAX / 4);

/// First output allocation of a streamed decompression; it then doubles as bytes arrive.
constexpr std::size_t kInitialOutputBytes = 64 * 1024;

/// Frames may always declare a window up to 2^23 bytes (8 MiB, zstd's window at level 19
/// when the size is not known in advance), even for less content.
constexpr int kAlwaysAllowedWindowLog = 23;

struct DCtxDeleter {
  void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};

Status SizeMismatch(std::string_view what, std::string_view actual, std::size_t expected) {
  return CorruptError(std::string(what) + ": expands to " + std::string(actual) +
                      " bytes, expected " + std::to_string(expected));
}

}  // namespace

std::vector<std::uint8_t> CompressBlock(std::span<const std::uint8_t> raw, int level) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t size = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), level);
  // Compression into a ZSTD_compressBound buffer cannot fail for valid levels.
  out.resize(ZSTD_isError(size) ? 0 : size);
  return out;
}

StatusOr<std::vector<std::uint8_t>> DecompressBlock(std::span<const std::uint8_t> compressed,
                                                    std::size_t expected_size,
                                                    std::string_view what) {
  const unsigned long long content_size =
      ZSTD_getFrameContentSize(compressed.data(), compressed.size());
  if (content_size == ZSTD_CONTENTSIZE_ERROR) {
    return CorruptError(std::string(what) + ": not a zstd frame");
  }
  if (content_size != ZSTD_CONTENTSIZE_UNKNOWN && content_size != expected_size) {
    return SizeMismatch(what, std::to_string(content_size), expected_size);
  }
  // Checked before anything is allocated: the counts behind expected_size come from the file.
  if (!ZstdCanExpandTo(compressed.size(), expected_size)) {
    return CorruptError(std::string(what) + ": " + std::to_string(compressed.size()) +
                        " compressed bytes cannot expand to the " + std::to_string(expected_size) +
                        " bytes its counts say (a zstd frame expands at most " +
                        std::to_string(kMaxZstdExpansion) + "-fold)");
  }
  const std::unique_ptr<ZSTD_DCtx, DCtxDeleter> context(ZSTD_createDCtx());
  if (context == nullptr) return InternalError(std::string(what) + ": out of memory");
  // A streaming decoder allocates the window the frame header declares; no frame needs more
  // than its content, so a larger window is refused unless zstd's usual ones cover it.
  const ZSTD_bounds window_bounds = ZSTD_dParam_getBounds(ZSTD_d_windowLogMax);
  const int window_log =
      std::clamp(std::max(kAlwaysAllowedWindowLog, static_cast<int>(std::bit_width(expected_size))),
                 window_bounds.lowerBound, window_bounds.upperBound);
  ZSTD_DCtx_setParameter(context.get(), ZSTD_d_windowLogMax, window_log);
  // Streamed, so memory follows the bytes the frame actually produces: a frame that claims
  // (or is said to hold) more than it does fails after allocating about what it holds.
  std::vector<std::uint8_t> out;
  std::size_t produced = 0;
  ZSTD_inBuffer in{compressed.data(), compressed.size(), 0};
  while (true) {
    if (produced == out.size() && out.size() < expected_size) {
      const std::size_t size =
          std::min(expected_size, std::max(kInitialOutputBytes, 2 * out.size()));
      out.reserve(size);  // exactly: resize alone may round the capacity up past expected_size
      out.resize(size);
    }
    // Once the expected bytes are in, one spare byte tells a frame that expands further.
    std::uint8_t spare = 0;
    const bool full = produced == expected_size;
    ZSTD_outBuffer output =
        full ? ZSTD_outBuffer{&spare, 1, 0} : ZSTD_outBuffer{out.data(), out.size(), produced};
    const std::size_t remaining = ZSTD_decompressStream(context.get(), &output, &in);
    if (ZSTD_isError(remaining)) {
      return CorruptError(std::string(what) + ": " + ZSTD_getErrorName(remaining));
    }
    if (full && output.pos > 0) {
      return SizeMismatch(what, "more than " + std::to_string(expected_size), expected_size);
    }
    if (!full) produced = output.pos;
    if (remaining == 0) break;  // the frame is complete and flushed
    if (in.pos == in.size && output.pos < output.size) {
      return CorruptError(std::string(what) + ": the zstd frame is truncated (after " +
                          std::to_string(produced) + " of " + std::to_string(expected_size) +
                          " bytes)");
    }
  }
  if (in.pos != in.size) {
    return CorruptError(std::string(what) + ": " + std::to_string(in.size - in.pos) +
                        " bytes follow the zstd frame");
  }
  if (produced != expected_size) {
    return SizeMismatch(what, std::to_string(produced), expected_size);
  }
  out.resize(produced);
  return out;
}

}  // namespace meshvid
