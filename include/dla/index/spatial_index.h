#pragma once
//! \file spatial_index.h
//! The nearest-particle look-up that the walk asks at every step, and the brute-force
//! reference implementation.
//!
//! An index reads positions from the particle store it was built on (it never copies them)
//! and must offer:
//!
//! \code
//!   Index(const std::vector<Particle>& particles, double spacing, int dimensions);
//!   bool insert(std::int32_t id);                 // particles[id] was appended; ids come in
//!                                                  // order. True if it opened a cell (below)
//!   void cover(const Vec3& center, double radius); // later queries lie in this ball
//!   Probe probe(const Vec3& x, Reach reach = Reach::set) const;
//!                                                  // Reach::skip: the probe's reach may be
//!                                                  // left unbounded
//!   void reserve(std::size_t particles);          // room for this many, made before growth
//!   bool holds(const Vec3& center, double radius) const;
//!                                                  // whether inserting or covering within the
//!                                                  // ball keeps the index's layout: probes on
//!                                                  // other threads may run meanwhile (dla.h;
//!                                                  // only GridIndex is used so)
//!   template <class Visit> void for_each_within(const Vec3& x, double radius, Visit&& visit) const;
//!                                                  // visit(id, squared distance) for every
//!                                                  // particle centre within radius of x
//!   Probe nearest(const Vec3& x) const;           // the exact nearest particle, however far,
//!                                                  // the lowest id among equally near ones
//!                                                  // (random drops, drop.h; grid and brute)
//!   double bound(const Vec3& x) const;            // a lower bound on the distance to the
//!                                                  // nearest particle, cheap (straight lines,
//!                                                  // ballistic.h; grid and brute)
//! \endcode
//!
//! GridIndex (grid_index.h) is the default; KdTreeIndex (kdtree_index.h) and BruteForceIndex
//! are there to compare against (tests, bench/).

#include "dla/core/cluster.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

//! What a probe knows of the nearest particle to a point.
struct Probe {
  std::int32_t nearest = -1;  //!< the nearest particle, or -1 if the index only has a bound
  double distance = std::numeric_limits<double>::infinity();  //!< exact distance to `nearest`,
                                                              //!< else a lower bound
  //! No particle inserted outside this box would change the answer, except one that opens a
  //! cell (insert() returns true) in the `opening` box: what a walker running ahead of others
  //! must check (dla.h). Unbounded unless the index says otherwise.
  Vec3 reach_min = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 reach_max = Vec3::Constant(std::numeric_limits<double>::infinity());
  //! Where only a particle that opens a cell would change the answer: coarse bounds that read
  //! which cells hold particles, not where the particles are. Empty unless the index says
  //! otherwise.
  Vec3 opening_min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 opening_max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  //! Sets the reach to the cube of half-side `radius` about x (around the ball that matters).
  Probe& reaching(const Vec3& x, double radius) {
    reach_min = x.array() - radius;
    reach_max = x.array() + radius;
    return *this;
  }
};

//! Whether p lies in the box [min, max] (an empty box, min above max, holds nothing).
inline bool in_box(const Vec3& p, const Vec3& min, const Vec3& max) {
  return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
}

//! Whether a probe must bound its reach. Only a walker running ahead of others reads it
//! (dla.h); on one thread the grid saves the few percent its boxes cost.
enum class Reach { skip, set };

//! Checks every particle: exact, O(n) per query. The reference the fast indexes are tested
//! against.
class BruteForceIndex {
 public:
  BruteForceIndex(const std::vector<Particle>& particles, double /*spacing*/, int /*dimensions*/)
      : particles_(particles) {}

  void reserve(std::size_t /*particles*/) {}
  bool holds(const Vec3& /*center*/, double /*radius*/) const { return true; }
  bool insert(std::int32_t id) {
    count_ = static_cast<std::size_t>(id) + 1;
    return true;
  }
  void cover(const Vec3& /*center*/, double /*radius*/) {}

  Probe probe(const Vec3& x, Reach /*reach*/ = Reach::set) const {  // the reach costs nothing here
    Probe result;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < count_; ++i) {
      const double d2 = (particles_[i].position - x).squaredNorm();
      if (d2 < best) {
        best = d2;
        result.nearest = static_cast<std::int32_t>(i);
      }
    }
    if (result.nearest >= 0) result.reaching(x, result.distance = std::sqrt(best));
    return result;
  }

  Probe nearest(const Vec3& x) const { return probe(x); }
  double bound(const Vec3& x) const { return probe(x).distance; }

  template <class Visit>
  void for_each_within(const Vec3& x, double radius, Visit&& visit) const {
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < count_; ++i) {
      const double d2 = (particles_[i].position - x).squaredNorm();
      if (d2 <= r2) visit(static_cast<std::int32_t>(i), d2);
    }
  }

 private:
  const std::vector<Particle>& particles_;
  std::size_t count_ = 0;
};

}  // namespace dla
