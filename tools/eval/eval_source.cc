#include "tools/eval/eval_source.h"

#include <limits>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <utility>

#include "tools/io/file_pattern.h"

namespace meshvid {
namespace {

std::string LowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool LooksLikeCapture(const std::string& spec) {
  if (FilePattern::LooksLikePattern(spec)) {
    StatusOr<FilePattern> pattern = FilePattern::Parse(spec);
    return pattern.ok() && pattern->has_view();
  }
  const std::string ext = LowerExtension(spec);
  if (ext == ".json" || ext == ".conf") return true;
  // A folder holding a manifest.json is a capture (as CaptureSequence::Open reads it), not a
  // folder of meshes.
  std::error_code error;
  return std::filesystem::is_regular_file(std::filesystem::path(spec) / "manifest.json", error);
}

CaptureUnionSequence::CaptureUnionSequence(std::unique_ptr<CaptureSequence> capture)
    : capture_(std::move(capture)) {}

int CaptureUnionSequence::frame_count() const { return capture_->frame_count(); }

double CaptureUnionSequence::frame_rate() const { return capture_->info().frame_rate; }

StatusOr<TriangleMesh> CaptureUnionSequence::Frame(int t) {
  if (t < 0 || t >= frame_count()) {
    return InvalidArgumentError("frame " + std::to_string(t) + " is outside the capture (" +
                                std::to_string(frame_count()) + " frames)");
  }
  MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, capture_->LoadFrame(t));
  TriangleMesh all;
  for (const TriangleMesh& view : views) AppendMesh(view, &all);
  if (all.triangles.empty()) {
    return InvalidArgumentError("frame " + std::to_string(t) + " of the capture (" +
                                capture_->view_path(t, 0) + " ...) has no triangles in any view");
  }
  return all;
}

std::string CaptureUnionSequence::description() const {
  return "capture of " + std::to_string(capture_->view_count()) + " views x " +
         std::to_string(frame_count()) + " frames (" +
         (frame_count() > 0 && capture_->view_count() > 0 ? capture_->view_path(0, 0)
                                                          : std::string("empty")) +
         " ...)";
}

StatusOr<std::unique_ptr<MvidSequence>> MvidSequence::Open(const std::string& path, int level,
                                                           bool allow_partial) {
  std::unique_ptr<MvidSequence> sequence(new MvidSequence());
  sequence->path_ = path;
  MESHVID_ASSIGN_OR_RETURN(sequence->decoder_,
                           MvidDecoder::OpenFile(path, {.allow_partial = allow_partial}));
  // MeshSequence counts frames in an int; a larger count (a damaged or hostile file) is
  // refused rather than wrapped negative.
  const std::uint32_t frames = sequence->decoder_->info().frame_count;
  if (frames > static_cast<std::uint32_t>(std::numeric_limits<int>::max())) {
    return UnsupportedError(path + ": " + std::to_string(frames) + " frames; eval reads at most " +
                            std::to_string(std::numeric_limits<int>::max()));
  }
  const int levels = sequence->decoder_->info().levels;
  sequence->level_ = level < 0 ? levels : level;
  if (sequence->level_ > levels) {
    return InvalidArgumentError(path + " stores levels 0.." + std::to_string(levels) +
                                ", not " + std::to_string(level));
  }
  return sequence;
}

int MvidSequence::frame_count() const {
  return static_cast<int>(decoder_->info().frame_count);
}

double MvidSequence::frame_rate() const { return decoder_->info().frame_rate; }

StatusOr<TriangleMesh> MvidSequence::Frame(int t) {
  if (t < 0) return InvalidArgumentError("frame " + std::to_string(t) + " is negative");
  return decoder_->DecodeFrame(static_cast<std::uint32_t>(t), level_);
}

std::string MvidSequence::description() const {
  return path_ + " at level " + std::to_string(level_);
}

StatusOr<std::unique_ptr<MeshSequence>> OpenEvalTestSource(const std::string& spec, int level,
                                                           bool allow_partial) {
  if (spec.size() > 5 && spec.compare(spec.size() - 5, 5, ".mvid") == 0) {
    MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<MvidSequence> mvid,
                             MvidSequence::Open(spec, level, allow_partial));
    return std::unique_ptr<MeshSequence>(std::move(mvid));
  }
  if (LooksLikeCapture(spec)) {
    MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<CaptureSequence> capture,
                             CaptureSequence::Open(spec));
    return std::unique_ptr<MeshSequence>(new CaptureUnionSequence(std::move(capture)));
  }
  return OpenMeshSequence(spec);
}

}  // namespace meshvid
