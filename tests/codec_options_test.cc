// The encoder's tuning knobs (codec/enc/options.h): every knob is set and read back by its key,
// checked against its range, and listed in docs/tuning.md exactly as the table declares it.
// Regenerate the page after changing a knob with MESHVID_UPDATE_DOCS=1 ctest -R TuningKnobs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <string>

#include "codec/enc/options.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

TEST(TuningKnobs, EveryKnobHasAUniqueKeyAFormerFlagAndADefaultInItsRange) {
  const EncoderTuning defaults;
  std::set<std::string> keys, flags;
  for (const TuningKnob& knob : TuningKnobs()) {
    EXPECT_TRUE(keys.insert(knob.key).second) << knob.key;
    // Knobs added since `--tune` have no former flag.
    if (*knob.former_flag != '\0') {
      EXPECT_TRUE(flags.insert(knob.former_flag).second) << knob.former_flag;
    }
    EXPECT_LE(knob.lowest, knob.default_value) << knob.key;
    EXPECT_GE(knob.highest, knob.default_value) << knob.key;
    EXPECT_FALSE(std::string(knob.help).empty()) << knob.key;
    EXPECT_FALSE(TuningValue(defaults, knob.key).empty()) << knob.key;
  }
  EXPECT_EQ(keys.size(), 36u);
  EXPECT_TRUE(CheckOptions(EncoderOptions()).ok());
}

TEST(TuningKnobs, EachKeySetsItsOwnFieldAndReadsBack) {
  for (const TuningKnob& knob : TuningKnobs()) {
    EncoderTuning tuning;
    const std::string type = knob.type;
    // A value other than the default, inside the range.
    std::string value;
    if (type == "bool") {
      value = knob.default_value != 0 ? "false" : "true";
    } else {
      const double v = knob.default_value < knob.highest && knob.default_value + 1 <= knob.highest
                           ? knob.default_value + 1
                           : knob.lowest;
      value = type == "double" ? std::to_string(v) : std::to_string(static_cast<long long>(v));
    }
    ASSERT_TRUE(SetTuning(tuning, knob.key, value).ok()) << knob.key << "=" << value;
    EXPECT_NE(TuningValue(tuning, knob.key), TuningValue(EncoderTuning(), knob.key)) << knob.key;
    // No other knob moved.
    for (const TuningKnob& other : TuningKnobs()) {
      if (std::string(other.key) == knob.key) continue;
      EXPECT_EQ(TuningValue(tuning, other.key), TuningValue(EncoderTuning(), other.key))
          << knob.key << " moved " << other.key;
    }
    // What TuningValue prints, SetTuning reads back to the same value.
    EncoderTuning again;
    ASSERT_TRUE(SetTuning(again, knob.key, TuningValue(tuning, knob.key)).ok()) << knob.key;
    EXPECT_EQ(TuningValue(again, knob.key), TuningValue(tuning, knob.key)) << knob.key;
  }
}

TEST(TuningKnobs, RefusesUnknownKeysBadValuesAndValuesOutOfRange) {
  EncoderTuning tuning;
  Status s = SetTuning(tuning, "no_such_knob", "1");
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("unknown tuning key 'no_such_knob'"), std::string::npos);
  s = SetTuning(tuning, "window", "1.5");
  EXPECT_NE(s.message().find("tuning.window: '1.5' is not a whole number"), std::string::npos)
      << s.message();
  s = SetTuning(tuning, "window", "64 frames");
  EXPECT_FALSE(s.ok());
  s = SetTuning(tuning, "base_ahead", "yes");
  EXPECT_NE(s.message().find("is not true or false"), std::string::npos) << s.message();
  s = SetTuning(tuning, "proxy_fraction", "nan");
  EXPECT_NE(s.message().find("tuning.proxy_fraction must be in [0.001, 1]"), std::string::npos)
      << s.message();
  s = SetTuning(tuning, "node_spacing", "-0.1");
  EXPECT_NE(s.message().find("tuning.node_spacing must be >= 0"), std::string::npos) << s.message();
  // A refused value leaves the knob as it was.
  EXPECT_EQ(TuningValue(tuning, "node_spacing"), "0");
  EXPECT_EQ(TuningValue(tuning, "window"), "256");
}

TEST(TuningKnobs, CheckOptionsHoldsSetFieldsToTheSameRanges) {
  EncoderOptions options;
  options.tuning.deform_coarse_stiffness = 2000;
  Status s = CheckOptions(options);
  EXPECT_NE(s.message().find("tuning.deform_coarse_stiffness must be in [1, 1000]"),
            std::string::npos)
      << s.message();
  options = EncoderOptions();
  options.tuning.deform_backward_frames = -1;
  EXPECT_FALSE(CheckOptions(options).ok());
  options = EncoderOptions();
  options.tuning.transform_step = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(CheckOptions(options).ok());
}

TEST(TuningKnobs, DocsTuningIsTheTableTheKnobsDeclare) {
  const std::string path = std::string(MESHVID_GOLDEN_DIR) + "/../../docs/tuning.md";
  const std::string heading =
      "# Encoder tuning\n"
      "\n"
      "The encoder's internals, set with `meshvid encode --tune KEY=VALUE` (repeatable) or\n"
      "`--tune FILE.json` (an object of them), and in the library as `EncoderOptions::tuning`.\n"
      "Lengths are in scene units; 0 derives a length from frame 0's size (its bounding-box\n"
      "diagonal). Every default was chosen by measurement (`bench/`): change them to experiment,\n"
      "not to use the codec. The former flag is the one `meshvid encode` took before `--tune`,\n"
      "as older bench records name it (\"none\" for knobs added since).\n"
      "\n"
      "This page is generated from `MESHVID_ENCODER_TUNING` in `codec/enc/options.h`\n"
      "(`MESHVID_UPDATE_DOCS=1 ctest -R TuningKnobs` rewrites it); a test keeps the two equal.\n"
      "\n";
  const std::string expected = heading + TuningTableMarkdown();
  if (std::getenv("MESHVID_UPDATE_DOCS") != nullptr) {
    std::ofstream(path, std::ios::binary) << expected;
  }
  EXPECT_EQ(testing::ReadFile(path), expected)
      << "docs/tuning.md is stale: MESHVID_UPDATE_DOCS=1 ctest -R TuningKnobs";
}

}  // namespace
}  // namespace meshvid
