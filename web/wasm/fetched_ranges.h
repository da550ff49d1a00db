// A ByteSource over the parts of a remote file that have arrived (HTTP range requests made
// by web/decoder/meshvid.mjs). A read of bytes that have not arrived fails and records them
// (Missing), so the page fetches them and calls again: the container reader reads a streamed
// file as it reads one in memory.
#ifndef MESHVID_WEB_WASM_FETCHED_RANGES_H_
#define MESHVID_WEB_WASM_FETCHED_RANGES_H_

#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "format/byte_source.h"

namespace meshvid {

/// A file of known size of which some byte ranges are held.
class FetchedRanges : public ByteSource {
 public:
  FetchedRanges(std::uint64_t size, std::string name) : size_(size), name_(std::move(name)) {}

  std::uint64_t size() const override { return size_; }
  const std::string& name() const override { return name_; }

  /// Holds `bytes` as the file's bytes from `offset`. Pieces must not overlap (the page
  /// fetches only the gaps FirstGap reports).
  void Add(std::uint64_t offset, std::vector<std::uint8_t> bytes) {
    if (bytes.empty() || offset >= size_) return;
    if (bytes.size() > size_ - offset) bytes.resize(size_ - offset);
    pieces_[offset] = std::move(bytes);
  }

  /// The first range [start, end) of [offset, offset + length) that is not held, if any.
  std::optional<std::pair<std::uint64_t, std::uint64_t>> FirstGap(std::uint64_t offset,
                                                                  std::uint64_t length) const {
    const std::uint64_t end = offset + length;
    std::uint64_t at = offset;
    while (at < end) {
      const std::uint64_t held = HeldFrom(at);
      if (held == 0) {
        // The gap runs to the next piece (or the end asked for).
        auto next = pieces_.upper_bound(at);
        const std::uint64_t gap_end = next == pieces_.end() ? end : std::min(end, next->first);
        return std::make_pair(at, gap_end);
      }
      at += held;
    }
    return std::nullopt;
  }

  Status ReadAt(std::uint64_t offset, std::span<std::uint8_t> out) override {
    if (offset > size_ || out.size() > size_ - offset) {
      return CorruptError(name_ + ": read of " + std::to_string(out.size()) + " bytes at offset " +
                          std::to_string(offset) + " runs past the end (" + std::to_string(size_) +
                          " bytes)");
    }
    if (const auto gap = FirstGap(offset, out.size())) {
      if (!missing_) missing_ = gap;
      return IoError(name_ + ": bytes " + std::to_string(gap->first) + ".." +
                     std::to_string(gap->second) + " have not arrived");
    }
    std::uint64_t at = offset;
    while (at < offset + out.size()) {
      auto piece = std::prev(pieces_.upper_bound(at));
      const std::uint64_t from = at - piece->first;
      const std::uint64_t count =
          std::min<std::uint64_t>(piece->second.size() - from, offset + out.size() - at);
      std::memcpy(out.data() + (at - offset), piece->second.data() + from, count);
      at += count;
    }
    return Status::Ok();
  }

  /// The first range a read since the last call found missing; clears it.
  std::optional<std::pair<std::uint64_t, std::uint64_t>> TakeMissing() {
    return std::exchange(missing_, std::nullopt);
  }

 private:
  /// How many bytes from `at` one held piece covers (0 if none).
  std::uint64_t HeldFrom(std::uint64_t at) const {
    auto piece = pieces_.upper_bound(at);
    if (piece == pieces_.begin()) return 0;
    --piece;
    const std::uint64_t end = piece->first + piece->second.size();
    return at < end ? end - at : 0;
  }

  std::uint64_t size_;
  std::string name_;
  std::map<std::uint64_t, std::vector<std::uint8_t>> pieces_;
  std::optional<std::pair<std::uint64_t, std::uint64_t>> missing_;
};

/// A ByteSource reading through to a FetchedRanges that outlives it: the ranges survive a
/// failed open, to which the page then adds what was missing.
class BorrowedRanges : public ByteSource {
 public:
  explicit BorrowedRanges(FetchedRanges& ranges) : ranges_(ranges) {}
  std::uint64_t size() const override { return ranges_.size(); }
  const std::string& name() const override { return ranges_.name(); }
  Status ReadAt(std::uint64_t offset, std::span<std::uint8_t> out) override {
    return ranges_.ReadAt(offset, out);
  }

 private:
  FetchedRanges& ranges_;
};

}  // namespace meshvid

#endif  // MESHVID_WEB_WASM_FETCHED_RANGES_H_
