// Helpers shared by the fuzz targets (tests/fuzz/*_fuzzer.cc): splitting the fuzzer's bytes
// into parameters and a payload, a scratch file for readers that take a path, and the one
// rule every target checks: a failure is a Status with a message, never a crash.
#ifndef MESHVID_TESTS_FUZZ_FUZZ_UTIL_H_
#define MESHVID_TESTS_FUZZ_FUZZ_UTIL_H_

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "format/status.h"

namespace meshvid::fuzz {

/// Reads small parameters from the front of a fuzz input; what is left is the payload.
/// Past the end every value reads as 0 (a fuzz input may be any length).
class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data, size) {}
  std::uint8_t U8() { return static_cast<std::uint8_t>(Take(1)); }
  std::uint16_t U16() { return static_cast<std::uint16_t>(Take(2)); }
  std::uint32_t U32() { return static_cast<std::uint32_t>(Take(4)); }
  /// The next `size` bytes (fewer at the end).
  std::span<const std::uint8_t> Bytes(std::size_t size) {
    const std::size_t n = size < data_.size() ? size : data_.size();
    const std::span<const std::uint8_t> out = data_.first(n);
    data_ = data_.subspan(n);
    return out;
  }
  /// Everything not read yet.
  std::span<const std::uint8_t> Rest() { return Bytes(data_.size()); }
  std::size_t remaining() const { return data_.size(); }

 private:
  std::uint64_t Take(int bytes) {
    std::uint64_t value = 0;
    for (int i = 0; i < bytes && !data_.empty(); ++i) {
      value |= std::uint64_t{data_[0]} << (8 * i);
      data_ = data_.subspan(1);
    }
    return value;
  }
  std::span<const std::uint8_t> data_;
};

/// Aborts (a finding for the fuzzer, a failed test for the replay driver) with `what`.
[[noreturn]] inline void Fail(std::string_view what) {
  std::fprintf(stderr, "fuzz invariant broken: %.*s\n", static_cast<int>(what.size()),
               what.data());
  std::abort();
}

/// A failure must be a clean error: a code other than ok or internal, and a message.
inline void ExpectCleanError(const Status& status) {
  if (status.ok()) return;
  if (status.message().empty()) Fail("an error without a message");
  if (status.code() == StatusCode::kInternal) Fail("internal error: " + status.message());
}

/// A folder of scratch files for readers that take a path, one per process (fuzzers run
/// one input at a time in a process): under $TMPDIR, or /dev/shm when it exists (no disk).
const std::string& ScratchDir();
/// Writes `data` to ScratchDir()/`name` and returns the path.
std::string WriteScratchFile(const std::string& name, std::span<const std::uint8_t> data);

}  // namespace meshvid::fuzz

/// The entry point of every target (libFuzzer's name): one input, always returns 0.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

#endif  // MESHVID_TESTS_FUZZ_FUZZ_UTIL_H_
