// Writes a .mvid's groups of frames over and over into one long file, copied chunk for chunk
// (format/container_copy.h): a file of many megabytes for the player's streaming test, made in
// a moment from a short encode. `meshvid concat` refuses this on purpose (the copies hold the
// same capture frames), so the test makes it here.
// Usage: repeat_mvid IN.mvid TIMES OUT.mvid
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "format/container_copy.h"
#include "format/container_reader.h"
#include "format/container_writer.h"

namespace {

int Fail(const meshvid::Status& status) {
  std::cerr << "repeat_mvid: " << status.ToString() << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace meshvid;
  const int times = argc == 4 ? std::atoi(argv[2]) : 0;
  if (times < 1) {
    std::cerr << "usage: repeat_mvid IN.mvid TIMES OUT.mvid\n";
    return 2;
  }
  StatusOr<ContainerReader> in = ContainerReader::OpenFile(argv[1]);
  if (!in.ok()) return Fail(in.status());
  if (Status whole = CheckWholeContainer(*in, argv[1]); !whole.ok()) return Fail(whole);
  ContainerHeader header = in->header();
  header.frame_count = static_cast<std::uint32_t>(in->frame_count() * times);
  header.metadata_json = "{\"repeated\":" + std::to_string(times) + "}";
  std::ofstream file(argv[3], std::ios::binary);
  ContainerWriter writer(OstreamSink(file, argv[3]));
  if (Status begun = writer.Begin(header); !begun.ok()) return Fail(begun);
  for (int i = 0; i < times; ++i) {
    if (Status copied = CopyGofs(*in, 0, in->gof_count(), writer); !copied.ok()) {
      return Fail(copied);
    }
  }
  if (Status finished = writer.Finish(); !finished.ok()) return Fail(finished);
  file.close();
  if (!file) {
    std::cerr << "repeat_mvid: cannot write " << argv[3] << "\n";
    return 1;
  }
  return 0;
}
