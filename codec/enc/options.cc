#include "codec/enc/options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <type_traits>

#include "codec/common/subdivision.h"

namespace meshvid {

double RebaseGainDb(const EncoderOptions& options) {
  // Above kFinestRebasingQuality more key groups gain nothing measurable (bench/QUALITY.md).
  const int quality = std::min(options.quality, kFinestRebasingQuality);
  return options.rebase_gain_db * std::exp2((40.0 - quality) / 20.0);
}

double BaseCoarsening(int quality) {
  // 4 at quality 0, so the coarsest base is the same whatever quality the coarsening starts at.
  const double below = std::max(0, kFinestBaseQuality - std::clamp(quality, 0, 100));
  return std::exp2(2.0 * below / kFinestBaseQuality);
}

int QualityToQp(VideoCodec codec, int quality) {
  const double fraction = 1.0 - std::clamp(quality, 0, 100) / 100.0;
  switch (codec) {
    case VideoCodec::kAv1: return static_cast<int>(std::lround(63 * fraction));
    case VideoCodec::kFfv1: return 0;
    case VideoCodec::kHevc:
    default: return static_cast<int>(std::lround(51 * fraction));
  }
}

namespace {

template <typename T>
constexpr const char* KnobType() {
  if constexpr (std::is_same_v<T, bool>) return "bool";
  if constexpr (std::is_same_v<T, int>) return "int";
  if constexpr (std::is_same_v<T, std::size_t>) return "size";
  return "double";
}

/// Each knob's place in kKnobs, in the table's order (kKnobIndex_deform_rigidity, ...).
enum KnobIndex {
#define MESHVID_KNOB_INDEX(type, name, value, lowest, highest, flag, help) kKnobIndex_##name,
  MESHVID_ENCODER_TUNING(MESHVID_KNOB_INDEX)
#undef MESHVID_KNOB_INDEX
};

constexpr TuningKnob kKnobs[] = {
#define MESHVID_KNOB_ENTRY(type, name, value, lowest, highest, flag, help) \
  {#name, KnobType<type>(), static_cast<double>(value), lowest, highest, flag, help},
    MESHVID_ENCODER_TUNING(MESHVID_KNOB_ENTRY)
#undef MESHVID_KNOB_ENTRY
};

/// A number as SetTuning reads it back: the shortest text that round-trips.
std::string NumberText(double value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof(text), value);
  return error == std::errc() ? std::string(text, end) : std::to_string(value);
}

}  // namespace

std::string TuningRangeText(const TuningKnob& knob) {
  if (std::string_view(knob.type) == "bool") return "true, false";
  if (knob.highest >= kNoLimit) return ">= " + NumberText(knob.lowest);
  return "[" + NumberText(knob.lowest) + ", " + NumberText(knob.highest) + "]";
}

namespace {

/// kInvalidArgument naming the knob unless `value` is finite and in its range.
Status CheckKnob(const TuningKnob& knob, double value) {
  if (std::isfinite(value) && value >= knob.lowest && value <= knob.highest) return Status::Ok();
  return InvalidArgumentError(std::string("tuning.") + knob.key + " must be " +
                              (knob.highest >= kNoLimit ? "" : "in ") + TuningRangeText(knob));
}

template <typename T>
Status ParseKnob(const TuningKnob& knob, std::string_view text, T* out) {
  const auto refuse = [&] {
    return InvalidArgumentError(std::string("tuning.") + knob.key + ": '" + std::string(text) +
                                "' is not " +
                                (std::is_same_v<T, bool>     ? "true or false"
                                 : std::is_same_v<T, double> ? "a number"
                                                             : "a whole number"));
  };
  if constexpr (std::is_same_v<T, bool>) {
    if (text == "true" || text == "1")
      *out = true;
    else if (text == "false" || text == "0")
      *out = false;
    else
      return refuse();
    return Status::Ok();
  } else {
    T value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) return refuse();
    if (Status in_range = CheckKnob(knob, static_cast<double>(value)); !in_range.ok()) {
      return in_range;
    }
    *out = value;
    return Status::Ok();
  }
}

}  // namespace

std::span<const TuningKnob> TuningKnobs() { return kKnobs; }

Status SetTuning(EncoderTuning& tuning, std::string_view key, std::string_view value) {
#define MESHVID_SET_KNOB(type, name, default_value, lowest, highest, flag, help) \
  if (key == #name) return ParseKnob(kKnobs[kKnobIndex_##name], value, &tuning.name);
  MESHVID_ENCODER_TUNING(MESHVID_SET_KNOB)
#undef MESHVID_SET_KNOB
  return InvalidArgumentError("unknown tuning key '" + std::string(key) +
                              "' (TuningKnobs lists them: docs/tuning.md)");
}

std::string TuningValue(const EncoderTuning& tuning, std::string_view key) {
#define MESHVID_KNOB_VALUE(type, name, default_value, lowest, highest, flag, help)   \
  if (key == #name) {                                                                \
    if constexpr (std::is_same_v<type, bool>) return tuning.name ? "true" : "false"; \
    return NumberText(static_cast<double>(tuning.name));                             \
  }
  MESHVID_ENCODER_TUNING(MESHVID_KNOB_VALUE)
#undef MESHVID_KNOB_VALUE
  return {};
}

std::string TuningTableMarkdown() {
  const EncoderTuning defaults;
  std::string table =
      "| key | default | range | former flag | what it does |\n"
      "|---|---|---|---|---|\n";
  for (const TuningKnob& knob : kKnobs) {
    table += std::string("| `") + knob.key + "` | " + TuningValue(defaults, knob.key) + " | " +
             TuningRangeText(knob) + " | " +
             (*knob.former_flag != '\0' ? std::string("`") + knob.former_flag + "`" : "none") +
             " | " + knob.help + " |\n";
  }
  return table;
}

Status CheckOptions(const EncoderOptions& o) {
  auto bad = [](const std::string& what) { return InvalidArgumentError(what); };
  if (o.levels < 0 || o.levels > RegularSubdivision::kMaxLevels) {
    return bad("levels must be in 0.." + std::to_string(RegularSubdivision::kMaxLevels));
  }
  if (o.quality < 0 || o.quality > 100) return bad("quality must be in 0..100");
  if (o.colour_quality < -1 || o.colour_quality > 100) {
    return bad("colour_quality must be in 0..100 (-1: quality's)");
  }
  if (o.effort < 0 || o.effort > 9) return bad("effort must be in 0..9");
  if (o.gof_size < 1 || o.gof_size > 1024) return bad("gof_size must be in 1..1024");
  if (!(o.rebase_gain_db >= 0 && o.rebase_gain_db <= 100)) {
    return bad("rebase_gain_db must be in [0, 100] dB");
  }
  if (o.max_key_groups < 0) return bad("max_key_groups must be >= 0 (0: no limit)");
  if (o.base_vertices < 4) return bad("base_vertices must be at least 4");
#define MESHVID_CHECK_KNOB(type, name, default_value, lowest, highest, flag, help)                \
  if (Status in_range = CheckKnob(kKnobs[kKnobIndex_##name], static_cast<double>(o.tuning.name)); \
      !in_range.ok()) {                                                                           \
    return in_range;                                                                              \
  }
  MESHVID_ENCODER_TUNING(MESHVID_CHECK_KNOB)
#undef MESHVID_CHECK_KNOB
  return Status::Ok();
}

}  // namespace meshvid
