// `meshvid concat` and `meshvid cut`: .mvid files joined and cut without re-encoding. Chunks are
// copied as they are (format/container_copy.h); only the header, the groups' numbering and the
// index are written anew. A long capture encoded in pieces (`meshvid encode --frames A:B`, on
// many machines) is joined into one file; a file is cut to the groups of frames that hold a
// range.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/progress.h"
#include "codec/dec/mvid_decoder.h"
#include "format/container_copy.h"
#include "format/container_reader.h"
#include "format/container_writer.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"

namespace meshvid::cli {
namespace {

/// The capture frames [first, end) a file holds, and the capture's name.
struct CaptureFrames {
  std::string capture;
  std::int64_t first = 0;
  std::int64_t end = 0;
};

/// What a file's metadata says of its capture frames (`meshvid encode` writes them as
/// "capture_frames"); nullopt when it says nothing.
std::optional<CaptureFrames> CaptureFramesOf(const nlohmann::json& metadata) {
  if (!metadata.is_object()) return std::nullopt;
  const auto frames = metadata.find("capture_frames");
  if (frames == metadata.end() || !frames->is_array() || frames->size() != 2 ||
      !(*frames)[0].is_number_integer() || !(*frames)[1].is_number_integer()) {
    return std::nullopt;
  }
  CaptureFrames range;
  range.first = (*frames)[0].get<std::int64_t>();
  range.end = (*frames)[1].get<std::int64_t>();
  const auto capture = metadata.find("capture");
  if (capture != metadata.end() && capture->is_string())
    range.capture = capture->get<std::string>();
  return range;
}

/// A header's metadata as JSON (an object; a text that is not one is kept under "text").
nlohmann::json MetadataOf(const ContainerHeader& header) {
  if (header.metadata_json.empty()) return nlohmann::json::object();
  nlohmann::json parsed = nlohmann::json::parse(header.metadata_json, nullptr, false);
  if (parsed.is_discarded() || !parsed.is_object()) return {{"text", header.metadata_json}};
  return parsed;
}

/// Opens a .mvid to copy from: the whole file, or an error naming it.
StatusOr<ContainerReader> OpenWhole(const std::string& path) {
  StatusOr<ContainerReader> reader = ContainerReader::OpenFile(path);
  if (!reader.ok()) return reader.status();
  MESHVID_RETURN_IF_ERROR(CheckWholeContainer(*reader, path));
  return reader;
}

/// Writes `header` and then what `copy` appends to `path`, atomically; returns the bytes.
template <typename Copy>
StatusOr<std::uint64_t> WriteContainer(const std::string& path, const ContainerHeader& header,
                                       const Copy& copy) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> file, OutputFile::Open(path));
  ContainerWriter writer(OstreamSink(file->stream(), path));
  MESHVID_RETURN_IF_ERROR(writer.Begin(header));
  MESHVID_RETURN_IF_ERROR(copy(writer));
  MESHVID_RETURN_IF_ERROR(writer.Finish());
  const std::uint64_t bytes = writer.bytes_written();
  MESHVID_RETURN_IF_ERROR(file->Commit());
  return bytes;
}

struct ConcatArguments {
  std::vector<std::string> inputs;
  std::string output;
  bool quiet = false;
};

/// The joined file's metadata: the first file's, its capture frames running to the last
/// file's end. Files that say which capture frames they hold must follow each other.
StatusOr<std::string> JoinedMetadata(const ConcatArguments& args,
                                     const std::vector<ContainerReader>& readers) {
  nlohmann::json joined = MetadataOf(readers.front().header());
  const std::optional<CaptureFrames> first = CaptureFramesOf(joined);
  std::optional<CaptureFrames> previous = first;
  bool every_file_says = first.has_value();
  for (std::size_t i = 1; i < readers.size(); ++i) {
    const std::optional<CaptureFrames> next = CaptureFramesOf(MetadataOf(readers[i].header()));
    every_file_says = every_file_says && next.has_value();
    if (!every_file_says) break;
    const std::string& name = args.inputs[i];
    if (next->capture != previous->capture) {
      return InvalidArgumentError(name + ": encoded from capture '" + next->capture + "', " +
                                  args.inputs[i - 1] + " from '" + previous->capture + "'");
    }
    if (next->first != previous->end) {
      const std::string what = next->first > previous->end ? "a gap" : "an overlap";
      return InvalidArgumentError(name + ": holds capture frames " + std::to_string(next->first) +
                                  ":" + std::to_string(next->end) + ", but " + args.inputs[i - 1] +
                                  " ends at frame " + std::to_string(previous->end) + " (" + what +
                                  "); give the files in frame order");
    }
    previous = next;
  }
  if (every_file_says) {
    joined["capture_frames"] = {first->first, previous->end};
    return DumpJson(joined);
  }
  std::fprintf(stderr,
               "meshvid: warning: not every file says which capture frames it holds; they are "
               "joined in the order given, unchecked\n");
  if (!joined.contains("capture_frames")) return readers.front().header().metadata_json;
  joined.erase("capture_frames");  // the joined file's range is not known
  return DumpJson(joined);
}

int RunConcat(const ConcatArguments& args) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<ContainerReader> readers;
  std::uint64_t frames = 0, input_bytes = 0;
  for (const std::string& path : args.inputs) {
    StatusOr<ContainerReader> reader = OpenWhole(path);
    if (!reader.ok()) return ReportError(reader.status());
    if (!readers.empty()) {
      const Status joinable = CheckJoinable(readers.front().header(), reader->header(), path);
      if (!joinable.ok()) return ReportError(joinable);
    }
    frames += reader->frame_count();
    input_bytes += reader->source().size();
    readers.push_back(*std::move(reader));
  }
  if (frames > UINT32_MAX) return ReportError(InvalidArgumentError("more than 2^32 frames"));
  StatusOr<std::string> metadata = JoinedMetadata(args, readers);
  if (!metadata.ok()) return ReportError(metadata.status());
  ContainerHeader header = readers.front().header();
  header.frame_count = static_cast<std::uint32_t>(frames);
  header.metadata_json = *metadata;
  std::size_t key_groups = 0;
  StatusOr<std::uint64_t> written =
      WriteContainer(args.output, header, [&](ContainerWriter& writer) -> Status {
        for (std::size_t i = 0; i < readers.size(); ++i) {
          MESHVID_RETURN_IF_ERROR(
              CopyGofs(readers[i], 0, readers[i].gof_count(), writer).WithContext(args.inputs[i]));
          key_groups += readers[i].key_groups().size();
        }
        return Status::Ok();
      });
  if (!written.ok()) return ReportError(written.status().WithContext("-o " + args.output));
  if (!args.quiet) {
    const double seconds = SecondsSince(start);
    std::fprintf(stderr, "Joined %s into %s: %s, %s, %s (%.0f MB/s)\n",
                 Count(readers.size(), "file").c_str(), args.output.c_str(),
                 Count(frames, "frame").c_str(), Count(key_groups, "key group").c_str(),
                 Kilobytes(double(*written)).c_str(),
                 seconds > 0 ? double(input_bytes) / seconds / 1e6 : 0.0);
  }
  return 0;
}

struct CutArguments {
  std::string input;
  std::string frames;
  std::string output;
  bool quiet = false;
};

int RunCut(const CutArguments& args) {
  StatusOr<ContainerReader> reader = OpenWhole(args.input);
  if (!reader.ok()) return ReportError(reader.status());
  StatusOr<std::pair<int, int>> range =
      FramesOption(args.frames, static_cast<int>(reader->frame_count()));
  if (!range.ok()) return ReportError(range.status());
  const auto [first, end] = *range;
  StatusOr<std::size_t> first_gof = reader->FindGof(static_cast<std::uint64_t>(first));
  StatusOr<std::size_t> last_gof = reader->FindGof(static_cast<std::uint64_t>(end - 1));
  if (!first_gof.ok()) return ReportError(first_gof.status());
  if (!last_gof.ok()) return ReportError(last_gof.status());
  const std::size_t end_gof = *last_gof + 1;
  const IndexEntry& from = reader->gofs()[*first_gof];
  const IndexEntry& to = reader->gofs()[*last_gof];
  const std::uint32_t kept_first = from.first_frame, kept_end = to.first_frame + to.frame_count;
  ContainerHeader header = reader->header();
  header.frame_count = kept_end - kept_first;
  // HEAD's picture size is the first key group's: the cut's, when it starts in a later one.
  // Every stream has it (the displacements', and the colour's where there is one).
  if (reader->KeyGroupOfGof(*first_gof) != 0) {
    StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenFile(args.input);
    if (!decoder.ok()) return ReportError(decoder.status());
    StatusOr<std::pair<int, int>> size = (*decoder)->PictureSizeOf(kept_first);
    if (!size.ok()) return ReportError(size.status());
    for (StreamInfo& stream : header.streams) {
      stream.width = static_cast<std::uint32_t>(size->first);
      stream.height = static_cast<std::uint32_t>(size->second);
    }
  }
  // The metadata is kept as it is, but for the capture frames the cut holds.
  nlohmann::json metadata = MetadataOf(header);
  if (const std::optional<CaptureFrames> capture = CaptureFramesOf(metadata)) {
    metadata["capture_frames"] = {capture->first + kept_first, capture->first + kept_end};
    header.metadata_json = DumpJson(metadata);
  }
  StatusOr<std::uint64_t> written =
      WriteContainer(args.output, header, [&](ContainerWriter& writer) {
        return CopyGofs(*reader, *first_gof, end_gof, writer).WithContext(args.input);
      });
  if (!written.ok()) return ReportError(written.status().WithContext("-o " + args.output));
  if (kept_first != std::uint32_t(first) || kept_end != std::uint32_t(end)) {
    std::fprintf(stderr,
                 "meshvid: frames %d:%d rounded out to %u:%u, the groups of frames that hold "
                 "them (a group is copied whole, never re-encoded)\n",
                 first, end, kept_first, kept_end);
  }
  if (!args.quiet) {
    std::fprintf(stderr, "Cut %s frames %u:%u into %s: %s, %s\n", args.input.c_str(), kept_first,
                 kept_end, args.output.c_str(), Count(kept_end - kept_first, "frame").c_str(),
                 Kilobytes(double(*written)).c_str());
  }
  return 0;
}

}  // namespace

void AddConcatCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ConcatArguments>();
  CLI::App* cmd = app.add_subcommand(
      "concat",
      "Join .mvid files whose frames follow each other into one, without re-encoding: their\n"
      "key groups are copied byte for byte and the header, frame numbering and index written\n"
      "anew (a long capture encoded in pieces with `meshvid encode --frames A:B`). The files\n"
      "must have been encoded alike (frame rate, codec, levels, group size); files that say\n"
      "which capture frames they hold must follow each other with no gap or overlap.\n"
      "The output appears only when it is whole.");
  cmd->add_option("FILES", args->inputs, "The .mvid files, in frame order")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "The joined .mvid")->required();
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing but errors and warnings");
  cmd->callback([args, exit_code] { *exit_code = RunConcat(*args); });
}

void AddCutCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<CutArguments>();
  CLI::App* cmd = app.add_subcommand(
      "cut",
      "Copy the frames A:B of a .mvid into a new file, without re-encoding. Whole groups of\n"
      "frames are copied (with their key group's base and motion), so a range that starts or\n"
      "ends inside a group is rounded out to the group's edges, and the command says so.\n"
      "The output appears only when it is whole.");
  cmd->add_option("FILE", args->input, "The .mvid to cut")->required()->check(CLI::ExistingFile);
  cmd->add_option("--frames", args->frames, "The frames to keep: A:B (half-open), A:, :B or N")
      ->required();
  cmd->add_option("-o,--output", args->output, "The cut .mvid")->required();
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing but errors and warnings");
  cmd->callback([args, exit_code] { *exit_code = RunCut(*args); });
}

}  // namespace meshvid::cli
