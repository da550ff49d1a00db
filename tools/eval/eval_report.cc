// JSON and terminal table of an EvalResult (declared in tools/eval/evaluation.h).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "format/output_file.h"
#include "tools/eval/evaluation.h"

namespace meshvid {
namespace {

/// A number for JSON; +-inf (an exact frame's PSNR) becomes the string "inf"/"-inf", NaN null.
nlohmann::json JsonNumber(double value) {
  if (std::isnan(value)) return nullptr;
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;
}

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
  return j;
}

std::string FormatPsnr(double psnr) {
  if (std::isinf(psnr)) return psnr > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", psnr);
  return buffer;
}

std::string FormatRow(const std::string& label, const FrameMetrics& m) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "%6s %8s %8s %11.4g %11.4g %11.4g %8.2f%%\n",
                label.c_str(), FormatPsnr(m.d1_psnr).c_str(), FormatPsnr(m.d2_psnr).c_str(),
                m.accuracy_rms, m.completeness_rms, m.hausdorff, 100.0 * m.coverage);
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
      {"samples", result.samples},
      {"seed", result.seed},
      {"coverage_tolerance", result.coverage_tolerance},
  };
  j["peak"] = result.peak;
  j["coverage_tolerance"] = result.coverage_tolerance;
  j["frames"] = nlohmann::json::array();
  for (const FrameMetrics& m : result.frames) j["frames"].push_back(MetricsToJson(m));
  j["mean"] = MetricsToJson(result.mean);
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
                "%6s %8s %8s %11s %11s %11s %9s\n",
                result.peak, result.coverage_tolerance, result.samples, "frame", "D1 PSNR",
                "D2 PSNR", "accuracy", "complete", "Hausdorff", "coverage");
  std::string text = header;
  for (const FrameMetrics& m : result.frames) text += FormatRow(std::to_string(m.frame), m);
  text += FormatRow("mean", result.mean);
  return text;
}

}  // namespace meshvid
