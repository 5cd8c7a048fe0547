#pragma once
//! \file ballistic.h
//! Ballistic aggregation (Roberts 2001, "Sticky Pixels", section 3.4; Vold 1963): particles fly
//! along straight lines and stick where they first touch the structure. Lines come from
//! uniformly random directions, or all along one direction (deposition), spread uniformly over
//! the disk across them that the structure can touch. Each line is traced with the index's
//! bound on the distance to the structure (sphere tracing), and only next to the structure in
//! short stretches tested exactly. The result is the Cluster every model returns. See
//! docs/ballistic.md.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/models/walk.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dla {

//! Options of a ballistic run. Lengths are in scene units; the spacing sets the scale.
struct BallisticOptions {
  std::size_t particles = 10000;  //!< particles to attach, seeds not counted
  double spacing = 1.0;           //!< contact distance and distance to the parent, [1e-25, 1e25]
  std::uint64_t rng_seed = 1;     //!< seeds every random choice of the run
  int dimensions = 3;             //!< 3, or 2 for growth in the plane z = 0
  std::vector<Vec3> seeds = {Vec3::Zero()};  //!< one tree per seed
  //! Deposition: every particle flies along this direction (any length but 0; in z = 0 for
  //! 2D). Zero: each from a uniformly random direction.
  Vec3 direction = Vec3::Zero();
};

//! How the lines went, for the summary and the JSON record.
struct BallisticStats {
  std::uint64_t launched = 0;    //!< lines flown
  std::uint64_t missed = 0;      //!< lines that passed the structure without touching it
  std::uint64_t far_steps = 0;   //!< sphere-tracing steps, by the index's distance bound
  std::uint64_t near_steps = 0;  //!< short stretches next to the structure, tested exactly
};

inline void validate(const BallisticOptions& o) {
  detail::validate_seeded(o.particles, o.seeds, o.spacing, o.dimensions);
  if (!o.direction.allFinite()) throw InvalidInput("the direction is not finite");
  if (o.dimensions == 2 && o.direction.z() != 0.0)
    throw InvalidInput("the direction has a z component but growth in 2 dimensions is in the plane z = 0");
}

//! Grows a structure by ballistic aggregation with a given index (GridIndex, or BruteForceIndex
//! to test against). Does not validate. Calls `progress` every 256 particles and at the end;
//! `stop` ends growth early, the cluster marked incomplete. Throws PartialGrowth if the
//! structure outgrows the index.
template <class Index>
Cluster ballistic_with(const BallisticOptions& options, const ProgressFn& progress = {}, const StopFlag* stop = nullptr,
                       BallisticStats* stats = nullptr);

//! Validates the options and grows with the grid index.
Cluster ballistic(const BallisticOptions& options, const ProgressFn& progress = {}, const StopFlag* stop = nullptr,
                  BallisticStats* stats = nullptr);

}  // namespace dla
