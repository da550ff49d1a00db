// Progressive reader of a .mvid byte stream (pipe, socket, file read front to back). Pulls one
// chunk at a time from a std::istream, never seeks and never needs INDX/TRLR: a cut stream still
// yields every complete group of frames before the cut, then an error.
#ifndef MESHVID_FORMAT_STREAM_READER_H_
#define MESHVID_FORMAT_STREAM_READER_H_

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "format/chunk.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// Bounds for reading from a stream, whose size is not known in advance.
struct StreamLimits {
  /// Largest payload_size accepted (a stated maximum since the stream length is unknown).
  uint64_t max_chunk_payload = uint64_t{1} << 32;
  /// A payload is read in steps of at most this many bytes, so a lying payload_size on a short
  /// stream fails at the end of the stream after allocating at most what it delivered + one step.
  uint64_t read_step = uint64_t{1} << 20;
};

/// One item of a .mvid stream, in file order.
struct StreamItem {
  enum class Kind {
    kBase,    ///< `bytes` holds the BASE payload
    kMotion,  ///< `bytes` holds the MOTN payload
    kGof,     ///< `gof` holds a group of frames
    kIndex,   ///< `index` holds INDX (already checked against the GOFs seen)
    kEnd,     ///< TRLR read: the stream is complete
  };
  Kind kind = Kind::kEnd;
  /// The key group a kBase, kMotion or kGof item belongs to (0-based).
  size_t key_group = 0;
  std::vector<uint8_t> bytes;
  GroupOfFrames gof;
  ContainerIndex index;
};

/// Reads a .mvid stream chunk by chunk.
class StreamReader {
 public:
  /// `in` must outlive the reader; `name` appears in error messages.
  explicit StreamReader(std::istream& in, std::string name = "<stream>", StreamLimits limits = {})
      : in_(in), name_(std::move(name)), limits_(limits) {}

  /// Reads the preamble and HEAD. Must be called once, before Next().
  StatusOr<ContainerHeader> ReadHeader();
  /// The next item. After kEnd, returns kEnd again. A truncated or corrupt stream returns an
  /// error (kCorrupt) naming the offset, after every complete item before the damage.
  StatusOr<StreamItem> Next();

  /// The preamble's format_version (valid after ReadHeader).
  uint32_t format_version() const { return format_version_; }
  /// Bytes consumed so far.
  uint64_t offset() const { return offset_; }
  /// Groups of frames delivered so far.
  size_t gofs_read() const { return gof_offsets_.size(); }

 private:
  struct RawChunk {
    uint32_t type = 0;
    uint32_t flags = 0;
    uint64_t offset = 0;
    std::vector<uint8_t> payload;
  };
  StatusOr<RawChunk> ReadChunk();
  Status ReadExactly(uint8_t* out, uint64_t size, std::string_view what);

  std::istream& in_;
  std::string name_;
  StreamLimits limits_;
  ContainerHeader header_;
  bool header_read_ = false;
  bool ended_ = false;
  uint64_t offset_ = 0;
  uint64_t next_frame_ = 0;
  uint32_t format_version_ = kMvidFormatVersion;
  KeyGroupTracker key_groups_{kMvidFormatVersion};
  uint64_t index_offset_ = 0;
  bool index_seen_ = false;
  std::vector<uint64_t> gof_offsets_;
};

}  // namespace meshvid

#endif  // MESHVID_FORMAT_STREAM_READER_H_
