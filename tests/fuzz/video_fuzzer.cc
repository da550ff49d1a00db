// Fuzz target: the displacement video path: VideoDecoder::Create with a configuration record,
// then Decode of each packet and Flush, as MvidDecoder feeds a group. Input: u8 codec (HEVC,
// AV1, FFV1), u16 width, u16 height (1..512: a real picture size follows from the base mesh),
// u32 config_size and the configuration, then packets as u32 size + bytes (at most 64).
// Invariants: clean errors; every picture has the size asked for and 10-bit samples.
#include <vector>

#include "codec/common/video_codec.h"
#include "codec/dec/video_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FuzzInput input(data, size);
  static constexpr VideoCodec kCodecs[] = {VideoCodec::kHevc, VideoCodec::kAv1, VideoCodec::kFfv1};
  const VideoCodec codec = kCodecs[input.U8() % 3];
  const int width = 1 + input.U16() % 512;
  const int height = 1 + input.U16() % 512;
  const std::span<const std::uint8_t> config = input.Bytes(input.U32());
  StatusOr<std::unique_ptr<VideoDecoder>> decoder =
      VideoDecoder::Create(codec, width, height, config, 1);
  if (!decoder.ok()) {
    fuzz::ExpectCleanError(decoder.status());
    return 0;
  }
  std::vector<GreyPicture> pictures;
  VideoPacket packet;
  for (int p = 0; p < 64 && input.remaining() > 0; ++p) {
    const std::span<const std::uint8_t> bytes = input.Bytes(input.U32());
    packet.data.assign(bytes.begin(), bytes.end());
    packet.pts = packet.dts = p;
    packet.keyframe = p == 0 || codec == VideoCodec::kFfv1;
    const Status status = (*decoder)->Decode(packet, &pictures);
    fuzz::ExpectCleanError(status);
    if (!status.ok()) return 0;
  }
  fuzz::ExpectCleanError((*decoder)->Flush(&pictures));
  for (const GreyPicture& picture : pictures) {
    if (picture.width != width || picture.height != height ||
        picture.samples.size() != static_cast<std::size_t>(width) * height) {
      fuzz::Fail("a picture of the wrong size");
    }
  }
  return 0;
}
