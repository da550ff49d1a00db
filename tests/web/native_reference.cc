// Writes what the native decoder makes of a .mvid, for the WebAssembly decoder's test
// (decoder_test.mjs) to compare against: every frame's displacement picture (which the test
// hands the WebAssembly decoder in place of the browser's video decoder) and its positions and
// triangles at every level. Little-endian:
//   u32 frame_count | u32 levels | per frame: u32 key_group | u32 width | u32 height |
//   u16 samples[width * height] | per level: u32 vertices | f32 xyz[3 * vertices] |
//   u32 triangles | u32 corners[3 * triangles]
// Usage: native_reference IN.mvid OUT.bin
#include <bit>
#include <fstream>
#include <iostream>
#include <memory>

#include "codec/dec/mvid_decoder.h"
#include "format/byte_io.h"

namespace {

int Fail(const meshvid::Status& status) {
  std::cerr << "native_reference: " << status.ToString() << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace meshvid;
  if (argc != 3) {
    std::cerr << "usage: native_reference IN.mvid OUT.bin\n";
    return 2;
  }
  StatusOr<std::unique_ptr<MvidDecoder>> opened = MvidDecoder::OpenFile(argv[1]);
  if (!opened.ok()) return Fail(opened.status());
  MvidDecoder& decoder = **opened;
  const MvidInfo& info = decoder.info();
  ByteWriter out;
  out.PutU32(info.frame_count);
  out.PutU32(static_cast<std::uint32_t>(info.levels));
  for (std::uint32_t t = 0; t < info.frame_count; ++t) {
    StatusOr<std::uint32_t> key_group = decoder.KeyGroupOf(t);
    if (!key_group.ok()) return Fail(key_group.status());
    StatusOr<const GreyPicture*> picture = decoder.DisplacementPicture(t);
    if (!picture.ok()) return Fail(picture.status());
    out.PutU32(*key_group);
    out.PutU32(static_cast<std::uint32_t>((*picture)->width));
    out.PutU32(static_cast<std::uint32_t>((*picture)->height));
    for (std::uint16_t sample : (*picture)->samples) out.PutU16(sample);
    for (int level = 0; level <= info.levels; ++level) {
      StatusOr<TriangleMesh> frame = decoder.DecodeFrame(t, level);
      if (!frame.ok()) return Fail(frame.status());
      out.PutU32(static_cast<std::uint32_t>(frame->vertex_count()));
      for (const Eigen::Vector3f& p : frame->positions) {
        for (int c = 0; c < 3; ++c) out.PutU32(std::bit_cast<std::uint32_t>(p[c]));
      }
      out.PutU32(static_cast<std::uint32_t>(frame->triangle_count()));
      for (const Triangle& triangle : frame->triangles) {
        for (int c = 0; c < 3; ++c) out.PutU32(triangle[c]);
      }
    }
  }
  std::ofstream file(argv[2], std::ios::binary);
  const std::vector<std::uint8_t>& bytes = out.bytes();
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!file) {
    std::cerr << "native_reference: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
