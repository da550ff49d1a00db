#include "format/container_writer.h"

#include "format/chunk.h"

namespace meshvid {

ByteSink OstreamSink(std::ostream& out, std::string name) {
  return [&out, name = std::move(name)](std::span<const uint8_t> bytes) -> Status {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) return IoError(name + ": write failed (disk full or closed pipe?)");
    return Status::Ok();
  };
}

Status ContainerWriter::Misuse(const std::string& problem) {
  return InvalidArgumentError("ContainerWriter: " + problem);
}

Status ContainerWriter::Emit(std::span<const uint8_t> bytes) {
  Status status = sink_(bytes);
  if (!status.ok()) {
    state_ = State::kFailed;
    return status;
  }
  offset_ += bytes.size();
  return Status::Ok();
}

Status ContainerWriter::EmitChunk(uint32_t type, std::span<const uint8_t> payload) {
  return Emit(EncodeChunk(type, 0, payload));
}

Status ContainerWriter::Begin(const ContainerHeader& header) {
  if (state_ != State::kNew) return Misuse("Begin called twice or after an error");
  MESHVID_RETURN_IF_ERROR(CheckHeader(header));
  header_ = header;
  MESHVID_RETURN_IF_ERROR(Emit(EncodePreamble()));
  MESHVID_RETURN_IF_ERROR(EmitChunk(kChunkHead, EncodeHeaderPayload(header)));
  state_ = State::kBegun;
  return Status::Ok();
}

Status ContainerWriter::WriteKeyGroupChunk(uint32_t type, std::span<const uint8_t> payload) {
  const std::string name = type == kChunkBase ? "WriteBase" : "WriteMotion";
  if (state_ != State::kBegun && state_ != State::kGofs) {
    return Misuse(name + " must come after Begin and before Finish");
  }
  const Status order = key_groups_.AddBaseOrMotion(type == kChunkBase, offset_, name);
  if (!order.ok()) return Misuse(order.message());
  index_.key_groups = key_groups_.key_groups();
  return EmitChunk(type, payload);
}

Status ContainerWriter::WriteBase(std::span<const uint8_t> base_mesh) {
  return WriteKeyGroupChunk(kChunkBase, base_mesh);
}

Status ContainerWriter::WriteMotion(std::span<const uint8_t> motion) {
  return WriteKeyGroupChunk(kChunkMotion, motion);
}

Status ContainerWriter::WriteGof(const GroupOfFrames& gof) {
  if (state_ != State::kBegun && state_ != State::kGofs) {
    return Misuse("WriteGof must come after Begin and before Finish");
  }
  const std::string which = "GOF " + std::to_string(index_.gofs.size());
  if (gof.gof_index != index_.gofs.size()) {
    return Misuse(which + " has gof_index " + std::to_string(gof.gof_index));
  }
  if (gof.first_frame != frames_written_) {
    return Misuse(which + " first_frame " + std::to_string(gof.first_frame) +
                  " should be " + std::to_string(frames_written_));
  }
  if (gof.frame_count == 0) return Misuse(which + " has no frames");
  if (gof.packets.size() != header_.streams.size()) {
    return Misuse(which + " has " + std::to_string(gof.packets.size()) +
                  " packet lists for " + std::to_string(header_.streams.size()) + " streams");
  }
  if (gof.transforms.size() > UINT32_MAX) return Misuse(which + " transforms exceed 4 GiB");
  for (const auto& stream_packets : gof.packets) {
    if (stream_packets.size() > UINT32_MAX) return Misuse(which + " has too many packets");
    for (const auto& packet : stream_packets) {
      if (packet.size() > UINT32_MAX) return Misuse(which + " has a packet over 4 GiB");
    }
  }
  if (frames_written_ + gof.frame_count > UINT32_MAX) return Misuse("more than 2^32 frames");
  index_.gofs.push_back({offset_, gof.first_frame, gof.frame_count});
  key_groups_.AddGof();
  index_.key_groups = key_groups_.key_groups();
  frames_written_ += gof.frame_count;
  state_ = State::kGofs;
  return EmitChunk(kChunkGof, EncodeGofPayload(gof));
}

Status ContainerWriter::Finish() {
  if (state_ != State::kBegun && state_ != State::kGofs) {
    return Misuse("Finish must come after Begin, once");
  }
  if (header_.frame_count != 0 && header_.frame_count != frames_written_) {
    state_ = State::kFailed;
    return Misuse("the header declared frame_count " + std::to_string(header_.frame_count) +
                  " but " + std::to_string(frames_written_) + " frames were written");
  }
  index_.key_groups = key_groups_.key_groups();
  if (index_.key_groups.size() > 1 && index_.key_groups.back().first_gof >= index_.gofs.size()) {
    state_ = State::kFailed;
    return Misuse("the last key group has no group of frames");
  }
  const uint64_t index_offset = offset_;
  MESHVID_ASSIGN_OR_RETURN(const std::vector<uint8_t> index,
                           EncodeIndexPayload(index_, kMvidFormatVersion));
  MESHVID_RETURN_IF_ERROR(EmitChunk(kChunkIndex, index));
  MESHVID_RETURN_IF_ERROR(EmitChunk(kChunkTrailer, EncodeTrailerPayload(index_offset)));
  state_ = State::kFinished;
  return Status::Ok();
}

}  // namespace meshvid
