// Fuzz target: a whole .mvid through MvidDecoder, as `meshvid decode` and `info --check` use
// it: open (file path of a memory buffer), describe every key group, measure the streams,
// decode up to 16 frames at every stored level; then the same bytes as a stream.
// Invariants: clean errors; a decoded frame has the vertices and triangles info() promises
// for its level, and only finite positions.
#include <sstream>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

namespace {

/// Decodes frames [0, min(count, 16)) at every level; stops at the first error.
void DecodeSome(MvidDecoder& decoder, std::uint32_t count) {
  const MvidInfo& info = decoder.info();
  for (std::uint32_t frame = 0; frame < count && frame < 16; ++frame) {
    for (int level = 0; level <= info.levels; ++level) {
      StatusOr<TriangleMesh> mesh = decoder.DecodeFrame(frame, level);
      if (!mesh.ok()) {
        fuzz::ExpectCleanError(mesh.status());
        return;
      }
      for (const Eigen::Vector3f& p : mesh->positions) {
        if (!p.allFinite()) fuzz::Fail("a decoded position is not finite");
      }
      for (const Triangle& t : mesh->triangles) {
        if (t.maxCoeff() >= mesh->positions.size()) fuzz::Fail("a triangle index out of range");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  StatusOr<std::unique_ptr<MvidDecoder>> decoder =
      MvidDecoder::OpenMemory(std::vector<std::uint8_t>(data, data + size));
  if (!decoder.ok()) {
    fuzz::ExpectCleanError(decoder.status());
  } else {
    MvidDecoder& d = **decoder;
    const MvidInfo& info = d.info();
    if (info.vertices_per_level.size() != static_cast<std::size_t>(info.levels) + 1) {
      fuzz::Fail("vertices_per_level does not list every level");
    }
    fuzz::ExpectCleanError(d.MeasureStreams().status());
    for (std::uint32_t k = 0; k < info.key_groups.size() && k < 4; ++k) {
      StatusOr<MvidKeyGroupInfo> described = d.DescribeKeyGroup(k);
      fuzz::ExpectCleanError(described.status());
    }
    DecodeSome(d, info.frame_count);
    fuzz::ExpectCleanError(d.DecodeFrame(info.frame_count, 0).status());
  }
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  StatusOr<std::unique_ptr<MvidDecoder>> stream = MvidDecoder::OpenStream(in);
  if (!stream.ok()) {
    fuzz::ExpectCleanError(stream.status());
  } else {
    DecodeSome(**stream, 16);
  }
  return 0;
}
