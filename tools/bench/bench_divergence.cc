#include "tools/bench/bench_divergence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "codec/common/video_codec.h"
#include "codec/enc/encoder.h"

namespace meshvid {
namespace {

/// meshvid's accuracy over the baseline's on one frame; NaN when either is missing.
double AccuracyRatio(double meshvid, double baseline) {
  if (!std::isfinite(meshvid) || !std::isfinite(baseline)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (baseline == 0) return meshvid == 0 ? 1 : std::numeric_limits<double>::infinity();
  return meshvid / baseline;
}

/// How the default point is named in notes: "hevc q40 level 2".
std::string DefaultPointName(int level) {
  return DefaultCodecName() + " q" + std::to_string(DefaultQuality()) +
         (level >= 0 ? " level " + std::to_string(level) : std::string());
}

}  // namespace

std::string DefaultCodecName() { return std::string(VideoCodecName(EncoderOptions().codec)); }

int DefaultQuality() { return EncoderOptions().quality; }

int DefaultPointLevel(const BenchRecord& record) {
  const std::string codec = DefaultCodecName();
  const int quality = DefaultQuality();
  for (const BenchEncode& e : record.encodes) {
    if (e.method == kMethodMeshvid && e.codec == codec && e.quality == quality && e.ok) {
      return e.levels;
    }
  }
  int finest = -1;
  for (const BenchPoint& p : record.points) {
    if (p.method == kMethodMeshvid && p.codec == codec && p.quality == quality) {
      finest = std::max(finest, p.level);
    }
  }
  return finest;
}

const BenchPoint* FindDefaultPoint(const BenchRecord& record) {
  const std::string codec = DefaultCodecName();
  const int quality = DefaultQuality();
  const int level = DefaultPointLevel(record);
  for (const BenchPoint& p : record.points) {
    if (p.method == kMethodMeshvid && p.codec == codec && p.quality == quality &&
        p.level == level) {
      return &p;
    }
  }
  return nullptr;
}

const BenchPoint* FindBaselineBest(const BenchRecord& record) {
  const std::string kind = RecordPsnrKind(record);
  const BenchPoint* best = nullptr;
  for (const BenchPoint& p : record.points) {
    if (!p.ok || p.method != kMethodBaseline || std::isnan(D1Psnr(p, kind))) continue;
    if (best == nullptr || D1Psnr(p, kind) > D1Psnr(*best, kind) ||
        (D1Psnr(p, kind) == D1Psnr(*best, kind) && p.bytes_per_frame < best->bytes_per_frame)) {
      best = &p;
    }
  }
  return best;
}

void ComputeDivergence(BenchRecord& record) {
  DivergenceCheck d;
  d.codec = DefaultCodecName();
  d.quality = DefaultQuality();
  d.level = DefaultPointLevel(record);
  d.psnr = RecordPsnrKind(record);
  const BenchPoint* meshvid = FindDefaultPoint(record);
  const BenchPoint* baseline = FindBaselineBest(record);
  d.has_default = meshvid != nullptr && meshvid->ok;
  d.has_baseline = baseline != nullptr;
  std::string note;
  auto add_note = [&note](const std::string& text) { note += (note.empty() ? "" : "; ") + text; };
  if (meshvid == nullptr) {
    add_note("no " + DefaultPointName(d.level) + " point");
  } else if (!meshvid->ok) {
    add_note(DefaultPointName(d.level) + " failed");
  }
  if (!d.has_baseline) add_note("no successful baseline point");
  if (d.has_baseline) d.baseline_bits = baseline->quality;
  if (!d.has_default || !d.has_baseline) {
    d.note = note;
    record.divergence = d;
    return;
  }
  d.meshvid_d1_psnr = D1Psnr(*meshvid, d.psnr);
  d.baseline_d1_psnr = D1Psnr(*baseline, d.psnr);
  d.psnr_met = d.meshvid_d1_psnr >= d.baseline_d1_psnr;  // false if either is NaN

  if (!HasFrameFigures(*meshvid) || !HasFrameFigures(*baseline)) {
    add_note("no per-frame figures for " +
             std::string(!HasFrameFigures(*meshvid) ? "the default point" : "the baseline") +
             " (an older record whose eval JSON is gone: run the bench again)");
    d.note = note;
    record.divergence = d;
    return;
  }
  const std::size_t m_frames = meshvid->frame_accuracy_rms.size();
  const std::size_t b_frames = baseline->frame_accuracy_rms.size();
  if (m_frames != b_frames) {
    add_note("meshvid has " + std::to_string(m_frames) + " frames, the baseline " +
             std::to_string(b_frames) + ": the first " +
             std::to_string(std::min(m_frames, b_frames)) + " compared");
  }
  d.has_frames = true;
  d.frames = static_cast<int>(std::min(m_frames, b_frames));
  double worst = -1;  // NaN ratios count as +inf
  for (int t = 0; t < d.frames; ++t) {
    const double m = meshvid->frame_accuracy_rms[t];
    const double b = baseline->frame_accuracy_rms[t];
    const double ratio = AccuracyRatio(m, b);
    if (ratio <= d.ratio_limit) ++d.frames_within;
    const double rank = std::isnan(ratio) ? std::numeric_limits<double>::infinity() : ratio;
    if (rank > worst) {  // the first of equal ratios
      worst = rank;
      d.worst_frame = t;
      d.worst_meshvid_accuracy_rms = m;
      d.worst_baseline_accuracy_rms = b;
      d.worst_ratio = ratio;
    }
  }
  d.share_within = d.frames > 0 ? static_cast<double>(d.frames_within) / d.frames
                                : std::numeric_limits<double>::quiet_NaN();
  d.share_met = d.share_within >= kDivergenceShareGoal;
  d.note = note;
  record.divergence = d;
}

std::string DescribeDivergence(const DivergenceCheck& d) {
  std::string text = "divergence of " + d.codec + " q" + std::to_string(d.quality) +
                     (d.level >= 0 ? " L" + std::to_string(d.level) : std::string()) +
                     " against the baseline's " +
                     (d.has_baseline ? std::to_string(d.baseline_bits) + " bits" : "best") + ": ";
  if (!d.has_default || !d.has_baseline) return text + "n/a (" + d.note + ")";
  char buffer[320];
  if (d.has_frames) {
    std::snprintf(buffer, sizeof(buffer),
                  "%d/%d frames within %.3gx (%.1f%%, goal %.0f%%: %s), worst frame %d (%.3gx: "
                  "accuracy %.4g against %.4g), ",
                  d.frames_within, d.frames, d.ratio_limit, 100 * d.share_within,
                  100 * kDivergenceShareGoal, d.share_met ? "met" : "missed", d.worst_frame,
                  d.worst_ratio, d.worst_meshvid_accuracy_rms, d.worst_baseline_accuracy_rms);
    text += buffer;
  } else {
    text += "frames n/a (" + d.note + "), ";
  }
  std::snprintf(buffer, sizeof(buffer), "D1 PSNR %.2f against %.2f dB (%s)", d.meshvid_d1_psnr,
                d.baseline_d1_psnr, d.psnr_met ? "met" : "missed");
  return text + buffer;
}

}  // namespace meshvid
