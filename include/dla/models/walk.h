#pragma once
//! \file walk.h
//! The pieces of a Brownian walk in continuous space that do not depend on the structure:
//! the exterior return rule and the contact test of a short step. Growth models share them.

#include "dla/core/random.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dla {

class ParticleFeed;

//! Counters of DLA's walks, for the JSON sidecar and for tuning.
struct WalkStats {
  std::uint64_t walkers = 0;      //!< walkers launched (one per attached particle)
  std::uint64_t steps = 0;        //!< walk steps, all kinds
  std::uint64_t near_steps = 0;   //!< short steps next to the structure, with a contact test
  std::uint64_t contacts = 0;     //!< contacts, stuck or refused
  std::uint64_t returns = 0;      //!< walkers put back on the return sphere from outside it
  std::uint64_t relaunches = 0;   //!< walkers that escaped and started afresh
  std::uint64_t lost = 0;         //!< walkers on the wrong side of a constraint mesh, started afresh
  std::uint64_t rejected = 0;     //!< branches refused because they crossed the constraint mesh
  std::uint64_t clipped = 0;      //!< branches cut short at the constraint mesh
  //! Walkers that went back to the breakdown model's target electrode, or far away from it and
  //! the structure, and left it again (breakdown.h)
  std::uint64_t absorbed = 0;
};

//! Adds the counts of `s` to `total`.
inline void accumulate(WalkStats& total, const WalkStats& s) {
  total.walkers += s.walkers, total.steps += s.steps, total.near_steps += s.near_steps;
  total.contacts += s.contacts, total.returns += s.returns, total.relaunches += s.relaunches;
  total.lost += s.lost, total.rejected += s.rejected, total.clipped += s.clipped, total.absorbed += s.absorbed;
}

//! What a DLA run did beside the structure it grew (dla.h).
struct DlaStats {
  WalkStats walk;
  //! Walkers run again because a particle attached by an earlier walker on another thread
  //! changed their path.
  std::uint64_t replays = 0;
  //! Growing to fill a mesh (DlaOptions::fill): the fraction of its volume covered so far;
  //! else 0.
  double filled = 0.0;
  //! Where each particle goes as it attaches, seeds first, for another thread to work on while
  //! growth goes on (run.h); null: nowhere.
  ParticleFeed* feed = nullptr;
};

//! A unit vector orthogonal to unit vector n (Duff et al., "Building an orthonormal basis,
//! revisited", 2017).
inline Eigen::Vector3d orthogonal_unit(const Eigen::Vector3d& n) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  return {1.0 + sign * n.x() * n.x() * a, sign * n.x() * n.y() * a, -sign * n.x()};
}

//! Where a Brownian walker now at `offset` from the centre of a sphere of radius R < |offset|,
//! with nothing outside the sphere, first hits it; `returned` is false when it escapes to
//! infinity instead.
//!
//! In 3D it returns with probability R/r, at a point drawn from the exterior harmonic measure,
//! whose density on the sphere is proportional to |x - xi|^-3. In 2D (offset and result in
//! z = 0) it always returns, and the angle from the walker's direction is wrapped-Cauchy with
//! concentration R/r (the interior Poisson kernel at the Kelvin image of the walker).
struct ReturnPoint {
  bool returned;
  Eigen::Vector3d offset;  //!< from the sphere's centre, of length R
};

inline ReturnPoint return_to_sphere(const Eigen::Vector3d& offset, double R, Rng& rng,
                                    int dimensions) {
  constexpr double pi = 3.141592653589793238462643383279502884;
  const double r = offset.norm();
  const Eigen::Vector3d axis = offset / r;
  if (dimensions == 2) {
    const double q = R / r;
    const double theta = 2.0 * std::atan((1.0 - q) / (1.0 + q) * std::tan(pi * (rng.uniform() - 0.5)));
    const Eigen::Vector3d side(-axis.y(), axis.x(), 0.0);
    return {true, R * (std::cos(theta) * axis + std::sin(theta) * side)};
  }
  if (rng.uniform() * r >= R) return {false, Eigen::Vector3d::Zero()};
  // Inverse CDF of cos(theta): |x - xi|^-1 is uniform between 1/(r+R) and 1/(r-R).
  const double inv = 1.0 / (r + R) + rng.uniform() * (1.0 / (r - R) - 1.0 / (r + R));
  const double chord2 = 1.0 / (inv * inv);
  const double cos_theta = std::clamp((r * r + R * R - chord2) / (2.0 * r * R), -1.0, 1.0);
  const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
  const double phi = 2.0 * pi * rng.uniform();
  const Eigen::Vector3d u = orthogonal_unit(axis);
  const Eigen::Vector3d v = axis.cross(u);
  return {true, R * (cos_theta * axis + sin_theta * (std::cos(phi) * u + std::sin(phi) * v))};
}

//! Fraction t in [0, 1] of the step from `from` along `step` at which the moving point first
//! comes within `contact` of `center`, or a negative number if it does not. A point already in
//! contact and moving inwards touches at t = 0; one moving outwards does not touch.
inline double contact_along(const Eigen::Vector3d& from, const Eigen::Vector3d& step,
                            const Eigen::Vector3d& center, double contact) {
  const Eigen::Vector3d w = from - center;
  const double a = step.squaredNorm();
  const double b = w.dot(step);
  const double c = w.squaredNorm() - contact * contact;
  if (c <= 0.0) return b < 0.0 ? 0.0 : -1.0;
  if (b >= 0.0) return -1.0;
  const double disc = b * b - a * c;
  if (disc < 0.0) return -1.0;
  const double t = c / (-b + std::sqrt(disc));  // the smaller root, without cancellation
  return t <= 1.0 ? t : -1.0;
}

}  // namespace dla
