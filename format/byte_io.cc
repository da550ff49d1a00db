#include "format/byte_io.h"

#include <cstring>

namespace meshvid {

uint32_t LoadLittleEndianU32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

uint64_t LoadLittleEndianU64(const uint8_t* p) {
  return static_cast<uint64_t>(LoadLittleEndianU32(p)) |
         static_cast<uint64_t>(LoadLittleEndianU32(p + 4)) << 32;
}

Status ByteReader::Error(std::string_view problem) const {
  return CorruptError(context_ + ": " + std::string(problem));
}

Status ByteReader::Need(uint64_t size, std::string_view what) const {
  if (size <= remaining()) return Status::Ok();
  return Error("truncated " + std::string(what) + ": needs " + std::to_string(size) +
               " bytes at offset " + std::to_string(position_) + " but only " +
               std::to_string(remaining()) + " remain");
}

StatusOr<uint8_t> ByteReader::ReadU8(std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(1, what));
  return data_[position_++];
}

StatusOr<uint16_t> ByteReader::ReadU16(std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(2, what));
  const uint8_t* p = data_.data() + position_;
  position_ += 2;
  return static_cast<uint16_t>(p[0] | p[1] << 8);
}

StatusOr<uint32_t> ByteReader::ReadU32(std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(4, what));
  const uint32_t value = LoadLittleEndianU32(data_.data() + position_);
  position_ += 4;
  return value;
}

StatusOr<uint64_t> ByteReader::ReadU64(std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(8, what));
  const uint64_t value = LoadLittleEndianU64(data_.data() + position_);
  position_ += 8;
  return value;
}

StatusOr<std::span<const uint8_t>> ByteReader::ReadBytes(uint64_t size, std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(size, what));
  std::span<const uint8_t> view = data_.subspan(position_, static_cast<size_t>(size));
  position_ += static_cast<size_t>(size);
  return view;
}

StatusOr<std::string> ByteReader::ReadSizedString(uint64_t max_size, std::string_view what) {
  MESHVID_ASSIGN_OR_RETURN(const uint32_t size, ReadU32(std::string(what) + " size"));
  if (size > max_size) {
    return Error(std::string(what) + " size " + std::to_string(size) + " exceeds the limit of " +
                 std::to_string(max_size) + " bytes");
  }
  MESHVID_ASSIGN_OR_RETURN(const auto bytes, ReadBytes(size, what));
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

Status ByteReader::Skip(uint64_t size, std::string_view what) {
  MESHVID_RETURN_IF_ERROR(Need(size, what));
  position_ += static_cast<size_t>(size);
  return Status::Ok();
}

void ByteWriter::PutU16(uint16_t value) {
  PutU8(static_cast<uint8_t>(value));
  PutU8(static_cast<uint8_t>(value >> 8));
}

void ByteWriter::PutU32(uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) PutU8(static_cast<uint8_t>(value >> shift));
}

void ByteWriter::PutU64(uint64_t value) {
  for (int shift = 0; shift < 64; shift += 8) PutU8(static_cast<uint8_t>(value >> shift));
}

void ByteWriter::PutBytes(std::span<const uint8_t> bytes) {
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
}

void ByteWriter::PutFourcc(std::string_view fourcc) {
  for (size_t i = 0; i < 4; ++i) PutU8(i < fourcc.size() ? static_cast<uint8_t>(fourcc[i]) : ' ');
}

void ByteWriter::PutSizedString(std::string_view text) {
  PutU32(static_cast<uint32_t>(text.size()));
  PutBytes(AsBytes(text));
}

void ByteWriter::PatchU32(size_t offset, uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes_.at(offset + i) = static_cast<uint8_t>(value >> (8 * i));
}

}  // namespace meshvid
