#pragma once
// Space colonization's step (colonization.h): the noise, the fixed-point directions and where a
// node grows next, shared by colonize() (colonization.cpp) and the tests' brute-force rescan.
// Private to libdla.

#include "dla/models/colonization.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace dla {

namespace detail {

//! Smooth, seeded vector noise: in each coordinate, values at the integer lattice points
//! (hashed from the seed) blended with a smoothstep, each in [-1, 1].
class LatticeNoise {
 public:
  explicit LatticeNoise(std::uint64_t seed) : seed_(seed) {}

  Vec3 operator()(const Vec3& p) const {
    const Vec3 floor = p.array().floor();
    const Vec3 f = p - floor;
    const Vec3 w = f.array() * f.array() * (3.0 - 2.0 * f.array());
    Vec3 sum = Vec3::Zero();
    for (int corner = 0; corner < 8; ++corner) {
      double weight = 1.0;
      std::array<std::int64_t, 3> cell{};
      for (int axis = 0; axis < 3; ++axis) {
        const bool high = (corner >> axis) & 1;
        weight *= high ? w[axis] : 1.0 - w[axis];
        cell[static_cast<std::size_t>(axis)] = static_cast<std::int64_t>(floor[axis]) + high;
      }
      if (weight == 0.0) continue;
      std::uint64_t h = seed_ ^ (static_cast<std::uint64_t>(cell[0]) * 0x9e3779b97f4a7c15ULL) ^
                        (static_cast<std::uint64_t>(cell[1]) * 0xc2b2ae3d27d4eb4fULL) ^
                        (static_cast<std::uint64_t>(cell[2]) * 0x165667b19e3779f9ULL);
      for (int axis = 0; axis < 3; ++axis)
        sum[axis] += weight * (static_cast<double>(splitmix64(h) >> 11) * 0x1.0p-52 - 1.0);
    }
    return sum;
  }

 private:
  std::uint64_t seed_;
};

//! A unit direction in fixed point (2^-40 steps): sums of them are exact in any order.
inline std::array<std::int64_t, 3> fixed_direction(const Vec3& from, const Vec3& to) {
  const Vec3 unit = (to - from).normalized();
  // Adding and taking away 1.5 * 2^52 rounds to the nearest integer inline (|x| <= 2^40),
  // where llround is a call.
  const auto round = [](double x) { return static_cast<std::int64_t>((x * 0x1.0p40 + 0x1.8p52) - 0x1.8p52); };
  return {round(unit.x()), round(unit.y()), round(unit.z())};
}
//! The squared kill distance and influence radius in scene units (infinity: unbounded).
inline double kill_distance2(const ColonizationOptions& o) { return std::pow(o.kill_distance * o.spacing, 2); }
inline double reach2(const ColonizationOptions& o) {
  const double influence = influence_of(o);
  return std::isfinite(influence) ? std::pow(influence * o.spacing, 2) : std::numeric_limits<double>::infinity();
}

}  // namespace detail

//! Where node `v` grows next, given the sum of unit directions to its attractors (fixed
//! point); false when it does not grow (they cancel out, or the tropism cancels them).
inline bool colonization_step(const ColonizationOptions& o, const detail::LatticeNoise& noise, const Vec3& from,
                              const std::array<std::int64_t, 3>& sum, Vec3* to) {
  Vec3 direction(static_cast<double>(sum[0]), static_cast<double>(sum[1]), static_cast<double>(sum[2]));
  if (direction.squaredNorm() == 0.0) return false;
  direction = direction.normalized() + o.tropism;
  if (o.dimensions == 2) direction.z() = 0.0;
  if (direction.squaredNorm() < 1e-12) return false;
  Vec3 next = from + o.spacing * direction.normalized();
  if (o.noise_amplitude > 0.0) {
    Vec3 shift = noise(next / (o.noise_scale * o.spacing)) * (o.noise_amplitude * o.spacing);
    if (o.dimensions == 2) shift.z() = 0.0;
    next += shift;
  }
  if (o.collide) {
    next = o.collide->apply(from, next, o.spacing);
    if ((next - from).squaredNorm() < 0.01 * o.spacing * o.spacing) return false;
  }
  if (o.vessel) {
    const BranchCheck check = o.vessel->check_branch(from, next);
    if (!check.accepted) return false;
    next = check.end;
  }
  *to = next;
  return true;
}

}  // namespace dla
