// The checks every decoder (native and WebAssembly) makes of a container's HEAD before it
// decodes anything.
#ifndef MESHVID_CODEC_DEC_STREAM_HEADER_H_
#define MESHVID_CODEC_DEC_STREAM_HEADER_H_

#include <string>

#include "codec/common/video_codec.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// The codec of `header`'s displacement video, after checking that the header declares the one
/// 10-bit "displacement" stream meshvid writes, of a codec it decodes, and a level count the
/// subdivision supports. kUnsupported / kCorrupt naming `name` otherwise.
StatusOr<VideoCodec> CheckStreamHeader(const ContainerHeader& header, const std::string& name);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_STREAM_HEADER_H_
