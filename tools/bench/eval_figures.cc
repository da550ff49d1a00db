#include "tools/bench/eval_figures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "tools/bench/baseline.h"
#include "tools/json/json_number.h"

namespace meshvid {
namespace {

using nlohmann::json;

/// Equal up to rounding in the last digits (a record and an eval JSON both keep doubles
/// whole), or both NaN.
bool SameFigure(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  if (std::isinf(a) || std::isinf(b)) return a == b;
  return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b));
}

}  // namespace

StatusOr<EvalFigures> ParseEvalFigures(const std::string& text, const std::string& name) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return CorruptError(name + ": not a JSON object");
  if (!j.contains("mean") || !j.at("mean").is_object()) {
    return CorruptError(name + " has no \"mean\"");
  }
  EvalFigures f;
  try {  // JsonNumber throws on a figure that is not a number
    const json& mean = j.at("mean");
    f.d1_psnr = JsonNumber(mean, "d1_psnr");
    f.d2_psnr = JsonNumber(mean, "d2_psnr");
    f.d1_psnr_mean_of_frames = JsonNumber(mean, "d1_psnr_mean_of_frames");
    f.d2_psnr_mean_of_frames = JsonNumber(mean, "d2_psnr_mean_of_frames");
    f.accuracy_rms = JsonNumber(mean, "accuracy_rms");
    f.completeness_rms = JsonNumber(mean, "completeness_rms");
    f.hausdorff = JsonNumber(mean, "hausdorff");
    f.coverage = JsonNumber(mean, "coverage");
    f.y_psnr = JsonNumber(mean, "y_psnr");  // absent (NaN) without colour
    f.yuv_psnr = JsonNumber(mean, "yuv_psnr");
    const auto frames = j.find("frames");
    if (frames != j.end() && frames->is_array()) {
      f.frames = static_cast<int>(frames->size());
      for (const json& frame : *frames) {
        const bool object = frame.is_object();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        f.frame_accuracy_rms.push_back(
            RoundFrameFigure(object ? JsonNumber(frame, "accuracy_rms") : nan));
        f.frame_d1_psnr.push_back(RoundFrameFigure(object ? JsonNumber(frame, "d1_psnr") : nan));
      }
    }
  } catch (const std::invalid_argument& e) {
    return CorruptError(name + ": " + e.what());
  }
  return f;
}

void SetEvalFigures(const EvalFigures& f, BenchPoint* point) {
  point->d1_psnr = f.d1_psnr;
  point->d2_psnr = f.d2_psnr;
  point->d1_psnr_mean_of_frames = f.d1_psnr_mean_of_frames;
  point->d2_psnr_mean_of_frames = f.d2_psnr_mean_of_frames;
  point->accuracy_rms = f.accuracy_rms;
  point->completeness_rms = f.completeness_rms;
  point->hausdorff = f.hausdorff;
  point->coverage = f.coverage;
  point->y_psnr = f.y_psnr;
  point->yuv_psnr = f.yuv_psnr;
  if (f.frames > 0) point->frames = f.frames;
  point->frame_accuracy_rms = f.frame_accuracy_rms;
  point->frame_d1_psnr = f.frame_d1_psnr;
}

std::string PointWorkStem(const BenchPoint& point) {
  if (point.method == kMethodBaseline) return point.codec + "-b" + std::to_string(point.quality);
  return point.codec + "-q" + std::to_string(point.quality) + "-L" + std::to_string(point.level);
}

std::string EvalJsonPath(const std::string& work_dir, const BenchRecord& record,
                         const BenchPoint& point) {
  return work_dir + "/" + BenchRecordName(record) + "/" + PointWorkStem(point) + ".eval.json";
}

Status FillFrameFiguresFromEvalJson(const std::string& path, BenchPoint* point) {
  MESHVID_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  MESHVID_ASSIGN_OR_RETURN(const EvalFigures f, ParseEvalFigures(text, path));
  if (f.frames != point->frames || !SameFigure(f.d1_psnr, point->d1_psnr) ||
      !SameFigure(f.accuracy_rms, point->accuracy_rms)) {
    return InvalidArgumentError(path + " is not the evaluation the point recorded (" +
                                std::to_string(f.frames) + " frames against " +
                                std::to_string(point->frames) + ", or other means)");
  }
  point->frame_accuracy_rms = f.frame_accuracy_rms;
  point->frame_d1_psnr = f.frame_d1_psnr;
  return Status::Ok();
}

int BackfillFrameFigures(BenchRecord& record, const std::string& work_dir) {
  int filled = 0;
  for (BenchPoint& point : record.points) {
    if (!point.ok || HasFrameFigures(point)) continue;
    const std::string path = EvalJsonPath(work_dir, record, point);
    if (!std::filesystem::is_regular_file(path)) continue;
    filled += FillFrameFiguresFromEvalJson(path, &point).ok();
  }
  return filled;
}

}  // namespace meshvid
