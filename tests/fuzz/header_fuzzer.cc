// Fuzz target: the HEAD payload (frame rate, counts, the stream table, metadata) as the
// container and the decoder read it. Invariants: clean errors; a decoded header passes
// CheckHeader and re-encodes to the same bytes.
#include <algorithm>
#include <string>
#include <vector>

#include "format/payloads.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> payload(data, size);
  StatusOr<ContainerHeader> header = DecodeHeaderPayload(payload, "HEAD");
  if (!header.ok()) {
    fuzz::ExpectCleanError(header.status());
    return 0;
  }
  if (!CheckHeader(*header).ok()) fuzz::Fail("a decoded header fails CheckHeader");
  const std::vector<std::uint8_t> encoded = EncodeHeaderPayload(*header);
  if (!std::equal(encoded.begin(), encoded.end(), payload.begin(), payload.end())) {
    fuzz::Fail("HEAD does not re-encode to its bytes");
  }
  return 0;
}
