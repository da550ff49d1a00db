#include "tools/io/pc2.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

namespace meshvid {
namespace {

constexpr char kMagic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::size_t kHeaderBytes = 32;
constexpr std::size_t kNumSamplesOffset = 28;

template <typename T>
T LoadLittleEndian(const char* p) {
  static_assert(sizeof(T) == 4);
  char bytes[4];
  std::memcpy(bytes, p, 4);
  if constexpr (std::endian::native == std::endian::big) {
    std::swap(bytes[0], bytes[3]);
    std::swap(bytes[1], bytes[2]);
  }
  T value;
  std::memcpy(&value, bytes, 4);
  return value;
}

template <typename T>
void StoreLittleEndian(T value, char* p) {
  static_assert(sizeof(T) == 4);
  std::memcpy(p, &value, 4);
  if constexpr (std::endian::native == std::endian::big) {
    std::swap(p[0], p[3]);
    std::swap(p[1], p[2]);
  }
}

}  // namespace

StatusOr<std::unique_ptr<Pc2Reader>> Pc2Reader::Open(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) {
    if (!std::filesystem::exists(path)) return NotFoundError(path + ": no such file");
    return IoError(path + ": cannot read the file size: " + ec.message());
  }
  std::unique_ptr<Pc2Reader> reader(new Pc2Reader());
  reader->path_ = path;
  reader->in_.open(path, std::ios::binary);
  if (!reader->in_) return IoError(path + ": cannot open for reading (permissions?)");
  char bytes[kHeaderBytes];
  if (file_size < kHeaderBytes || !reader->in_.read(bytes, kHeaderBytes)) {
    return CorruptError(path + ": not a PC2 file (shorter than the 32-byte header)");
  }
  if (std::memcmp(bytes, kMagic, sizeof(kMagic)) != 0) {
    return CorruptError(path + ": not a PC2 file (missing the POINTCACHE2 signature)");
  }
  Pc2Header& h = reader->header_;
  h.version = LoadLittleEndian<std::int32_t>(bytes + 12);
  h.num_points = LoadLittleEndian<std::int32_t>(bytes + 16);
  h.start_frame = LoadLittleEndian<float>(bytes + 20);
  h.sample_rate = LoadLittleEndian<float>(bytes + 24);
  h.num_samples = LoadLittleEndian<std::int32_t>(bytes + kNumSamplesOffset);
  if (h.version != 1) {
    return CorruptError(path + ": unsupported PC2 version " + std::to_string(h.version) +
                        " (only version 1 exists)");
  }
  if (h.num_points < 1) {
    return CorruptError(path + ": PC2 header has numPoints = " + std::to_string(h.num_points) +
                        " (must be at least 1)");
  }
  if (h.num_samples < 0) {
    return CorruptError(path + ": PC2 header has numSamples = " + std::to_string(h.num_samples) +
                        " (must not be negative)");
  }
  const std::uint64_t needed = kHeaderBytes + static_cast<std::uint64_t>(h.num_samples) *
                                                  static_cast<std::uint64_t>(h.num_points) * 12;
  if (file_size < needed) {
    return CorruptError(path + ": truncated PC2 file: " + std::to_string(h.num_samples) +
                        " samples of " + std::to_string(h.num_points) + " points need " +
                        std::to_string(needed) + " bytes, the file has " +
                        std::to_string(file_size));
  }
  return reader;
}

StatusOr<std::vector<Eigen::Vector3f>> Pc2Reader::ReadFrame(int index) {
  if (index < 0 || index >= header_.num_samples) {
    return InvalidArgumentError(path_ + ": frame " + std::to_string(index) +
                                " out of range (the file has " +
                                std::to_string(header_.num_samples) + " samples)");
  }
  const std::size_t points = static_cast<std::size_t>(header_.num_points);
  const std::uint64_t offset = kHeaderBytes + static_cast<std::uint64_t>(index) * points * 12;
  std::vector<char> bytes(points * 12);
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  if (!in_.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    return IoError(path_ + ": failed to read frame " + std::to_string(index) +
                   " (file changed or read error)");
  }
  std::vector<Eigen::Vector3f> positions(points);
  const char* p = bytes.data();
  for (std::size_t i = 0; i < points; ++i) {
    for (int c = 0; c < 3; ++c, p += 4) positions[i][c] = LoadLittleEndian<float>(p);
    if (!positions[i].allFinite()) {
      return CorruptError(path_ + ": frame " + std::to_string(index) + " point " +
                          std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  return positions;
}

StatusOr<std::unique_ptr<Pc2Writer>> Pc2Writer::Create(const std::string& path,
                                                       std::int32_t num_points,
                                                       float start_frame, float sample_rate) {
  if (num_points < 1) {
    return InvalidArgumentError(path + ": a PC2 file needs at least 1 point, got " +
                                std::to_string(num_points));
  }
  std::unique_ptr<Pc2Writer> writer(new Pc2Writer());
  writer->path_ = path;
  writer->header_.num_points = num_points;
  writer->header_.start_frame = start_frame;
  writer->header_.sample_rate = sample_rate;
  writer->header_.num_samples = 0;
  MESHVID_ASSIGN_OR_RETURN(writer->out_, OutputFile::Open(path));
  char bytes[kHeaderBytes];
  std::memcpy(bytes, kMagic, sizeof(kMagic));
  StoreLittleEndian(writer->header_.version, bytes + 12);
  StoreLittleEndian(num_points, bytes + 16);
  StoreLittleEndian(start_frame, bytes + 20);
  StoreLittleEndian(sample_rate, bytes + 24);
  StoreLittleEndian(std::int32_t{0}, bytes + kNumSamplesOffset);
  if (!writer->out_->stream().write(bytes, kHeaderBytes)) return IoError(path + ": header write failed");
  return writer;
}

Status Pc2Writer::AppendFrame(const std::vector<Eigen::Vector3f>& positions) {
  if (!out_) return InvalidArgumentError(path_ + ": AppendFrame after Finish");
  if (positions.size() != static_cast<std::size_t>(header_.num_points)) {
    return InvalidArgumentError(path_ + ": frame has " + std::to_string(positions.size()) +
                                " points, the PC2 file has " +
                                std::to_string(header_.num_points));
  }
  if (header_.num_samples == std::numeric_limits<std::int32_t>::max()) {
    return InvalidArgumentError(path_ + ": too many frames for a PC2 file");
  }
  std::vector<char> bytes(positions.size() * 12);
  char* p = bytes.data();
  for (const Eigen::Vector3f& v : positions) {
    for (int c = 0; c < 3; ++c, p += 4) StoreLittleEndian(v[c], p);
  }
  if (!out_->stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    return IoError(path_ + ": write failed (disk full?)");
  }
  ++header_.num_samples;
  return Status::Ok();
}

Status Pc2Writer::Finish() {
  if (!out_) return InvalidArgumentError(path_ + ": Finish called twice");
  char bytes[4];
  StoreLittleEndian(header_.num_samples, bytes);
  out_->stream().seekp(static_cast<std::streamoff>(kNumSamplesOffset));
  out_->stream().write(bytes, 4);
  const Status committed = out_->Commit();
  out_.reset();
  return committed;
}

}  // namespace meshvid
