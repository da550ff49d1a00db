#include "tools/bench/bench_record.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "format/output_file.h"
#include "tools/bench/bd_rate.h"
#include "tools/json/json_number.h"

namespace meshvid {
namespace {

using nlohmann::json;

/// An array of numbers written by JsonNumber(); a missing key is an empty array.
std::vector<double> GetNumbers(const json& j, const char* key) {
  std::vector<double> values;
  const auto it = j.find(key);
  if (it == j.end()) return values;
  if (!it->is_array()) throw std::invalid_argument(std::string("'") + key + "' is not an array");
  values.reserve(it->size());
  for (const json& value : *it) values.push_back(JsonNumberValue(value, key));
  return values;
}

json Numbers(const std::vector<double>& values) {
  json array = json::array();
  for (double value : values) array.push_back(JsonNumber(RoundFrameFigure(value)));
  return array;
}

/// The keys of the per-frame arrays, written one array a line.
constexpr const char* kFrameArrayKeys[] = {"frame_accuracy_rms", "frame_d1_psnr"};

/// `text` (indented JSON) with every per-frame array on one line: "[1.5, 2, null]" rather
/// than one value a line, so a record of many frames stays small and readable. Their values
/// are numbers, null, "inf" or "-inf": no brackets or spaces inside. A string value cannot
/// match `"key": [`, its quotes being escaped.
std::string CollapseFrameArrays(std::string text) {
  for (const char* key : kFrameArrayKeys) {
    const std::string opening = std::string("\"") + key + "\": [";
    for (std::size_t at = text.find(opening); at != std::string::npos;
         at = text.find(opening, at + 1)) {
      const std::size_t begin = at + opening.size();
      const std::size_t end = text.find(']', begin);
      if (end == std::string::npos) break;
      std::string items;  // the values without whitespace, ", " between them
      for (std::size_t i = begin; i < end; ++i) {
        if (text[i] == ' ' || text[i] == '\n') continue;
        items += text[i];
        if (text[i] == ',') items += ' ';
      }
      text.replace(begin, end - begin, items);
    }
  }
  return text;
}

json DivergenceToJson(const DivergenceCheck& d) {
  return {{"has_default", d.has_default},
          {"has_baseline", d.has_baseline},
          {"has_frames", d.has_frames},
          {"note", d.note},
          {"codec", d.codec},
          {"quality", d.quality},
          {"level", d.level},
          {"baseline_bits", d.baseline_bits},
          {"psnr", d.psnr},
          {"ratio_limit", JsonNumber(d.ratio_limit)},
          {"frames", d.frames},
          {"frames_within", d.frames_within},
          {"share_within", JsonNumber(d.share_within)},
          {"worst_frame", d.worst_frame},
          {"worst_meshvid_accuracy_rms", JsonNumber(d.worst_meshvid_accuracy_rms)},
          {"worst_baseline_accuracy_rms", JsonNumber(d.worst_baseline_accuracy_rms)},
          {"worst_ratio", JsonNumber(d.worst_ratio)},
          {"meshvid_d1_psnr", JsonNumber(d.meshvid_d1_psnr)},
          {"baseline_d1_psnr", JsonNumber(d.baseline_d1_psnr)},
          {"share_met", d.share_met},
          {"psnr_met", d.psnr_met}};
}

DivergenceCheck DivergenceFromJson(const json& j) {
  DivergenceCheck d;
  d.has_default = j.value("has_default", false);
  d.has_baseline = j.value("has_baseline", false);
  d.has_frames = j.value("has_frames", false);
  d.note = j.value("note", "");
  d.codec = j.value("codec", "");
  d.quality = j.value("quality", 0);
  d.level = j.value("level", -1);
  d.baseline_bits = j.value("baseline_bits", 0);
  d.psnr = j.value("psnr", std::string(kPsnrMeanOfFrames));
  d.ratio_limit = JsonNumber(j, "ratio_limit");
  d.frames = j.value("frames", 0);
  d.frames_within = j.value("frames_within", 0);
  d.share_within = JsonNumber(j, "share_within");
  d.worst_frame = j.value("worst_frame", -1);
  d.worst_meshvid_accuracy_rms = JsonNumber(j, "worst_meshvid_accuracy_rms");
  d.worst_baseline_accuracy_rms = JsonNumber(j, "worst_baseline_accuracy_rms");
  d.worst_ratio = JsonNumber(j, "worst_ratio");
  d.meshvid_d1_psnr = JsonNumber(j, "meshvid_d1_psnr");
  d.baseline_d1_psnr = JsonNumber(j, "baseline_d1_psnr");
  d.share_met = j.value("share_met", false);
  d.psnr_met = j.value("psnr_met", false);
  return d;
}

json CostToJson(const StepCost& c) {
  return {{"wall_seconds", c.wall_seconds},
          {"cpu_seconds", c.cpu_seconds},
          {"peak_rss_mb", c.peak_rss_mb}};
}

StepCost CostFromJson(const json& j) {
  StepCost c;
  if (!j.is_object()) return c;
  c.wall_seconds = JsonNumber(j, "wall_seconds");
  c.cpu_seconds = JsonNumber(j, "cpu_seconds");
  c.peak_rss_mb = JsonNumber(j, "peak_rss_mb");
  return c;
}

json EncodeToJson(const BenchEncode& e) {
  return {{"method", e.method},
          {"codec", e.codec},
          {"quality", e.quality},
          {"ok", e.ok},
          {"error", e.error},
          {"file", e.file},
          {"frames", e.frames},
          {"levels", e.levels},
          {"bytes_total", JsonNumber(e.bytes_total)},
          {"colour_bytes_total", JsonNumber(e.colour_bytes_total)},
          {"seconds", JsonNumber(e.seconds)},
          {"encode_fps", JsonNumber(e.encode_fps)},
          {"peak_rss_mb", JsonNumber(e.peak_rss_mb)},
          {"decode_fps", JsonNumber(e.decode_fps)},
          {"target_vertices", JsonNumber(e.target_vertices)},
          {"command", e.command}};
}

BenchEncode EncodeFromJson(const json& j) {
  BenchEncode e;
  e.method = j.value("method", "");
  e.codec = j.value("codec", "");
  e.quality = j.value("quality", 0);
  e.ok = j.value("ok", false);
  e.error = j.value("error", "");
  e.file = j.value("file", "");
  e.frames = j.value("frames", 0);
  e.levels = j.value("levels", 0);
  e.bytes_total = JsonNumber(j, "bytes_total");
  e.colour_bytes_total = JsonNumber(j, "colour_bytes_total");
  e.seconds = JsonNumber(j, "seconds");
  e.encode_fps = JsonNumber(j, "encode_fps");
  e.peak_rss_mb = JsonNumber(j, "peak_rss_mb");
  e.decode_fps = JsonNumber(j, "decode_fps");
  e.target_vertices = j.contains("target_vertices") ? JsonNumber(j, "target_vertices") : 0.0;
  e.command = j.value("command", "");
  return e;
}

json PointToJson(const BenchPoint& p) {
  return {{"method", p.method},
          {"codec", p.codec},
          {"quality", p.quality},
          {"level", p.level},
          {"ok", p.ok},
          {"error", p.error},
          {"frames", p.frames},
          {"bytes_per_frame", JsonNumber(p.bytes_per_frame)},
          {"mbit_per_s", JsonNumber(p.mbit_per_s)},
          {"d1_psnr", JsonNumber(p.d1_psnr)},
          {"d2_psnr", JsonNumber(p.d2_psnr)},
          {"d1_psnr_mean_of_frames", JsonNumber(p.d1_psnr_mean_of_frames)},
          {"d2_psnr_mean_of_frames", JsonNumber(p.d2_psnr_mean_of_frames)},
          {"accuracy_rms", JsonNumber(p.accuracy_rms)},
          {"completeness_rms", JsonNumber(p.completeness_rms)},
          {"hausdorff", JsonNumber(p.hausdorff)},
          {"coverage", JsonNumber(p.coverage)},
          {"y_psnr", JsonNumber(p.y_psnr)},
          {"yuv_psnr", JsonNumber(p.yuv_psnr)},
          {"colour_bytes_per_frame", JsonNumber(p.colour_bytes_per_frame)},
          {"encode_fps", JsonNumber(p.encode_fps)},
          {"decode_fps", JsonNumber(p.decode_fps)},
          {"encode_peak_mb", JsonNumber(p.encode_peak_mb)},
          {"decode_peak_mb", JsonNumber(p.decode_peak_mb)},
          {"vertices", JsonNumber(p.vertices)},
          {"frame_accuracy_rms", Numbers(p.frame_accuracy_rms)},
          {"frame_d1_psnr", Numbers(p.frame_d1_psnr)},
          {"commands", p.commands}};
}

BenchPoint PointFromJson(const json& j) {
  BenchPoint p;
  p.method = j.value("method", "");
  p.codec = j.value("codec", "");
  p.quality = j.value("quality", 0);
  p.level = j.value("level", -1);
  p.ok = j.value("ok", false);
  p.error = j.value("error", "");
  p.frames = j.value("frames", 0);
  p.bytes_per_frame = JsonNumber(j, "bytes_per_frame");
  p.mbit_per_s = JsonNumber(j, "mbit_per_s");
  p.d1_psnr = JsonNumber(j, "d1_psnr");
  p.d2_psnr = JsonNumber(j, "d2_psnr");
  p.d1_psnr_mean_of_frames = JsonNumber(j, "d1_psnr_mean_of_frames");
  p.d2_psnr_mean_of_frames = JsonNumber(j, "d2_psnr_mean_of_frames");
  p.accuracy_rms = JsonNumber(j, "accuracy_rms");
  p.completeness_rms = JsonNumber(j, "completeness_rms");
  p.hausdorff = JsonNumber(j, "hausdorff");
  p.coverage = JsonNumber(j, "coverage");
  p.y_psnr = JsonNumber(j, "y_psnr");
  p.yuv_psnr = JsonNumber(j, "yuv_psnr");
  p.colour_bytes_per_frame = JsonNumber(j, "colour_bytes_per_frame");
  p.encode_fps = JsonNumber(j, "encode_fps");
  p.decode_fps = JsonNumber(j, "decode_fps");
  p.encode_peak_mb = JsonNumber(j, "encode_peak_mb");
  p.decode_peak_mb = JsonNumber(j, "decode_peak_mb");
  p.vertices = JsonNumber(j, "vertices");
  p.frame_accuracy_rms = GetNumbers(j, "frame_accuracy_rms");
  p.frame_d1_psnr = GetNumbers(j, "frame_d1_psnr");
  if (j.contains("commands")) p.commands = j.at("commands").get<std::vector<std::string>>();
  return p;
}

/// Where a meshvid curve stands when its PSNR range does not overlap the baseline's: its
/// nearest point against the baseline's nearest, in dB and in bytes per frame.
std::string NoOverlapNote(const std::vector<RdPoint>& baseline, const std::vector<RdPoint>& test,
                          const std::string& reference) {
  const std::vector<RdPoint> ref = PrepareRdCurve(baseline);
  const std::vector<RdPoint> tst = PrepareRdCurve(test);
  if (ref.empty() || tst.empty()) return "";
  char text[200];
  if (tst.front().psnr > ref.back().psnr) {
    std::snprintf(text, sizeof(text),
                  "; meshvid's lowest point is %.1f dB above the %s's best, with %.3gx its "
                  "bytes per frame",
                  tst.front().psnr - ref.back().psnr, reference.c_str(),
                  tst.front().rate / ref.back().rate);
    return text;
  }
  if (tst.back().psnr < ref.front().psnr) {
    std::snprintf(text, sizeof(text),
                  "; meshvid's best point is %.1f dB below the %s's lowest, with %.3gx its "
                  "bytes per frame",
                  ref.front().psnr - tst.back().psnr, reference.c_str(),
                  tst.back().rate / ref.front().rate);
    return text;
  }
  return "";
}

}  // namespace

std::string DecimatedCodecName(double multiple) {
  char text[32];
  std::snprintf(text, sizeof(text), "draco %gx", multiple);
  return text;
}

std::string BenchRecordName(const BenchRecord& record) {
  return record.sequence + "-" + record.rig;
}

std::string BenchRecordToJson(const BenchRecord& r) {
  json j;
  j["format"] = kBenchRecordFormat;
  j["sequence"] = r.sequence;
  j["ground_truth"] = r.ground_truth;
  j["rig"] = r.rig;
  j["views"] = r.views;
  j["layout"] = r.layout;
  j["frames"] = r.frames;
  j["frame_rate"] = r.frame_rate;
  j["eval_samples"] = r.eval_samples;
  j["capture"] = r.capture;
  j["reference"] = r.reference;
  j["date"] = r.date;
  j["run_key"] = r.run_key;
  if (!r.encode_args.empty()) j["encode_args"] = r.encode_args;
  j["machine"] = {{"cpu_model", r.machine.cpu_model},
                  {"cores", r.machine.cores},
                  {"ram_gb", r.machine.ram_gb},
                  {"kernel", r.machine.kernel}};
  j["simulate"] = {{"ok", r.simulate_ok},
                   {"error", r.simulate_error},
                   {"command", r.simulate_command},
                   {"cost", CostToJson(r.simulate_cost)}};
  j["baseline"] = {{"ok", r.baseline_ok},
                   {"error", r.baseline_error},
                   {"command", r.baseline_command},
                   {"fuse_seconds", r.baseline_fuse_seconds},
                   {"cost", CostToJson(r.baseline_cost)}};
  j["bench_process_peak_mb"] = r.bench_process_peak_mb;
  j["encodes"] = json::array();
  for (const BenchEncode& e : r.encodes) j["encodes"].push_back(EncodeToJson(e));
  j["points"] = json::array();
  for (const BenchPoint& p : r.points) j["points"].push_back(PointToJson(p));
  j["bd_rates"] = json::array();
  for (const BdRateEntry& b : r.bd_rates) {
    j["bd_rates"].push_back({{"reference", b.reference},
                             {"codec", b.codec},
                             {"level", b.level},
                             {"ok", b.ok},
                             {"psnr", b.psnr},
                             {"delta", JsonNumber(b.delta)},
                             {"psnr_low", JsonNumber(b.psnr_low)},
                             {"psnr_high", JsonNumber(b.psnr_high)},
                             {"note", b.note}});
  }
  j["divergence"] = DivergenceToJson(r.divergence);
  return CollapseFrameArrays(j.dump(2)) + "\n";
}

StatusOr<BenchRecord> ParseBenchRecord(const std::string& text, const std::string& name) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return CorruptError(name + ": not a JSON object");
  if (j.value("format", std::string()) != kBenchRecordFormat) {
    return UnsupportedError(name + ": not a meshvid bench record (\"format\" is not \"" +
                            kBenchRecordFormat + "\")");
  }
  try {
    BenchRecord r;
    r.sequence = j.value("sequence", "");
    r.ground_truth = j.value("ground_truth", "");
    r.rig = j.value("rig", "");
    r.views = j.value("views", 0);
    r.layout = j.value("layout", "");
    r.frames = j.value("frames", 0);
    r.frame_rate = JsonNumber(j, "frame_rate");
    r.eval_samples = j.value("eval_samples", 0);
    r.capture = j.value("capture", "");
    r.reference = j.value("reference", "");
    r.date = j.value("date", "");
    r.run_key = j.value("run_key", "");
    r.encode_args = j.value("encode_args", "");
    if (j.contains("machine")) {
      const json& m = j.at("machine");
      r.machine.cpu_model = m.value("cpu_model", "");
      r.machine.cores = m.value("cores", 0);
      r.machine.ram_gb = JsonNumber(m, "ram_gb");
      r.machine.kernel = m.value("kernel", "");
    }
    if (j.contains("simulate")) {
      const json& s = j.at("simulate");
      r.simulate_ok = s.value("ok", false);
      r.simulate_error = s.value("error", "");
      r.simulate_command = s.value("command", "");
      r.simulate_cost = CostFromJson(s.value("cost", json::object()));
    }
    if (j.contains("baseline")) {
      const json& b = j.at("baseline");
      r.baseline_ok = b.value("ok", false);
      r.baseline_error = b.value("error", "");
      r.baseline_command = b.value("command", "");
      r.baseline_fuse_seconds = JsonNumber(b, "fuse_seconds");
      r.baseline_cost = CostFromJson(b.value("cost", json::object()));
    }
    r.bench_process_peak_mb = JsonNumber(j, "bench_process_peak_mb");
    for (const json& e : j.value("encodes", json::array())) r.encodes.push_back(EncodeFromJson(e));
    for (const json& p : j.value("points", json::array())) r.points.push_back(PointFromJson(p));
    for (const json& b : j.value("bd_rates", json::array())) {
      BdRateEntry entry;
      entry.reference = b.value("reference", std::string(kMethodBaseline));
      entry.codec = b.value("codec", "");
      entry.level = b.value("level", 0);
      entry.ok = b.value("ok", false);
      entry.psnr = b.value("psnr", std::string(kPsnrOfMeanMse));
      entry.delta = JsonNumber(b, "delta");
      entry.psnr_low = JsonNumber(b, "psnr_low");
      entry.psnr_high = JsonNumber(b, "psnr_high");
      entry.note = b.value("note", "");
      r.bd_rates.push_back(entry);
    }
    if (j.contains("divergence")) r.divergence = DivergenceFromJson(j.at("divergence"));
    return r;
  } catch (const std::exception& e) {  // nlohmann type errors, bad numbers
    return CorruptError(name + ": " + e.what());
  }
}

StatusOr<BenchRecord> ReadBenchRecord(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return NotFoundError(path + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return ParseBenchRecord(text.str(), path);
}

Status WriteBenchRecord(const BenchRecord& record, const std::string& path) {
  return WriteFileAtomically(path, BenchRecordToJson(record));
}

StatusOr<std::vector<BenchRecord>> ReadBenchRecords(const std::string& folder) {
  std::vector<std::string> paths;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") {
      paths.push_back(entry.path().string());
    }
  }
  if (error) return NotFoundError(folder + ": cannot list: " + error.message());
  std::sort(paths.begin(), paths.end());
  std::vector<BenchRecord> records;
  for (const std::string& path : paths) {
    StatusOr<BenchRecord> record = ReadBenchRecord(path);
    if (record.ok()) {
      records.push_back(std::move(*record));
    } else if (record.status().code() != StatusCode::kUnsupported) {
      return record.status();
    }
  }
  return records;
}

BenchEncode* FindEncode(BenchRecord& record, const std::string& method, const std::string& codec,
                        int quality) {
  for (BenchEncode& e : record.encodes) {
    if (e.method == method && e.codec == codec && e.quality == quality) return &e;
  }
  return nullptr;
}

BenchPoint* FindPoint(BenchRecord& record, const std::string& method, const std::string& codec,
                      int quality, int level) {
  for (BenchPoint& p : record.points) {
    if (p.method == method && p.codec == codec && p.quality == quality && p.level == level) {
      return &p;
    }
  }
  return nullptr;
}

void UpsertPoint(BenchRecord& record, const BenchPoint& point) {
  if (BenchPoint* p = FindPoint(record, point.method, point.codec, point.quality, point.level)) {
    *p = point;
  } else {
    record.points.push_back(point);
  }
}

void UpsertEncode(BenchRecord& record, const BenchEncode& encode) {
  if (BenchEncode* e = FindEncode(record, encode.method, encode.codec, encode.quality)) {
    *e = encode;
  } else {
    record.encodes.push_back(encode);
  }
}

void ErasePoints(BenchRecord& record, const std::string& method, const std::string& codec,
                 int quality) {
  std::erase_if(record.points, [&](const BenchPoint& p) {
    return p.method == method && p.codec == codec && p.quality == quality;
  });
}

bool HasMeanOfFramesPsnr(const BenchPoint& point) {
  return !std::isnan(point.d1_psnr_mean_of_frames);
}

bool HasFrameFigures(const BenchPoint& point) {
  const std::size_t frames = point.frame_accuracy_rms.size();
  return frames > 0 && point.frame_d1_psnr.size() == frames &&
         static_cast<std::size_t>(point.frames) == frames;
}

double RoundFrameFigure(double value) {
  if (!std::isfinite(value)) return value;
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return std::strtod(text, nullptr);
}

std::string RecordPsnrKind(const BenchRecord& record) {
  for (const BenchPoint& p : record.points) {
    if (p.ok && !HasMeanOfFramesPsnr(p)) return kPsnrOfMeanMse;
  }
  return kPsnrMeanOfFrames;
}

double D1Psnr(const BenchPoint& point, const std::string& kind) {
  return kind == kPsnrOfMeanMse ? point.d1_psnr : point.d1_psnr_mean_of_frames;
}

void ComputeBdRates(BenchRecord& record) {
  record.bd_rates.clear();
  const std::string kind = RecordPsnrKind(record);
  // Reference curves by name, which is also their report order: "baseline" before every
  // "decimated ..." (the full baseline is always there, so every curve has its entry).
  std::map<std::string, std::vector<RdPoint>> references = {{kMethodBaseline, {}}};
  std::map<std::pair<std::string, int>, std::vector<RdPoint>> curves;  // (codec, level)
  for (const BenchPoint& p : record.points) {
    if (!p.ok) continue;
    const RdPoint point{p.bytes_per_frame, D1Psnr(p, kind)};
    if (p.method == kMethodBaseline) {
      references[kMethodBaseline].push_back(point);
    } else if (p.method == kMethodDecimated) {
      references[std::string(kMethodDecimated) + " " + p.codec].push_back(point);
    } else if (p.method == kMethodMeshvid) {
      curves[{p.codec, p.level}].push_back(point);
    }
  }
  for (const auto& [reference, reference_points] : references) {
    for (const auto& [key, points] : curves) {
      // One-point configurations (the lossless FFV1 reference) have no curve.
      if (points.size() < 2) continue;
      BdRateEntry entry;
      entry.reference = reference;
      entry.codec = key.first;
      entry.level = key.second;
      entry.psnr = kind;
      StatusOr<BdRateResult> result = BjontegaardDeltaRate(reference_points, points);
      if (result.ok()) {
        entry.ok = true;
        entry.delta = result->delta;
        entry.psnr_low = result->psnr_low;
        entry.psnr_high = result->psnr_high;
      } else {
        entry.note = result.status().message() + NoOverlapNote(reference_points, points, reference);
      }
      record.bd_rates.push_back(entry);
    }
  }
}

}  // namespace meshvid
