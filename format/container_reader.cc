#include "format/container_reader.h"

#include <array>

#include "format/byte_io.h"
#include "format/chunk.h"

namespace meshvid {
namespace {

// Largest payload a chunk starting at `offset` can have in an input of `size` bytes.
uint64_t MaxPayloadAt(uint64_t offset, uint64_t size) {
  const uint64_t overhead = kChunkHeaderSize + kChunkCrcSize;
  if (offset > size || size - offset < overhead) return 0;
  return size - offset - overhead;
}

}  // namespace

StatusOr<ContainerReader> ContainerReader::Open(std::unique_ptr<ByteSource> source) {
  ContainerReader reader(std::move(source));
  MESHVID_RETURN_IF_ERROR(reader.ReadHead());
  reader.index_status_ = reader.LoadIndex();
  reader.used_index_ = reader.index_status_.ok();
  if (!reader.used_index_) {
    reader.index_ = ContainerIndex();
    reader.ScanChunks();
  }
  if (reader.index_.key_groups.empty()) reader.index_.key_groups.push_back({});
  return reader;
}

StatusOr<ContainerReader> ContainerReader::OpenFile(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(auto source, FileSource::Open(path));
  return Open(std::move(source));
}

StatusOr<ContainerReader> ContainerReader::OpenMemory(std::vector<uint8_t> bytes,
                                                      std::string name) {
  return Open(std::make_unique<MemorySource>(std::move(bytes), std::move(name)));
}

StatusOr<std::vector<uint8_t>> ContainerReader::ReadChunkPayload(uint64_t offset, uint32_t type) {
  const std::string& name = source_->name();
  const uint64_t size = source_->size();
  if (offset > size || size - offset < kChunkHeaderSize + kChunkCrcSize) {
    return CorruptError(ChunkContext(name, type, offset) + ": truncated chunk (file has " +
                        std::to_string(size) + " bytes)");
  }
  std::array<uint8_t, kChunkHeaderSize> header_bytes;
  MESHVID_RETURN_IF_ERROR(source_->ReadAt(offset, header_bytes));
  MESHVID_ASSIGN_OR_RETURN(const ChunkHeader header,
                           ParseChunkHeader(header_bytes, offset, MaxPayloadAt(offset, size), name));
  if (header.type != type) {
    return CorruptError(name + ": expected a '" + FourccName(type) + "' chunk at offset " +
                        std::to_string(offset) + " but found '" + FourccName(header.type) + "'");
  }
  // Bounded by the file size above, so this allocation is justified by the input.
  std::vector<uint8_t> chunk(header.chunk_size());
  std::copy(header_bytes.begin(), header_bytes.end(), chunk.begin());
  MESHVID_RETURN_IF_ERROR(source_->ReadAt(
      offset + kChunkHeaderSize, std::span<uint8_t>(chunk).subspan(kChunkHeaderSize)));
  MESHVID_RETURN_IF_ERROR(VerifyChunkCrc(chunk, offset, name));
  chunk.resize(chunk.size() - kChunkCrcSize);
  chunk.erase(chunk.begin(), chunk.begin() + kChunkHeaderSize);
  return chunk;
}

Status ContainerReader::ReadHead() {
  std::array<uint8_t, kPreambleSize> preamble{};
  const size_t available = source_->size() < kPreambleSize ? source_->size() : kPreambleSize;
  MESHVID_RETURN_IF_ERROR(source_->ReadAt(0, std::span<uint8_t>(preamble).first(available)));
  MESHVID_ASSIGN_OR_RETURN(
      format_version_,
      CheckPreamble(std::span<const uint8_t>(preamble).first(available), source_->name()));
  if (source_->size() < kPreambleSize + kChunkHeaderSize + kChunkCrcSize) {
    return CorruptError(source_->name() + ": truncated before the end of the HEAD chunk");
  }
  MESHVID_ASSIGN_OR_RETURN(const auto payload, ReadChunkPayload(kPreambleSize, kChunkHead));
  MESHVID_ASSIGN_OR_RETURN(header_, DecodeHeaderPayload(payload, ChunkContext(source_->name(),
                                                                     kChunkHead, kPreambleSize)));
  head_end_ = kPreambleSize + kChunkHeaderSize + payload.size() + kChunkCrcSize;
  return Status::Ok();
}

Status ContainerReader::LoadIndex() {
  const std::string& name = source_->name();
  const uint64_t size = source_->size();
  if (size < head_end_ + kTrailerChunkSize) {
    return CorruptError(name + ": no room for a TRLR chunk (file truncated?)");
  }
  const uint64_t trailer_offset = size - kTrailerChunkSize;
  MESHVID_ASSIGN_OR_RETURN(const auto trailer, ReadChunkPayload(trailer_offset, kChunkTrailer));
  MESHVID_ASSIGN_OR_RETURN(const uint64_t index_offset,
                           DecodeTrailerPayload(trailer, ChunkContext(name, kChunkTrailer,
                                                                      trailer_offset)));
  if (index_offset < head_end_ || index_offset >= trailer_offset) {
    return CorruptError(name + ": TRLR index_offset " + std::to_string(index_offset) +
                        " is outside the chunk area [" + std::to_string(head_end_) + ", " +
                        std::to_string(trailer_offset) + ")");
  }
  MESHVID_ASSIGN_OR_RETURN(const auto payload, ReadChunkPayload(index_offset, kChunkIndex));
  const std::string context = ChunkContext(name, kChunkIndex, index_offset);
  if (index_offset + kChunkHeaderSize + payload.size() + kChunkCrcSize != trailer_offset) {
    return CorruptError(context + ": INDX is not immediately followed by TRLR");
  }
  MESHVID_ASSIGN_OR_RETURN(index_, DecodeIndexPayload(payload, format_version_, context));
  // Every referenced chunk must lie between HEAD and INDX with room for its header.
  const uint64_t limit = index_offset;
  auto in_area = [&](uint64_t offset, uint64_t min_payload) {
    return offset >= head_end_ && offset < limit &&
           limit - offset >= kChunkHeaderSize + min_payload + kChunkCrcSize;
  };
  for (size_t k = 0; k < index_.key_groups.size(); ++k) {
    const KeyGroupEntry& key_group = index_.key_groups[k];
    for (const auto& [name, offset] : {std::pair{"base_offset", key_group.base_offset},
                                       std::pair{"motion_offset", key_group.motion_offset}}) {
      if (offset != 0 && !in_area(offset, 0)) {
        return CorruptError(context + ": key group " + std::to_string(k) + " " + name + " " +
                            std::to_string(offset) + " is outside the chunk area");
      }
    }
  }
  for (size_t k = 0; k < index_.gofs.size(); ++k) {
    if (!in_area(index_.gofs[k].offset, kGofPrefixSize)) {
      return CorruptError(context + ": GOF " + std::to_string(k) + " offset " +
                          std::to_string(index_.gofs[k].offset) + " is outside the chunk area");
    }
  }
  if (!index_.gofs.empty() && index_.gofs[0].first_frame != 0) {
    return CorruptError(context + ": the first GOF does not start at frame 0");
  }
  if (header_.frame_count != 0 && header_.frame_count != frame_count()) {
    return CorruptError(context + ": the index covers " + std::to_string(frame_count()) +
                        " frames but HEAD declares frame_count " +
                        std::to_string(header_.frame_count));
  }
  return Status::Ok();
}

void ContainerReader::ScanChunks() {
  const std::string& name = source_->name();
  const uint64_t size = source_->size();
  uint64_t offset = head_end_;
  uint64_t next_frame = 0;
  KeyGroupTracker key_groups(format_version_);
  auto stop = [&](Status status) {
    scan_status_ = std::move(status);
    index_.key_groups = key_groups.key_groups();
    // A key group cut before its first GOF has nothing readable.
    if (index_.key_groups.size() > 1 && index_.key_groups.back().first_gof >= gof_count()) {
      index_.key_groups.pop_back();
    }
  };
  while (true) {
    if (offset == size) {
      return stop(CorruptError(name + ": the file ends after " + std::to_string(gof_count()) +
                               " groups of frames without INDX/TRLR (truncated)"));
    }
    if (size - offset < kChunkHeaderSize + kChunkCrcSize) {
      return stop(CorruptError(name + ": the last " + std::to_string(size - offset) +
                               " bytes at offset " + std::to_string(offset) +
                               " are not a complete chunk (truncated)"));
    }
    std::array<uint8_t, kChunkHeaderSize> bytes;
    if (Status s = source_->ReadAt(offset, bytes); !s.ok()) return stop(s);
    StatusOr<ChunkHeader> parsed = ParseChunkHeader(bytes, offset, MaxPayloadAt(offset, size), name);
    if (!parsed.ok()) return stop(parsed.status());
    const ChunkHeader header = *parsed;
    const std::string context = ChunkContext(name, header.type, offset);
    if (header.type == kChunkBase || header.type == kChunkMotion) {
      if (Status s = key_groups.AddBaseOrMotion(header.type == kChunkBase, offset, context);
          !s.ok()) {
        return stop(s);
      }
    } else if (header.type == kChunkGof) {
      std::array<uint8_t, kGofPrefixSize> prefix;
      if (header.payload_size < kGofPrefixSize) return stop(CorruptError(context + ": too small"));
      if (Status s = source_->ReadAt(offset + kChunkHeaderSize, prefix); !s.ok()) return stop(s);
      const uint32_t gof_index = LoadLittleEndianU32(prefix.data());
      const uint32_t first_frame = LoadLittleEndianU32(prefix.data() + 4);
      const uint32_t frame_count = LoadLittleEndianU32(prefix.data() + 8);
      if (gof_index != gof_count() || first_frame != next_frame || frame_count == 0 ||
          !FrameRangeFits(first_frame, frame_count)) {
        return stop(CorruptError(context + ": gof_index " + std::to_string(gof_index) +
                                 " first_frame " + std::to_string(first_frame) + " frame_count " +
                                 std::to_string(frame_count) + " break the GOF sequence"));
      }
      index_.gofs.push_back({offset, first_frame, frame_count});
      key_groups.AddGof();
      next_frame += frame_count;
    } else if (header.type == kChunkTrailer) {
      return stop(Status::Ok());
    } else if (header.type != kChunkIndex && (header.flags & kChunkFlagSkippable) == 0) {
      return stop(UnsupportedError(context + ": unknown chunk type that is not skippable"));
    }
    offset += header.chunk_size();
  }
}

uint64_t ContainerReader::frame_count() const {
  if (index_.gofs.empty()) return 0;
  return uint64_t{index_.gofs.back().first_frame} + index_.gofs.back().frame_count;
}

StatusOr<size_t> ContainerReader::FindGof(uint64_t frame) const {
  // GOFs are contiguous and sorted: binary search on first_frame.
  size_t low = 0, high = index_.gofs.size();
  while (low < high) {
    const size_t mid = (low + high) / 2;
    if (index_.gofs[mid].first_frame + uint64_t{index_.gofs[mid].frame_count} <= frame) {
      low = mid + 1;
    } else {
      high = mid;
    }
  }
  if (low == index_.gofs.size() || index_.gofs[low].first_frame > frame) {
    return NotFoundError(source_->name() + ": frame " + std::to_string(frame) +
                         " is not in any readable group of frames (" +
                         std::to_string(frame_count()) + " frames)");
  }
  return low;
}

std::pair<size_t, size_t> ContainerReader::GofsOfKeyGroup(size_t k) const {
  const size_t first = index_.key_groups[k].first_gof;
  const size_t end =
      k + 1 < index_.key_groups.size() ? index_.key_groups[k + 1].first_gof : index_.gofs.size();
  return {first, end};
}

StatusOr<std::vector<uint8_t>> ContainerReader::ReadBase(size_t k) {
  if (k >= index_.key_groups.size() || index_.key_groups[k].base_offset == 0) {
    return NotFoundError(source_->name() + ": key group " + std::to_string(k) +
                         " has no readable BASE chunk");
  }
  return ReadChunkPayload(index_.key_groups[k].base_offset, kChunkBase);
}

StatusOr<std::vector<uint8_t>> ContainerReader::ReadMotion(size_t k) {
  if (k >= index_.key_groups.size() || index_.key_groups[k].motion_offset == 0) {
    return NotFoundError(source_->name() + ": key group " + std::to_string(k) +
                         " has no readable MOTN chunk");
  }
  return ReadChunkPayload(index_.key_groups[k].motion_offset, kChunkMotion);
}

StatusOr<GroupOfFrames> ContainerReader::ReadGof(size_t k) {
  if (k >= gof_count()) {
    return NotFoundError(source_->name() + ": group of frames " + std::to_string(k) +
                         " does not exist (" + std::to_string(gof_count()) + " readable)");
  }
  const IndexEntry& entry = index_.gofs[k];
  MESHVID_ASSIGN_OR_RETURN(const auto payload, ReadChunkPayload(entry.offset, kChunkGof));
  const std::string context = ChunkContext(source_->name(), kChunkGof, entry.offset);
  MESHVID_ASSIGN_OR_RETURN(GroupOfFrames gof,
                           DecodeGofPayload(payload, header_.streams.size(), context));
  if (gof.gof_index != k || gof.first_frame != entry.first_frame ||
      gof.frame_count != entry.frame_count) {
    return CorruptError(context + ": the chunk does not match index entry " + std::to_string(k));
  }
  return gof;
}

}  // namespace meshvid
