#pragma once
// The breakdown model's charges field (BreakdownField::charges, breakdown.h), after Kim, Sud and
// Lin's "Fast Simulation of Laplacian Growth" (2007), off the lattice. Private to libdla.
//
// Every particle is an equal point charge. Candidate sites sit a spacing from a particle, in six
// directions of a random frame; each keeps the sum of every charge's potential at it (1/r in 3D,
// -log r in 2D), updated as each particle attaches. With a target the structure and the target
// make a neutral capacitor: a plane by the charges' images across it, a point or a mesh by an
// opposite charge, the structure's total, on it. Site i's potential is then V_i = -U_i / n for
// U_i = sum_j G(c_i, x_j) - n T_i, T_i the target's potential per unit charge, and site i grows
// with weight ((U_max - U_i) / (U_max - U_min))^eta: the most screened site is at the
// structure's potential, as FSLG normalizes it.

#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/index/grid_index.h"
#include "dla/models/breakdown.h"
#include "dla/models/electrode.h"

#include "models/crew.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace dla::detail {

//! The sums of the charges' potentials at the candidate sites, kept in floats in spacings from
//! an origin, in blocks whose least and greatest U bound the draw. Every sum adds its terms in
//! one fixed order (a site's new charge after the last; a new site's charges in eight fixed
//! lanes), so the sums do not depend on the threads or on the width of the machine's vectors.
class ChargeField {
 public:
  //! Sites a block: the draw weighs blocks by their bound, then sites within one.
  static constexpr std::size_t kBlock = 256;

  //! `mirror_axis` >= 0: every charge has an opposite image across the plane where that axis
  //! is `mirror_at` (scene units).
  ChargeField(const Vec3& origin, double spacing, int dimensions, int mirror_axis = -1, double mirror_at = 0.0);

  //! A charge at p: every site's sum gains its potential, and sites nearer p than a spacing
  //! close. Runs on `crew`'s threads when there are many sites.
  void add_charge(const Vec3& p, Crew& crew);
  //! New sites at `at` beside particle `parent`, each with its target's potential per unit
  //! charge, summed over every charge so far (less their images); one job a site on `crew`.
  void add_sites(const std::vector<Vec3>& at, std::int32_t parent, const std::vector<double>& target_potential,
                 Crew& crew);
  //! The target's charge is gone (a point struck and buried): U is the charges' sum alone.
  void drop_target();

  //! Sites so far, closed ones among them until compact_if_sparse() drops them.
  std::size_t sites() const { return used_; }
  std::size_t open_sites() const { return open_count_; }
  bool open(std::size_t site) const { return open_[site] != 0; }
  const Vec3& at(std::size_t site) const { return at_[site]; }
  std::int32_t parent(std::size_t site) const { return parent_[site]; }
  //! The sum of every charge's potential at the site, less their images'.
  float sum(std::size_t site) const { return sum_[site]; }
  //! U: the sum, less n times the target's potential per unit charge.
  float u(std::size_t site) const { return sum_[site] - n_target() * target_[site]; }

  //! One open site by weight ((U_max - U) / (U_max - U_min))^eta (all alike when U is the same
  //! everywhere); -1 when none is open. Exact: a block is drawn by its size times its bound, a
  //! site in it uniformly, and kept with its weight over the bound (at most kBlock tries on
  //! average, far fewer where a block's sites are alike).
  std::ptrdiff_t draw(Rng& rng, double eta) const;
  void close(std::size_t site);
  //! Drops the closed sites when they outnumber the open ones, keeping the open ones' order.
  void compact_if_sparse();

 private:
  float n_target() const { return target_on_ ? static_cast<float>(charges_) : 0.0f; }
  void push_padding_block();
  //! Recomputes blocks [first, last)'s bounds and open counts from the sums.
  void bound_blocks(std::size_t first, std::size_t last);
  //! Runs job(first, last) over the blocks, split among `crew`'s threads when worth it.
  void over_blocks(Crew& crew, const std::function<void(std::size_t, std::size_t)>& job);
  float scaled(const Vec3& p, int axis) const { return static_cast<float>((p[axis] - origin_[axis]) / spacing_); }

  Vec3 origin_;
  double spacing_;
  int dimensions_;
  int mirror_axis_;
  float mirror_at_;  // in spacings from the origin
  bool target_on_ = true;
  std::size_t charges_ = 0;
  std::vector<float> charge_x_, charge_y_, charge_z_;  // the charges, for new sites' sums
  // Per site, in blocks of kBlock: closed padding sites far away fill the last one.
  std::size_t used_ = 0;
  std::vector<float> x_, y_, z_, sum_, target_;
  std::vector<float> open_;  // 1 open, 0 closed: a float, so the loops stay in one width
  std::vector<Vec3> at_;
  std::vector<std::int32_t> parent_;
  std::vector<float> block_low_, block_high_;          // per block: the least and greatest U open
  std::vector<std::uint32_t> block_open_;
  std::size_t open_count_ = 0;
};

// --- Shared by the point-charge fields (charges, conductor) -------------------------------------

// Streams of their own, apart from the walkers field's: the draw of particle k, the frame of
// particle id's sites, and the points that carry a target mesh's charge.
inline constexpr std::uint64_t kChoiceStreams = std::uint64_t{1} << 63;
inline constexpr std::uint64_t kFrameStreams = std::uint64_t{1} << 62;
inline constexpr std::uint64_t kTargetStreams = kFrameStreams + (std::uint64_t{1} << 61);

//! The points a point or mesh target's charge is spread over, evenly: a point's one, or 512
//! drawn uniformly by area over a mesh; none for a plane or without a target.
std::vector<Vec3> target_charge_points(const Target& target, std::uint64_t rng_seed);

//! Whether a particle at c, next to `parent`, is a spacing from every other one.
bool free_at(const GridIndex& index, const Vec3& c, std::int32_t parent, double spacing);

//! The candidate sites beside particle `id` at `from` into `out`: a spacing away in the six
//! directions of its own random frame (an octahedron's in 3D, a hexagon's in 2D, a frame a
//! particle so that no direction is favoured over the structure), where the mesh allows a
//! branch and no other particle is nearer than a spacing.
void sites_beside(std::int32_t id, const Vec3& from, const DlaOptions& walk, const MeshConstraint* constraint,
                  const GridIndex& index, std::vector<Vec3>& out);

//! The growth loop of both point-charge fields: seed() puts the seeds in, then attach(k) adds
//! particle k, up to the walk's count. The first particle within a spacing of `electrode`
//! (null: none) is the strike, which ends growth, or with `stop_at_strike` off and a point
//! target, calls point_struck(). Ctrl-C and a false from `progress` keep what grew, marked
//! incomplete; a failure part way throws PartialGrowth. `stats` gets the strike and channel.
void grow_until_done(Cluster& cluster, const DlaOptions& walk, const BreakdownOptions& options,
                     const Electrode* electrode, const ProgressFn& progress, const StopFlag* stop,
                     BreakdownStats& stats, const std::function<void()>& seed,
                     const std::function<void(std::size_t)>& attach, const std::function<void()>& point_struck);

//! Grows the breakdown model with the charges field; breakdown() validates first.
Cluster grow_by_charges(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                        const ProgressFn& progress, const StopFlag* stop, BreakdownStats& stats);

}  // namespace dla::detail
