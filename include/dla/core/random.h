#pragma once
//! \file random.h
//! The random engine and the samples the walk draws from it.
//!
//! Every walker owns a stream derived from (run seed, walker number), so a walker draws the
//! same numbers whichever thread runs it and however often it is replayed.

#include <Eigen/Core>

#include <cmath>
#include <cstdint>

namespace dla {

//! SplitMix64: turns a seed into well-mixed 64-bit words (used to seed Rng).
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

//! xoshiro256++ (Blackman & Vigna): fast, 256-bit state, passes BigCrush.
class Rng {
 public:
  using result_type = std::uint64_t;

  //! The stream of walker `stream` in the run seeded with `seed`.
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0) {
    std::uint64_t sm = seed ^ (stream * 0xd1342543de82ef95ULL + 0x2545f4914f6cdd1dULL);
    for (auto& word : state_) word = splitmix64(sm);
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }

  result_type operator()() {
    const std::uint64_t result = rotl(state_[0] + state_[3], 23) + state_[0];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  //! Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

//! Uniform direction on the unit sphere (`dimensions` 3) or the unit circle in z = 0 (2),
//! without trigonometry: a point uniform in the unit disk by rejection, then Marsaglia's map
//! (3D) or the squaring map z -> z^2/|z|^2 (2D).
inline Eigen::Vector3d random_direction(Rng& rng, int dimensions) {
  double u, v, s;
  do {
    u = 2.0 * rng.uniform() - 1.0;
    v = 2.0 * rng.uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  if (dimensions == 2) return {(u * u - v * v) / s, 2.0 * u * v / s, 0.0};
  const double root = 2.0 * std::sqrt(1.0 - s);
  return {u * root, v * root, 1.0 - 2.0 * s};
}

}  // namespace dla
