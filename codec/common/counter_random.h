// Counter-based random numbers: a value is a pure function of (seed, counters), so results do
// not depend on thread count or scheduling. Used by the simulator's sensor noise and the
// evaluation's surface sampling.
#ifndef MESHVID_CODEC_COMMON_COUNTER_RANDOM_H_
#define MESHVID_CODEC_COMMON_COUNTER_RANDOM_H_

#include <cstdint>

namespace meshvid {

/// SplitMix64's finaliser: a strong 64-bit mix of `x`.
constexpr std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Uniform in [0, 1) from the top 53 of 64 random bits.
constexpr double UniformClosedOpen(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// Uniform in (0, 1) (never 0, so its logarithm is finite) from 64 random bits.
constexpr double UniformOpen(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_COUNTER_RANDOM_H_
