// Opening a .mvid in a test: for tests that link the decoder (codec_*, cli_* and bench_*).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "codec/dec/mvid_decoder.h"

namespace meshvid::testing {

/// Opens the .mvid at `path`; on failure records a test failure with the decoder's message
/// and returns null (callers ASSERT_NE it).
inline std::unique_ptr<MvidDecoder> OpenDecoderOrFail(const std::string& path) {
  StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenFile(path);
  EXPECT_TRUE(decoder.ok()) << path << ": " << decoder.status().message();
  return decoder.ok() ? *std::move(decoder) : nullptr;
}

}  // namespace meshvid::testing
