#include "format/payloads.h"

#include "format/byte_io.h"

namespace meshvid {
namespace {

// Smallest encoded StreamInfo: codec(4) width height bit_depth (3 x u32) name_size(u32).
constexpr size_t kMinStreamInfoSize = 4 + 12 + 4;
// Smallest encoded INDX entry: offset(u64) first_frame(u32) frame_count(u32).
constexpr size_t kIndexEntrySize = 16;
constexpr size_t kKeyGroupEntrySize = 20;

Status TooMany(const ByteReader& reader, std::string_view what, uint64_t count, uint64_t limit) {
  return reader.Error(std::string(what) + " " + std::to_string(count) +
                      " is more than the remaining bytes can hold (at most " +
                      std::to_string(limit) + ")");
}

}  // namespace

Status CheckHeader(const ContainerHeader& header) {
  if (header.frame_rate_numerator == 0 || header.frame_rate_denominator == 0) {
    return InvalidArgumentError("container header: frame_rate_numerator and "
                                "frame_rate_denominator must not be 0");
  }
  if (header.streams.size() > kMaxStreams) {
    return InvalidArgumentError("container header: " + std::to_string(header.streams.size()) +
                                " streams, the limit is " + std::to_string(kMaxStreams));
  }
  for (size_t i = 0; i < header.streams.size(); ++i) {
    const StreamInfo& stream = header.streams[i];
    if (stream.codec.size() != kMaxCodecTagSize) {
      return InvalidArgumentError("container header: stream " + std::to_string(i) +
                                  " codec tag \"" + stream.codec + "\" is not 4 characters");
    }
    if (stream.name.size() > kMaxStreamNameSize) {
      return InvalidArgumentError("container header: stream " + std::to_string(i) +
                                  " name is longer than " + std::to_string(kMaxStreamNameSize) +
                                  " bytes");
    }
  }
  if (header.metadata_json.size() > UINT32_MAX) {
    return InvalidArgumentError("container header: metadata_json is larger than 4 GiB");
  }
  return Status::Ok();
}

std::vector<uint8_t> EncodeHeaderPayload(const ContainerHeader& header) {
  ByteWriter writer;
  writer.PutU32(header.frame_rate_numerator);
  writer.PutU32(header.frame_rate_denominator);
  writer.PutU32(header.frame_count);
  writer.PutU32(header.gof_size);
  writer.PutU32(header.level_count);
  writer.PutU32(static_cast<uint32_t>(header.streams.size()));
  for (const StreamInfo& stream : header.streams) {
    writer.PutFourcc(stream.codec);
    writer.PutU32(stream.width);
    writer.PutU32(stream.height);
    writer.PutU32(stream.bit_depth);
    writer.PutSizedString(stream.name);
  }
  writer.PutSizedString(header.metadata_json);
  return writer.Release();
}

StatusOr<ContainerHeader> DecodeHeaderPayload(std::span<const uint8_t> payload,
                                              std::string context) {
  ByteReader reader(payload, std::move(context));
  ContainerHeader header;
  MESHVID_ASSIGN_OR_RETURN(header.frame_rate_numerator, reader.ReadU32("frame_rate_numerator"));
  MESHVID_ASSIGN_OR_RETURN(header.frame_rate_denominator,
                           reader.ReadU32("frame_rate_denominator"));
  if (header.frame_rate_numerator == 0) return reader.Error("frame_rate_numerator is 0 (0 fps)");
  if (header.frame_rate_denominator == 0) return reader.Error("frame_rate_denominator is 0");
  MESHVID_ASSIGN_OR_RETURN(header.frame_count, reader.ReadU32("frame_count"));
  MESHVID_ASSIGN_OR_RETURN(header.gof_size, reader.ReadU32("gof_size"));
  MESHVID_ASSIGN_OR_RETURN(header.level_count, reader.ReadU32("level_count"));
  MESHVID_ASSIGN_OR_RETURN(const uint32_t stream_count, reader.ReadU32("stream_count"));
  if (stream_count > kMaxStreams) {
    return reader.Error("stream_count " + std::to_string(stream_count) + " exceeds the limit of " +
                        std::to_string(kMaxStreams));
  }
  if (stream_count > reader.remaining() / kMinStreamInfoSize) {
    return TooMany(reader, "stream_count", stream_count, reader.remaining() / kMinStreamInfoSize);
  }
  header.streams.resize(stream_count);
  for (uint32_t i = 0; i < stream_count; ++i) {
    StreamInfo& stream = header.streams[i];
    MESHVID_ASSIGN_OR_RETURN(const auto codec, reader.ReadBytes(4, "codec"));
    stream.codec.assign(reinterpret_cast<const char*>(codec.data()), codec.size());
    MESHVID_ASSIGN_OR_RETURN(stream.width, reader.ReadU32("width"));
    MESHVID_ASSIGN_OR_RETURN(stream.height, reader.ReadU32("height"));
    MESHVID_ASSIGN_OR_RETURN(stream.bit_depth, reader.ReadU32("bit_depth"));
    MESHVID_ASSIGN_OR_RETURN(stream.name, reader.ReadSizedString(kMaxStreamNameSize, "name"));
  }
  MESHVID_ASSIGN_OR_RETURN(header.metadata_json,
                           reader.ReadSizedString(reader.remaining(), "metadata_json"));
  if (reader.remaining() != 0) {
    return reader.Error(std::to_string(reader.remaining()) + " unexpected bytes after metadata_json");
  }
  return header;
}

std::vector<uint8_t> EncodeGofPayload(const GroupOfFrames& gof) {
  ByteWriter writer;
  writer.PutU32(gof.gof_index);
  writer.PutU32(gof.first_frame);
  writer.PutU32(gof.frame_count);
  writer.PutU32(static_cast<uint32_t>(gof.transforms.size()));
  writer.PutBytes(gof.transforms);
  writer.PutU32(static_cast<uint32_t>(gof.packets.size()));
  for (const auto& stream_packets : gof.packets) {
    writer.PutU32(static_cast<uint32_t>(stream_packets.size()));
    for (const auto& packet : stream_packets) {
      writer.PutU32(static_cast<uint32_t>(packet.size()));
      writer.PutBytes(packet);
    }
  }
  return writer.Release();
}

StatusOr<GroupOfFrames> DecodeGofPayload(std::span<const uint8_t> payload, size_t stream_count,
                                         std::string context) {
  ByteReader reader(payload, std::move(context));
  GroupOfFrames gof;
  MESHVID_ASSIGN_OR_RETURN(gof.gof_index, reader.ReadU32("gof_index"));
  MESHVID_ASSIGN_OR_RETURN(gof.first_frame, reader.ReadU32("first_frame"));
  MESHVID_ASSIGN_OR_RETURN(gof.frame_count, reader.ReadU32("frame_count"));
  if (gof.frame_count == 0) return reader.Error("frame_count is 0");
  if (!FrameRangeFits(gof.first_frame, gof.frame_count)) {
    return reader.Error("first_frame " + std::to_string(gof.first_frame) + " + frame_count " +
                        std::to_string(gof.frame_count) + " passes the last frame number");
  }
  MESHVID_ASSIGN_OR_RETURN(const uint32_t transforms_size, reader.ReadU32("transforms_size"));
  MESHVID_ASSIGN_OR_RETURN(const auto transforms, reader.ReadBytes(transforms_size, "transforms"));
  gof.transforms.assign(transforms.begin(), transforms.end());
  MESHVID_ASSIGN_OR_RETURN(const uint32_t gof_stream_count, reader.ReadU32("stream_count"));
  if (gof_stream_count != stream_count) {
    return reader.Error("stream_count " + std::to_string(gof_stream_count) +
                        " differs from the header's " + std::to_string(stream_count) + " streams");
  }
  gof.packets.resize(stream_count);
  for (size_t s = 0; s < stream_count; ++s) {
    MESHVID_ASSIGN_OR_RETURN(const uint32_t packet_count, reader.ReadU32("packet_count"));
    // Every packet needs at least its u32 packet_size.
    if (packet_count > reader.remaining() / 4) {
      return TooMany(reader, "packet_count", packet_count, reader.remaining() / 4);
    }
    gof.packets[s].resize(packet_count);
    for (uint32_t p = 0; p < packet_count; ++p) {
      MESHVID_ASSIGN_OR_RETURN(const uint32_t packet_size, reader.ReadU32("packet_size"));
      MESHVID_ASSIGN_OR_RETURN(const auto packet, reader.ReadBytes(packet_size, "packet"));
      gof.packets[s][p].assign(packet.begin(), packet.end());
    }
  }
  if (reader.remaining() != 0) {
    return reader.Error(std::to_string(reader.remaining()) + " unexpected bytes after the packets");
  }
  return gof;
}

size_t ContainerIndex::KeyGroupOfGof(size_t gof) const {
  size_t k = 0;
  while (k + 1 < key_groups.size() && key_groups[k + 1].first_gof <= gof) ++k;
  return k;
}

Status KeyGroupTracker::AddBaseOrMotion(bool is_base, uint64_t offset,
                                        const std::string& context) {
  KeyGroupEntry* current = &key_groups_.back();
  const bool has_gofs = gof_count_ > current->first_gof;
  if (has_gofs) {
    if (version_ < 2) {
      return CorruptError(context + ": BASE and MOTN must come before the first GOF in a " +
                          "format_version 1 file");
    }
    key_groups_.push_back({0, 0, gof_count_});
    current = &key_groups_.back();
  }
  uint64_t& slot = is_base ? current->base_offset : current->motion_offset;
  if (slot != 0) {
    return CorruptError(context + ": a second " + (is_base ? "BASE" : "MOTN") + " in key group " +
                        std::to_string(key_groups_.size() - 1) + " before any of its GOFs");
  }
  slot = offset;
  return Status::Ok();
}

StatusOr<std::vector<uint8_t>> EncodeIndexPayload(const ContainerIndex& index,
                                                  uint32_t format_version) {
  if (index.key_groups.empty() || (format_version < 2 && index.key_groups.size() != 1)) {
    return InvalidArgumentError("INDX of format_version " + std::to_string(format_version) +
                                " cannot hold " + std::to_string(index.key_groups.size()) +
                                " key groups");
  }
  ByteWriter writer;
  if (format_version < 2) {
    writer.PutU64(index.key_groups[0].base_offset);
    writer.PutU64(index.key_groups[0].motion_offset);
  } else {
    writer.PutU32(static_cast<uint32_t>(index.key_groups.size()));
    for (const KeyGroupEntry& key_group : index.key_groups) {
      writer.PutU64(key_group.base_offset);
      writer.PutU64(key_group.motion_offset);
      writer.PutU32(key_group.first_gof);
    }
  }
  writer.PutU32(static_cast<uint32_t>(index.gofs.size()));
  for (const IndexEntry& entry : index.gofs) {
    writer.PutU64(entry.offset);
    writer.PutU32(entry.first_frame);
    writer.PutU32(entry.frame_count);
  }
  return writer.Release();
}

StatusOr<ContainerIndex> DecodeIndexPayload(std::span<const uint8_t> payload,
                                            uint32_t format_version, std::string context) {
  ByteReader reader(payload, std::move(context));
  ContainerIndex index;
  if (format_version < 2) {
    KeyGroupEntry& only = index.key_groups.emplace_back();
    MESHVID_ASSIGN_OR_RETURN(only.base_offset, reader.ReadU64("base_offset"));
    MESHVID_ASSIGN_OR_RETURN(only.motion_offset, reader.ReadU64("motion_offset"));
  } else {
    MESHVID_ASSIGN_OR_RETURN(const uint32_t key_group_count, reader.ReadU32("key_group_count"));
    if (key_group_count == 0 || key_group_count > reader.remaining() / kKeyGroupEntrySize) {
      return reader.Error("key_group_count " + std::to_string(key_group_count) +
                          " does not fit the " + std::to_string(reader.remaining()) +
                          " bytes left (at least 1 entry of " +
                          std::to_string(kKeyGroupEntrySize) + " bytes each)");
    }
    index.key_groups.resize(key_group_count);
    for (uint32_t k = 0; k < key_group_count; ++k) {
      KeyGroupEntry& entry = index.key_groups[k];
      MESHVID_ASSIGN_OR_RETURN(entry.base_offset, reader.ReadU64("base_offset"));
      MESHVID_ASSIGN_OR_RETURN(entry.motion_offset, reader.ReadU64("motion_offset"));
      MESHVID_ASSIGN_OR_RETURN(entry.first_gof, reader.ReadU32("first_gof"));
      if (k == 0 ? entry.first_gof != 0 : entry.first_gof <= index.key_groups[k - 1].first_gof) {
        return reader.Error("key group " + std::to_string(k) + " first_gof " +
                            std::to_string(entry.first_gof) +
                            (k == 0 ? " is not 0" : " does not follow the previous key group's"));
      }
    }
  }
  MESHVID_ASSIGN_OR_RETURN(const uint32_t gof_count, reader.ReadU32("gof_count"));
  if (gof_count != reader.remaining() / kIndexEntrySize ||
      reader.remaining() % kIndexEntrySize != 0) {
    return reader.Error("gof_count " + std::to_string(gof_count) + " does not match the " +
                        std::to_string(reader.remaining()) + " bytes of entries");
  }
  index.gofs.resize(gof_count);
  for (uint32_t k = 0; k < gof_count; ++k) {
    IndexEntry& entry = index.gofs[k];
    MESHVID_ASSIGN_OR_RETURN(entry.offset, reader.ReadU64("offset"));
    MESHVID_ASSIGN_OR_RETURN(entry.first_frame, reader.ReadU32("first_frame"));
    MESHVID_ASSIGN_OR_RETURN(entry.frame_count, reader.ReadU32("frame_count"));
    if (entry.frame_count == 0) {
      return reader.Error("entry " + std::to_string(k) + " has frame_count 0");
    }
    if (!FrameRangeFits(entry.first_frame, entry.frame_count)) {
      return reader.Error("entry " + std::to_string(k) + " first_frame " +
                          std::to_string(entry.first_frame) + " + frame_count " +
                          std::to_string(entry.frame_count) + " passes the last frame number");
    }
    if (k > 0) {
      const IndexEntry& previous = index.gofs[k - 1];
      if (entry.offset <= previous.offset) {
        return reader.Error("entry " + std::to_string(k) + " offset " +
                            std::to_string(entry.offset) + " is not after the previous entry's");
      }
      if (entry.first_frame != uint64_t{previous.first_frame} + previous.frame_count) {
        return reader.Error("entry " + std::to_string(k) + " first_frame " +
                            std::to_string(entry.first_frame) +
                            " does not follow the previous group's frames");
      }
    }
  }
  if (index.key_groups.size() > 1 && index.key_groups.back().first_gof >= gof_count) {
    return reader.Error("the last key group holds no group of frames");
  }
  return index;
}

std::vector<uint8_t> EncodeTrailerPayload(uint64_t index_offset) {
  ByteWriter writer;
  writer.PutU64(index_offset);
  return writer.Release();
}

StatusOr<uint64_t> DecodeTrailerPayload(std::span<const uint8_t> payload, std::string context) {
  ByteReader reader(payload, std::move(context));
  MESHVID_ASSIGN_OR_RETURN(const uint64_t index_offset, reader.ReadU64("index_offset"));
  if (reader.remaining() != 0) return reader.Error("trailer payload is not 8 bytes");
  return index_offset;
}

}  // namespace meshvid
