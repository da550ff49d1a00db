// One-pass writer of .mvid files: preamble + HEAD, then BASE, MOTN, GOF chunks in order, then
// INDX + TRLR on Finish(). Never seeks, so it can write to a pipe.
#ifndef MESHVID_FORMAT_CONTAINER_WRITER_H_
#define MESHVID_FORMAT_CONTAINER_WRITER_H_

#include <cstdint>
#include <functional>
#include <ostream>
#include <span>

#include "format/chunk.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// Receives the bytes of the file in order; returns an error to abort writing.
using ByteSink = std::function<Status(std::span<const uint8_t>)>;

/// A sink appending to `out` (kIoError when the stream fails). `out` must outlive the sink.
ByteSink OstreamSink(std::ostream& out, std::string name = "<stream>");

/// Writes one .mvid file (format_version 2) in a single pass. Call order: Begin, then per key
/// group [WriteBase] [WriteMotion] WriteGof..., then Finish. A WriteBase or WriteMotion after a
/// GOF starts the next key group. Out-of-order calls return kInvalidArgument; after any error
/// the writer refuses further calls.
class ContainerWriter {
 public:
  explicit ContainerWriter(ByteSink sink) : sink_(std::move(sink)) {
    index_.key_groups = key_groups_.key_groups();
  }

  /// Writes the preamble and the HEAD chunk.
  Status Begin(const ContainerHeader& header);
  /// Writes a BASE chunk (base mesh bytes, opaque here): at most once per key group, before
  /// its GOFs; after a GOF it starts the next key group.
  Status WriteBase(std::span<const uint8_t> base_mesh);
  /// Writes a MOTN chunk (segments and blend weights, opaque here), with the rules of WriteBase.
  Status WriteMotion(std::span<const uint8_t> motion);
  /// Writes a GOF chunk. gof.gof_index must be the number of GOFs written so far, first_frame
  /// must follow the previous group, frame_count >= 1, and there must be one packet list per
  /// header stream.
  Status WriteGof(const GroupOfFrames& gof);
  /// Writes INDX and TRLR. If the header declared frame_count > 0 it must match the frames
  /// written.
  Status Finish();

  /// Bytes written so far (the offset of the next chunk).
  uint64_t bytes_written() const { return offset_; }
  /// The index built so far (key groups and entries of the GOFs already written).
  const ContainerIndex& index() const { return index_; }
  /// The key group the next GOF joins (0-based).
  size_t key_group() const { return key_groups_.key_groups().size() - 1; }

 private:
  enum class State { kNew, kBegun, kGofs, kFinished, kFailed };
  Status Emit(std::span<const uint8_t> bytes);
  Status EmitChunk(uint32_t type, std::span<const uint8_t> payload);
  Status Misuse(const std::string& problem);
  Status WriteKeyGroupChunk(uint32_t type, std::span<const uint8_t> payload);

  ByteSink sink_;
  State state_ = State::kNew;
  ContainerHeader header_;
  ContainerIndex index_;
  KeyGroupTracker key_groups_{kMvidFormatVersion};
  uint64_t offset_ = 0;
  uint64_t frames_written_ = 0;
};

}  // namespace meshvid

#endif  // MESHVID_FORMAT_CONTAINER_WRITER_H_
