// JSON and terminal table of an EvalResult (declared in tools/eval/evaluation.h).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "format/output_file.h"
#include "tools/eval/evaluation.h"
#include "tools/json/json_number.h"

namespace meshvid {
namespace {

nlohmann::json MetricsToJson(const FrameMetrics& m) {
  nlohmann::json j;
  if (m.frame >= 0) j["frame"] = m.frame;
  j["d1_psnr"] = JsonNumber(m.d1_psnr);
  j["d2_psnr"] = JsonNumber(m.d2_psnr);
  j["d1_mse"] = JsonNumber(m.d1_mse);
  j["d2_mse"] = JsonNumber(m.d2_mse);
  j["d1_mse_test_to_ref"] = JsonNumber(m.d1_mse_test_to_ref);
  j["d1_mse_ref_to_test"] = JsonNumber(m.d1_mse_ref_to_test);
  j["d2_mse_test_to_ref"] = JsonNumber(m.d2_mse_test_to_ref);
  j["d2_mse_ref_to_test"] = JsonNumber(m.d2_mse_ref_to_test);
  j["accuracy_rms"] = JsonNumber(m.accuracy_rms);
  j["completeness_rms"] = JsonNumber(m.completeness_rms);
  j["hausdorff"] = JsonNumber(m.hausdorff);
  j["coverage"] = JsonNumber(m.coverage);
  if (m.has_colour) {
    j["y_psnr"] = JsonNumber(m.y_psnr);
    j["cb_psnr"] = JsonNumber(m.cb_psnr);
    j["cr_psnr"] = JsonNumber(m.cr_psnr);
    j["yuv_psnr"] = JsonNumber(m.yuv_psnr);
    j["y_psnr_test_to_ref"] = JsonNumber(m.y_psnr_test_to_ref);
  }
  return j;
}

std::string FormatPsnr(double psnr) {
  if (std::isinf(psnr)) return psnr > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", psnr);
  return buffer;
}

/// Width of the first column, which holds "mean of frames".
constexpr int kLabelWidth = 14;

std::string FormatRow(const std::string& label, const FrameMetrics& m) {
  char buffer[192];
  std::snprintf(buffer, sizeof(buffer), "%*s %8s %8s %11.4g %11.4g %11.4g %8.2f%%", kLabelWidth,
                label.c_str(), FormatPsnr(m.d1_psnr).c_str(), FormatPsnr(m.d2_psnr).c_str(),
                m.accuracy_rms, m.completeness_rms, m.hausdorff, 100.0 * m.coverage);
  std::string row = buffer;
  if (m.has_colour) {
    row += " " + std::string(8 - std::min<std::size_t>(8, FormatPsnr(m.y_psnr).size()), ' ') +
           FormatPsnr(m.y_psnr) + " " +
           std::string(8 - std::min<std::size_t>(8, FormatPsnr(m.yuv_psnr).size()), ' ') +
           FormatPsnr(m.yuv_psnr);
  }
  return row + "\n";
}

/// The "mean of frames" row (PSNR columns only) and the lines saying what both mean rows are.
std::string FormatMeanOfFrames(const PsnrMeanOfFrames& m) {
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer),
                "%*s %8s %8s\n"
                "mean MSE: PSNR of the mean MSE over frames (other columns: mean over frames).\n"
                "mean of frames: mean of the per-frame PSNRs (MPEG CTC), each counted as at most "
                "%g dB; frames capped: D1 %d, D2 %d.\n",
                kLabelWidth, "mean of frames", FormatPsnr(m.d1_psnr).c_str(),
                FormatPsnr(m.d2_psnr).c_str(), kFramePsnrCapDb, m.d1_capped_frames,
                m.d2_capped_frames);
  return buffer;
}

}  // namespace

std::string EvalResultToJson(const EvalResult& result) {
  nlohmann::json j;
  j["settings"] = {
      {"ref", result.ref_description},
      {"test", result.test_description},
      {"first_frame", result.first_frame},
      {"end_frame", result.end_frame},
      {"ref_first", result.ref_first},
      {"samples", result.samples},
      {"seed", result.seed},
      {"coverage_tolerance", result.coverage_tolerance},
  };
  j["peak"] = result.peak;
  j["coverage_tolerance"] = result.coverage_tolerance;
  j["frame_psnr_cap"] = kFramePsnrCapDb;
  j["frames"] = nlohmann::json::array();
  for (const FrameMetrics& m : result.frames) j["frames"].push_back(MetricsToJson(m));
  j["mean"] = MetricsToJson(result.mean);
  j["mean"]["d1_psnr_mean_of_frames"] = JsonNumber(result.mean_of_frames.d1_psnr);
  j["mean"]["d2_psnr_mean_of_frames"] = JsonNumber(result.mean_of_frames.d2_psnr);
  j["mean"]["d1_psnr_capped_frames"] = result.mean_of_frames.d1_capped_frames;
  j["mean"]["d2_psnr_capped_frames"] = result.mean_of_frames.d2_capped_frames;
  return j.dump(2) + "\n";
}

Status WriteEvalJson(const EvalResult& result, const std::string& path) {
  return WriteFileAtomically(path, EvalResultToJson(result));
}

std::string FormatEvalTable(const EvalResult& result) {
  char header[320];
  std::snprintf(header, sizeof(header),
                "peak p = %.6g (reference bounding-box diagonal), coverage tolerance = %.4g, "
                "%zu samples per surface\n"
                "%*s %8s %8s %11s %11s %11s %9s%s\n",
                result.peak, result.coverage_tolerance, result.samples, kLabelWidth, "frame",
                "D1 PSNR", "D2 PSNR", "accuracy", "complete", "Hausdorff", "coverage",
                result.mean.has_colour ? "   Y PSNR YUV PSNR" : "");
  std::string text = header;
  if (result.ref_first != 0) {
    text.insert(text.find('\n'), ", test frame t against reference frame t + " +
                                      std::to_string(result.ref_first));
  }
  for (const FrameMetrics& m : result.frames) text += FormatRow(std::to_string(m.frame), m);
  text += FormatRow("mean MSE", result.mean);
  text += FormatMeanOfFrames(result.mean_of_frames);
  if (result.mean.has_colour) {
    text += "colour: PSNR of 8-bit BT.709 Y and of Y Cb Cr weighted 6:1:1 (MPEG); mean rows: the "
            "mean of the frames' PSNRs.\n";
  }
  return text;
}

}  // namespace meshvid
