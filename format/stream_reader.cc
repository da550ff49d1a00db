#include "format/stream_reader.h"

#include <algorithm>
#include <array>

#include "format/byte_io.h"
#include "format/chunk.h"
#include "format/crc32c.h"

namespace meshvid {

Status StreamReader::ReadExactly(uint8_t* out, uint64_t size, std::string_view what) {
  in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(size));
  const uint64_t got = static_cast<uint64_t>(in_.gcount());
  offset_ += got;
  if (got != size) {
    if (in_.bad()) return IoError(name_ + ": read error at offset " + std::to_string(offset_));
    return CorruptError(name_ + ": stream ends at offset " + std::to_string(offset_) + " inside " +
                        std::string(what) + " (truncated after " +
                        std::to_string(gof_offsets_.size()) + " complete groups of frames)");
  }
  return Status::Ok();
}

StatusOr<StreamReader::RawChunk> StreamReader::ReadChunk() {
  RawChunk chunk;
  chunk.offset = offset_;
  std::array<uint8_t, kChunkHeaderSize> header_bytes;
  if (in_.peek() == std::char_traits<char>::eof() && !in_.bad()) {
    return CorruptError(name_ + ": stream ends at offset " + std::to_string(offset_) + " after " +
                        std::to_string(gof_offsets_.size()) +
                        " groups of frames without INDX/TRLR (truncated)");
  }
  MESHVID_RETURN_IF_ERROR(ReadExactly(header_bytes.data(), header_bytes.size(), "a chunk header"));
  MESHVID_ASSIGN_OR_RETURN(const ChunkHeader header,
                           ParseChunkHeader(header_bytes, chunk.offset, limits_.max_chunk_payload,
                                            name_));
  chunk.type = header.type;
  chunk.flags = header.flags;
  const std::string context = ChunkContext(name_, header.type, chunk.offset);
  // Grow in bounded steps: memory follows the bytes actually delivered, not the claimed size.
  uint32_t crc = Crc32c(header_bytes);
  const uint64_t step = std::max<uint64_t>(limits_.read_step, 1);
  while (chunk.payload.size() < header.payload_size) {
    const uint64_t have = chunk.payload.size();
    const uint64_t piece = std::min(step, header.payload_size - have);
    chunk.payload.resize(have + piece);
    MESHVID_RETURN_IF_ERROR(ReadExactly(chunk.payload.data() + have, piece,
                                        "the payload of '" + FourccName(header.type) + "'"));
    crc = Crc32cExtend(crc, std::span<const uint8_t>(chunk.payload).subspan(have));
  }
  std::array<uint8_t, kChunkCrcSize> crc_bytes;
  MESHVID_RETURN_IF_ERROR(ReadExactly(crc_bytes.data(), crc_bytes.size(), "a chunk crc32c"));
  if (LoadLittleEndianU32(crc_bytes.data()) != crc) {
    return CorruptError(context + ": crc32c mismatch");
  }
  return chunk;
}

StatusOr<ContainerHeader> StreamReader::ReadHeader() {
  if (header_read_) return InvalidArgumentError(name_ + ": ReadHeader called twice");
  std::array<uint8_t, kPreambleSize> preamble;
  in_.read(reinterpret_cast<char*>(preamble.data()), preamble.size());
  const size_t got = static_cast<size_t>(in_.gcount());
  offset_ += got;
  MESHVID_ASSIGN_OR_RETURN(format_version_,
                           CheckPreamble(std::span<const uint8_t>(preamble).first(got), name_));
  key_groups_ = KeyGroupTracker(format_version_);
  MESHVID_ASSIGN_OR_RETURN(RawChunk chunk, ReadChunk());
  const std::string context = ChunkContext(name_, chunk.type, chunk.offset);
  if (chunk.type != kChunkHead) return CorruptError(context + ": the first chunk must be HEAD");
  MESHVID_ASSIGN_OR_RETURN(header_, DecodeHeaderPayload(chunk.payload, context));
  header_read_ = true;
  return header_;
}

StatusOr<StreamItem> StreamReader::Next() {
  if (!header_read_) return InvalidArgumentError(name_ + ": call ReadHeader before Next");
  StreamItem item;
  if (ended_) return item;
  while (true) {
    MESHVID_ASSIGN_OR_RETURN(RawChunk chunk, ReadChunk());
    const std::string context = ChunkContext(name_, chunk.type, chunk.offset);
    if (index_seen_ && chunk.type != kChunkTrailer) {
      return CorruptError(context + ": only TRLR may follow INDX");
    }
    if (chunk.type == kChunkBase || chunk.type == kChunkMotion) {
      MESHVID_RETURN_IF_ERROR(
          key_groups_.AddBaseOrMotion(chunk.type == kChunkBase, chunk.offset, context));
      item.key_group = key_groups_.key_groups().size() - 1;
      item.kind = chunk.type == kChunkBase ? StreamItem::Kind::kBase : StreamItem::Kind::kMotion;
      item.bytes = std::move(chunk.payload);
      return item;
    }
    if (chunk.type == kChunkGof) {
      MESHVID_ASSIGN_OR_RETURN(item.gof,
                               DecodeGofPayload(chunk.payload, header_.streams.size(), context));
      if (item.gof.gof_index != gof_offsets_.size() || item.gof.first_frame != next_frame_) {
        return CorruptError(context + ": gof_index " + std::to_string(item.gof.gof_index) +
                            " / first_frame " + std::to_string(item.gof.first_frame) +
                            " break the sequence (expected " + std::to_string(gof_offsets_.size()) +
                            " / " + std::to_string(next_frame_) + ")");
      }
      gof_offsets_.push_back(chunk.offset);
      key_groups_.AddGof();
      item.key_group = key_groups_.key_groups().size() - 1;
      next_frame_ += item.gof.frame_count;
      item.kind = StreamItem::Kind::kGof;
      return item;
    }
    if (chunk.type == kChunkIndex) {
      MESHVID_ASSIGN_OR_RETURN(item.index,
                               DecodeIndexPayload(chunk.payload, format_version_, context));
      bool matches = item.index.key_groups == key_groups_.key_groups() &&
                     item.index.gofs.size() == gof_offsets_.size();
      for (size_t k = 0; matches && k < gof_offsets_.size(); ++k) {
        matches = item.index.gofs[k].offset == gof_offsets_[k];
      }
      if (!matches) return CorruptError(context + ": the index does not match the chunks read");
      index_seen_ = true;
      index_offset_ = chunk.offset;
      item.kind = StreamItem::Kind::kIndex;
      return item;
    }
    if (chunk.type == kChunkTrailer) {
      MESHVID_ASSIGN_OR_RETURN(const uint64_t index_offset,
                               DecodeTrailerPayload(chunk.payload, context));
      if (!index_seen_ || index_offset != index_offset_) {
        return CorruptError(context + ": index_offset does not point at the INDX chunk");
      }
      ended_ = true;
      item.kind = StreamItem::Kind::kEnd;
      return item;
    }
    if (chunk.type == kChunkHead) return CorruptError(context + ": a second HEAD chunk");
    if ((chunk.flags & kChunkFlagSkippable) == 0) {
      return UnsupportedError(context + ": unknown chunk type that is not skippable");
    }
    // Unknown but skippable: ignore and read on.
  }
}

}  // namespace meshvid
