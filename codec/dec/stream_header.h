// The checks every decoder (native and WebAssembly) makes of a container's HEAD before it
// decodes anything.
#ifndef MESHVID_CODEC_DEC_STREAM_HEADER_H_
#define MESHVID_CODEC_DEC_STREAM_HEADER_H_

#include <cstdint>
#include <string>

#include "codec/common/video_codec.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// The codec of `header`'s displacement video, after checking that the header declares the
/// streams meshvid writes: the 10-bit "displacement" stream, optionally followed by an 8-bit
/// "colour" stream of the same codec and picture size; of a codec it decodes, and a level
/// count the subdivision supports. kUnsupported / kCorrupt naming `name` otherwise.
StatusOr<VideoCodec> CheckStreamHeader(const ContainerHeader& header, const std::string& name);

/// True when a header that passed CheckStreamHeader declares a colour stream (stream 1).
bool HasColourStream(const ContainerHeader& header);

/// "partial file: only 8 of the 12 frames its header promises are readable" when `readable` <
/// `declared`, else "": the words every front end uses for a partial file.
std::string PartialFileText(std::uint64_t readable, std::uint32_t declared);

/// Ok when a file with `readable` of the `declared` frames can be decoded: at least one frame,
/// and all of them unless `allow_partial`; kCorrupt naming `name` otherwise, telling how to
/// read a partial file (`allow_hint`, e.g. "--allow-partial").
Status CheckReadableFrames(std::uint64_t readable, std::uint32_t declared, bool allow_partial,
                           const std::string& name, const std::string& allow_hint);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_STREAM_HEADER_H_
