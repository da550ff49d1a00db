// Point Cache 2 (.pc2): per-frame vertex positions of an animated mesh.
//   char[12] "POINTCACHE2\0" | int32 version (1) | int32 numPoints | float32 startFrame
//   float32 sampleRate | int32 numSamples | numSamples x numPoints x float32[3], little-endian
#ifndef MESHVID_TOOLS_IO_PC2_H_
#define MESHVID_TOOLS_IO_PC2_H_

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "format/output_file.h"
#include "format/status.h"

namespace meshvid {

/// The fixed header fields of a .pc2 file.
struct Pc2Header {
  std::int32_t version = 1;
  std::int32_t num_points = 0;
  float start_frame = 0;
  float sample_rate = 1;
  std::int32_t num_samples = 0;
};

/// Reads frames of a .pc2 file on demand (seeking; the file is never loaded whole).
/// Not thread-safe: use one reader per thread.
class Pc2Reader {
 public:
  /// Opens and checks the header and that the file is long enough for every sample.
  static StatusOr<std::unique_ptr<Pc2Reader>> Open(const std::string& path);
  const Pc2Header& header() const { return header_; }
  /// Positions of sample `index` (0-based), num_points of them. Fails on NaN/inf.
  StatusOr<std::vector<Eigen::Vector3f>> ReadFrame(int index);

 private:
  Pc2Reader() = default;
  std::string path_;
  std::ifstream in_;
  Pc2Header header_;
};

/// Writes a .pc2 file one frame at a time; Finish() patches numSamples in the header.
class Pc2Writer {
 public:
  static StatusOr<std::unique_ptr<Pc2Writer>> Create(const std::string& path,
                                                     std::int32_t num_points,
                                                     float start_frame = 0,
                                                     float sample_rate = 1);
  /// Appends one frame; `positions` must have num_points entries.
  Status AppendFrame(const std::vector<Eigen::Vector3f>& positions);
  /// Writes the final sample count and closes the file.
  Status Finish();

 private:
  Pc2Writer() = default;
  std::string path_;
  std::unique_ptr<OutputFile> out_;  ///< null once finished
  Pc2Header header_;
};

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_PC2_H_
