#include "format/validate.h"

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cstdio>

#include "format/byte_io.h"
#include "format/chunk.h"

namespace meshvid {
namespace {

// A ByteSource over a span it does not own (Validate of bytes must not copy them).
class SpanSource : public ByteSource {
 public:
  SpanSource(std::span<const uint8_t> bytes, std::string name)
      : bytes_(bytes), name_(std::move(name)) {}
  uint64_t size() const override { return bytes_.size(); }
  Status ReadAt(uint64_t offset, std::span<uint8_t> out) override {
    if (offset > bytes_.size() || out.size() > bytes_.size() - offset) {
      return CorruptError(name_ + ": read past the end");
    }
    std::copy_n(bytes_.begin() + offset, out.size(), out.begin());
    return Status::Ok();
  }
  const std::string& name() const override { return name_; }

 private:
  std::span<const uint8_t> bytes_;
  std::string name_;
};

// Walks the chunks of one container, accumulating the report.
class Validator {
 public:
  Validator(ByteSource& source, ValidationReport* report) : source_(source), report_(*report) {}

  void Run() {
    const uint64_t size = source_.size();
    std::array<uint8_t, kPreambleSize> preamble{};
    const size_t got = size < kPreambleSize ? size : kPreambleSize;
    if (!Check(source_.ReadAt(0, std::span<uint8_t>(preamble).first(got)))) return;
    StatusOr<uint32_t> version =
        CheckPreamble(std::span<const uint8_t>(preamble).first(got), name());
    if (!Check(version.ok() ? Status::Ok() : version.status())) return;
    format_version_ = *version;
    key_groups_ = KeyGroupTracker(format_version_);
    uint64_t offset = kPreambleSize;
    bool trailer_seen = false;
    while (offset < size && !trailer_seen) {
      if (!VisitChunk(offset, &offset, &trailer_seen)) return;
    }
    if (!report_.header_ok) return Fail(name() + ": no HEAD chunk");
    if (!trailer_seen) {
      return Fail(name() + ": no TRLR chunk at the end (truncated, or the writer never finished)");
    }
    if (offset != size) {
      Fail(name() + ": " + std::to_string(size - offset) + " unexpected bytes after TRLR");
    }
    if (report_.header.frame_count != 0 && report_.header.frame_count != report_.frame_count) {
      Fail(name() + ": HEAD declares frame_count " + std::to_string(report_.header.frame_count) +
           " but the GOFs hold " + std::to_string(report_.frame_count));
    }
    report_.index_consistent = report_.has_index && index_errors_ == 0;
  }

 private:
  const std::string& name() const { return source_.name(); }
  void Fail(std::string message) { report_.errors.push_back(std::move(message)); }
  bool Check(const Status& status) {
    if (!status.ok()) Fail(status.message());
    return status.ok();
  }
  void IndexFail(std::string message) {
    ++index_errors_;
    Fail(std::move(message));
  }

  // Validates the chunk at `offset`; returns false when the walk cannot go on.
  bool VisitChunk(uint64_t offset, uint64_t* next, bool* trailer_seen) {
    const uint64_t size = source_.size();
    if (size - offset < kChunkHeaderSize + kChunkCrcSize) {
      Fail(name() + ": " + std::to_string(size - offset) + " bytes at offset " +
           std::to_string(offset) + " are not a complete chunk (truncated)");
      return false;
    }
    std::array<uint8_t, kChunkHeaderSize> header_bytes;
    if (!Check(source_.ReadAt(offset, header_bytes))) return false;
    StatusOr<ChunkHeader> parsed = ParseChunkHeader(
        header_bytes, offset, size - offset - kChunkHeaderSize - kChunkCrcSize, name());
    if (!Check(parsed.status().ok() ? Status::Ok() : parsed.status())) return false;
    const ChunkHeader header = *parsed;
    std::vector<uint8_t> chunk(header.chunk_size());  // bounded by the input size above
    std::copy(header_bytes.begin(), header_bytes.end(), chunk.begin());
    if (!Check(source_.ReadAt(offset + kChunkHeaderSize,
                              std::span<uint8_t>(chunk).subspan(kChunkHeaderSize)))) {
      return false;
    }
    ChunkReport entry{offset, FourccName(header.type), header.flags, header.payload_size, false};
    entry.crc_ok = Check(VerifyChunkCrc(chunk, offset, name()));
    report_.chunks.push_back(entry);
    *next = offset + header.chunk_size();
    const bool first = report_.chunks.size() == 1;
    const std::string context = ChunkContext(name(), header.type, offset);
    if (first != (header.type == kChunkHead)) {
      Fail(context + (first ? ": the first chunk must be HEAD" : ": a second HEAD chunk"));
      if (first) return false;  // nothing after can be interpreted without HEAD
    }
    if (!entry.crc_ok) return !first;
    const std::span<const uint8_t> payload =
        std::span<const uint8_t>(chunk).subspan(kChunkHeaderSize, header.payload_size);
    if (index_offset_ != 0 && header.type != kChunkTrailer) {
      Fail(context + ": only TRLR may follow INDX");
    }
    if (header.type == kChunkHead) {
      StatusOr<ContainerHeader> decoded = DecodeHeaderPayload(payload, context);
      if (!Check(decoded.ok() ? Status::Ok() : decoded.status())) return false;
      report_.header = *decoded;
      report_.header_ok = true;
    } else if (header.type == kChunkBase || header.type == kChunkMotion) {
      Check(key_groups_.AddBaseOrMotion(header.type == kChunkBase, offset, context));
    } else if (header.type == kChunkGof) {
      VisitGof(payload, offset, context);
    } else if (header.type == kChunkIndex) {
      VisitIndex(payload, offset, context);
    } else if (header.type == kChunkTrailer) {
      *trailer_seen = true;
      StatusOr<uint64_t> index_offset = DecodeTrailerPayload(payload, context);
      if (!Check(index_offset.ok() ? Status::Ok() : index_offset.status())) return true;
      if (index_offset_ == 0 || *index_offset != index_offset_) {
        IndexFail(context + ": index_offset " + std::to_string(*index_offset) +
                  " does not point at the INDX chunk");
      } else {
        report_.has_index = index_decoded_;
      }
    } else if ((header.flags & kChunkFlagSkippable) == 0) {
      Fail(context + ": unknown chunk type that is not skippable");
    }
    return true;
  }

  void VisitGof(std::span<const uint8_t> payload, uint64_t offset, const std::string& context) {
    StatusOr<GroupOfFrames> gof = DecodeGofPayload(payload, report_.header.streams.size(), context);
    if (!Check(gof.ok() ? Status::Ok() : gof.status())) return;
    if (gof->gof_index != gofs_.size() || gof->first_frame != report_.frame_count) {
      Fail(context + ": gof_index " + std::to_string(gof->gof_index) + " / first_frame " +
           std::to_string(gof->first_frame) + " break the sequence (expected " +
           std::to_string(gofs_.size()) + " / " + std::to_string(report_.frame_count) + ")");
    }
    gofs_.push_back({offset, gof->first_frame, gof->frame_count});
    key_groups_.AddGof();
    ++report_.gof_count;
    report_.frame_count += gof->frame_count;
  }

  void VisitIndex(std::span<const uint8_t> payload, uint64_t offset, const std::string& context) {
    if (index_offset_ != 0) return Fail(context + ": duplicate INDX");
    index_offset_ = offset;
    StatusOr<ContainerIndex> index = DecodeIndexPayload(payload, format_version_, context);
    if (!index.ok()) return IndexFail(index.status().message());
    index_decoded_ = true;
    const std::vector<KeyGroupEntry>& present = key_groups_.key_groups();
    report_.key_group_count = static_cast<uint32_t>(present.size());
    if (present.size() > 1 && present.back().first_gof >= gofs_.size()) {
      Fail(context + ": the last key group has no group of frames");
    }
    if (index->key_groups != present) {
      IndexFail(context + ": lists " + std::to_string(index->key_groups.size()) +
                " key groups that do not match the " + std::to_string(present.size()) +
                " key groups (BASE/MOTN offsets, first GOFs) of the file");
    }
    if (index->gofs.size() != gofs_.size()) {
      return IndexFail(context + ": lists " + std::to_string(index->gofs.size()) +
                       " groups of frames but the file holds " + std::to_string(gofs_.size()));
    }
    for (size_t k = 0; k < gofs_.size(); ++k) {
      if (!(index->gofs[k] == gofs_[k])) {
        IndexFail(context + ": entry " + std::to_string(k) + " does not match the GOF chunk at " +
                  std::to_string(gofs_[k].offset));
      }
    }
  }

  ByteSource& source_;
  ValidationReport& report_;
  uint32_t format_version_ = kMvidFormatVersion;
  KeyGroupTracker key_groups_{kMvidFormatVersion};
  uint64_t index_offset_ = 0;
  int index_errors_ = 0;
  bool index_decoded_ = false;
  std::vector<IndexEntry> gofs_;
};

}  // namespace

Status ValidationReport::ToStatus() const {
  if (ok()) return Status::Ok();
  std::string message = errors.front();
  if (errors.size() > 1) message += " (and " + std::to_string(errors.size() - 1) + " more problems)";
  return CorruptError(std::move(message));
}

std::string ValidationReport::ToText() const {
  std::string text;
  char line[160];
  for (const ChunkReport& chunk : chunks) {
    std::snprintf(line, sizeof(line), "%12" PRIu64 "  %-10s flags 0x%08x  %12" PRIu64
                  " bytes  crc %s\n", chunk.offset, chunk.type.c_str(), chunk.flags,
                  chunk.payload_size, chunk.crc_ok ? "ok" : "BAD");
    text += line;
  }
  std::snprintf(line, sizeof(line), "%u groups of frames, %" PRIu64 " frames, index %s\n",
                gof_count, frame_count,
                !has_index ? "missing" : (index_consistent ? "consistent" : "INCONSISTENT"));
  text += line;
  for (const std::string& error : errors) text += "error: " + error + "\n";
  text += ok() ? "valid\n" : "INVALID\n";
  return text;
}

ValidationReport ValidateContainer(ByteSource& source) {
  ValidationReport report;
  Validator(source, &report).Run();
  return report;
}

ValidationReport ValidateContainer(std::span<const uint8_t> bytes, std::string_view name) {
  SpanSource source(bytes, std::string(name));
  return ValidateContainer(source);
}

StatusOr<ValidationReport> ValidateContainerFile(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(auto source, FileSource::Open(path));
  return ValidateContainer(*source);
}

}  // namespace meshvid
