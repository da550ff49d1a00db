// Tests of the one writer and reader of numbers in the tools' JSON files (tools/json).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "tools/json/json_number.h"

namespace meshvid {
namespace {

TEST(JsonNumberTest, NonFiniteValuesRoundTrip) {
  const double inf = std::numeric_limits<double>::infinity();
  nlohmann::json j;
  j["exact"] = JsonNumber(inf);
  j["below"] = JsonNumber(-inf);
  j["unmeasured"] = JsonNumber(std::nan(""));
  j["psnr"] = JsonNumber(41.25);
  EXPECT_EQ(j.dump(), R"({"below":"-inf","exact":"inf","psnr":41.25,"unmeasured":null})");
  const nlohmann::json read = nlohmann::json::parse(j.dump());
  EXPECT_EQ(JsonNumber(read, "exact"), inf);
  EXPECT_EQ(JsonNumber(read, "below"), -inf);
  EXPECT_TRUE(std::isnan(JsonNumber(read, "unmeasured")));
  EXPECT_EQ(JsonNumber(read, "psnr"), 41.25);
}

TEST(JsonNumberTest, AMissingKeyIsNotMeasuredNeverZero) {
  const nlohmann::json j = nlohmann::json::parse(R"({"d1_psnr": 0})");
  EXPECT_EQ(JsonNumber(j, "d1_psnr"), 0);
  EXPECT_TRUE(std::isnan(JsonNumber(j, "d2_psnr")));
}

TEST(JsonNumberTest, WhatIsNotANumberIsAnErrorNamingTheKey) {
  const nlohmann::json j = nlohmann::json::parse(R"({"d1_psnr": "loud", "frames": [1]})");
  try {
    JsonNumber(j, "d1_psnr");
    FAIL() << "a string that is not inf was read as a number";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("d1_psnr"), std::string::npos);
  }
  EXPECT_THROW(JsonNumber(j, "frames"), std::invalid_argument);
}

}  // namespace
}  // namespace meshvid
