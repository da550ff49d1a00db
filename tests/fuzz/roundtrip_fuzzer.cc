// Fuzz target: the writer and the decoder together. The input picks a small sequence: a
// base mesh (an 18- or 66-vertex sphere in two blended segments), 1-8 frames in groups of
// 1-4, 0-2 levels, one or two key groups, FFV1 (lossless, fast); then per frame the two
// segments' motion and the displacement samples. It is encoded with MvidWriter and decoded
// with MvidDecoder from memory and as a stream. HEVC is left out: x265 refuses pictures as
// small as these bases give (avcodec_open2: Invalid argument, an internal error of the
// writer; noted in bench/FUZZ.md).
// Invariants: encoding succeeds; the decoder reads every frame, in the key group it was
// written to, with the vertices and triangles of its level and finite positions; FFV1
// displacements come back within one quantisation step.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/mvid_writer.h"
#include "tests/analytic_mvid.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

namespace {

/// A small rigid motion from 6 input bytes: up to ~0.25 rad and ~0.1 units.
RigidTransform MotionFrom(fuzz::FuzzInput& input) {
  Eigen::Vector3f axis_angle, translation;
  for (int c = 0; c < 3; ++c) axis_angle[c] = (input.U8() - 128) / 512.0f;
  for (int c = 0; c < 3; ++c) translation[c] = (input.U8() - 128) / 1280.0f;
  RigidTransform t;
  const float angle = axis_angle.norm();
  if (angle > 0) t.rotation = Eigen::AngleAxisf(angle, axis_angle / angle);
  t.translation = translation;
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FuzzInput input(data, size);
  const std::uint8_t shape = input.U8();
  const int frames = 1 + input.U8() % 8;
  MvidWriterSettings settings;
  settings.gof_size = 1 + input.U8() % 4;
  settings.levels = input.U8() % 3;
  input.U8();  // reserved: the codec (FFV1 only, see the top)
  settings.codec = VideoCodec::kFfv1;
  settings.threads = 1;
  // A second key group (a different base) from this frame on, if any.
  const int second_key_group = frames > 1 && (shape & 2) ? 1 + input.U8() % (frames - 1) : frames;
  const TriangleMesh bases[2] = {testing::SphereMesh(shape & 1), testing::LatLongSphere(3, 5)};

  std::vector<std::uint8_t> bytes;
  std::unique_ptr<MvidWriter> writer;
  std::vector<std::vector<float>> written;  // every frame's displacements, as written
  for (int k = 0; k < (second_key_group < frames ? 2 : 1); ++k) {
    const TriangleMesh& base = bases[k];
    if (k == 0) {
      StatusOr<std::unique_ptr<MvidWriter>> created = MvidWriter::Create(
          [&bytes](std::span<const std::uint8_t> b) {
            bytes.insert(bytes.end(), b.begin(), b.end());
            return Status::Ok();
          },
          base, testing::TwoSegments(base), settings);
      if (!created.ok()) fuzz::Fail("cannot create the writer: " + created.status().ToString());
      writer = std::move(*created);
    } else if (!writer->StartKeyGroup(base, testing::TwoSegments(base)).ok()) {
      fuzz::Fail("cannot start a key group");
    }
    const int first = k == 0 ? 0 : second_key_group;
    const int end = k == 0 ? second_key_group : frames;
    const std::size_t samples = writer->subdivision().samples().size();
    for (int group = first; group < end; group += settings.gof_size) {
      std::vector<std::vector<RigidTransform>> transforms;
      std::vector<std::vector<float>> displacements;
      for (int f = group; f < std::min(end, group + settings.gof_size); ++f) {
        transforms.push_back({MotionFrom(input), MotionFrom(input)});
        std::vector<float>& field = displacements.emplace_back(samples);
        const std::span<const std::uint8_t> detail = input.Bytes(16);
        for (std::size_t s = 0; s < samples; ++s) {
          field[s] = detail.empty() ? 0.0f : (detail[s % detail.size()] - 128) / 6400.0f;
        }
        written.push_back(field);
      }
      const Status status = writer->WriteGroup(transforms, displacements);
      if (!status.ok()) fuzz::Fail("cannot write a group: " + status.ToString());
    }
  }
  if (!writer->Finish().ok()) fuzz::Fail("cannot finish the file");

  StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenMemory(bytes);
  if (!decoder.ok()) fuzz::Fail("the file does not open: " + decoder.status().ToString());
  MvidDecoder& d = **decoder;
  if (d.info().frame_count != static_cast<std::uint32_t>(frames)) fuzz::Fail("frame count");
  std::vector<float> displacements;
  for (int f = 0; f < frames; ++f) {
    StatusOr<std::uint32_t> key_group = d.KeyGroupOf(f);
    if (!key_group.ok() || *key_group != (f < second_key_group ? 0u : 1u)) {
      fuzz::Fail("a frame in the wrong key group");
    }
    for (int level = 0; level <= settings.levels; ++level) {
      StatusOr<TriangleMesh> mesh = d.DecodeFrame(f, level);
      if (!mesh.ok()) fuzz::Fail("a frame does not decode: " + mesh.status().ToString());
      if (!ValidateMesh(*mesh, "decoded").ok()) fuzz::Fail("a decoded frame is not valid");
      // info() describes key group 0.
      if (f < second_key_group &&
          (mesh->positions.size() != d.info().vertices_per_level[level] ||
           mesh->triangles.size() != d.info().triangles_per_level[level])) {
        fuzz::Fail("a decoded frame's size differs from info()");
      }
    }
    if (!d.DecodeDisplacements(f, &displacements).ok()) fuzz::Fail("displacements");
    if (settings.codec == VideoCodec::kFfv1) {
      const std::vector<float>& expected = written[f];
      // 10 bits over a group's range, which lies within [-largest, largest]: one step is at
      // most 2 * largest / 1023.
      float largest = 0;
      for (const std::vector<float>& field : written) {
        for (float v : field) largest = std::max(largest, std::abs(v));
      }
      const float tolerance = 2 * largest / 1023 + 1e-6f;
      for (std::size_t s = 0; s < expected.size() && s < displacements.size(); ++s) {
        if (std::abs(displacements[s] - expected[s]) > tolerance) {
          fuzz::Fail("an FFV1 displacement off by more than a quantisation step");
        }
      }
    }
  }
  std::istringstream in(std::string(bytes.begin(), bytes.end()));
  StatusOr<std::unique_ptr<MvidDecoder>> stream = MvidDecoder::OpenStream(in);
  if (!stream.ok()) fuzz::Fail("the file does not open as a stream");
  for (int f = 0; f < frames; ++f) {
    if (!(*stream)->DecodeFrame(f, settings.levels).ok()) fuzz::Fail("a streamed frame");
  }
  return 0;
}
