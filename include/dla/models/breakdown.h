#pragma once
//! \file breakdown.h
//! The dielectric breakdown model (Niemeyer, Pietronero and Wiesmann 1984), off the lattice:
//! the structure is a conductor at one potential, a target electrode (or, without one, space
//! far away) at the other, and growth goes where the field is strong, in proportion to the
//! field to the power eta. eta = 1 is DLA, eta -> 0 a compact Eden-like blob, eta of 2 and up
//! sparse straight channels: lightning, Lichtenberg figures. See docs/breakdown.md.
//!
//! The field comes from DLA's own walkers (dla.h): the density of walkers' first contacts on the
//! structure is the field on its surface (the harmonic measure). Before each particle attaches,
//! `walkers` walkers run against the structure as it is; each parent particle is a growth site
//! weighted by its contacts to the power eta; one site is drawn by weight, and one of its
//! contacts, at random, is the new particle. At eta = 1 that is one walker's contact, drawn
//! uniformly: DLA by the same contact law, and with one walker the same structure as `dla3d`.
//! With a target, walkers leave from it and one that comes back to it starts again (the
//! excursion measure of the target, whose first contacts are the field of the capacitor).
//! `field = conductor` solves for the point charges that hold the structure at one potential
//! (the charge on a conductor is its harmonic measure): fast at any eta, with the model's
//! dimensions. `field = charges` gives every particle the same charge (FSLG): faster, but too
//! weakly screened to have the model's dimensions (docs/breakdown.md).

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/option_description.h"
#include "dla/core/options.h"
#include "dla/mesh/constraint.h"
#include "dla/models/walk.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace dla {

//! How the field on the structure is measured (`--field walkers|conductor|charges`);
//! docs/breakdown.md.
enum class BreakdownField {
  //! DLA's walkers' first contacts (the harmonic measure): exact, insulators shape the field,
  //! and at eta 1 it is DLA; the walkers a particle needs grow with eta
  walkers,
  //! a point charge a particle, solved so that the structure is one conductor: a particle
  //! grows with weight charge^eta, then one of its sites by its potential^eta; a cost that does
  //! not grow with eta, a field that ignores insulators (they still stop growth)
  conductor,
  //! every particle an equal point charge, the potential summed at candidate sites a spacing
  //! from the structure, updated as each particle attaches (Kim, Sud and Lin's FSLG): a cost
  //! that does not grow with eta, a field that ignores insulators and the charge's crowding
  //! on the tips
  charges,
};
inline constexpr WordTable<BreakdownField, 3> kBreakdownFieldWords{
    "field",
    {{{BreakdownField::walkers, "walkers"}, {BreakdownField::conductor, "conductor"},
      {BreakdownField::charges, "charges"}}}};
constexpr const auto& words_of(BreakdownField) { return kBreakdownFieldWords; }

//! The electrode at the other potential (`target_point`, `target_plane`, `target_mesh`).
enum class TargetKind {
  none,   //!< space far away: walkers come from a sphere around the structure, as DLA's
  point,  //!< a small ball at `target.point`, half a spacing across
  plane,  //!< the plane `target.axis` = `target.at` (a line in 2D): the ground
  mesh,   //!< the surface of `target.mesh` (a lightning rod, a second object), in 3D
};
inline constexpr WordTable<TargetKind, 4> kTargetKindWords{
    "target",
    {{{TargetKind::none, "none"}, {TargetKind::point, "point"}, {TargetKind::plane, "plane"}, {TargetKind::mesh, "mesh"}}}};
constexpr const auto& words_of(TargetKind) { return kTargetKindWords; }

struct Target {
  TargetKind kind = TargetKind::none;
  Vec3 point = Vec3::Zero();  //!< point: its centre
  Axis axis = Axis::y;        //!< plane: the axis across it (x or y in 2D)
  double at = 0.0;            //!< plane: where it crosses the axis, scene units
  //! mesh: the electrode as a constraint whose growing side is where walkers leave it
  //! (Side::outside for a closed rod, Side::both for a plate, which sends them from both faces);
  //! it must outlive growth. It does not constrain the walk.
  const MeshConstraint* mesh = nullptr;
};

//! Options of the breakdown model beside the walk's (DlaOptions). Lengths are in scene units.
//! Ranges and help: breakdown_option_table().
struct BreakdownOptions {
  double eta = 1.0;  //!< the field's exponent; 1: DLA
  BreakdownField field = BreakdownField::walkers;
  //! Walkers measured before each particle attaches; 0: one at eta 1, else
  //! default_breakdown_walkers(eta). More sharpen the field (docs/breakdown.md: the bias). The
  //! walkers field's alone: 0 with the others.
  int walkers = 0;
  Target target;
  //! End growth when a particle comes within a spacing of the target (the strike). Else growth
  //! goes on to its count: from a plane, walkers still leave it; a point, touched, is at the
  //! structure's potential, and walkers come from the spawn, as without a target.
  bool stop_at_strike = true;
};

inline constexpr int kMaxBreakdownWalkers = 4096;
inline constexpr double kMaxEta = 10.0;

//! The breakdown model's own options, described once (option_description.h): the CLI's
//! Discharge group, Python's keywords, validate()'s ranges and `dla3d options` read it.
inline const OptionTable<BreakdownOptions>& breakdown_option_table() {
  using O = BreakdownOptions;
  static const OptionTable<O> table{
      real("eta", &O::eta, closed(0.0, kMaxEta), "", "Discharge",
           "the field's exponent: growth goes where the field^eta is strong; 1 is DLA, 0 compact, 2 to 4 lightning"),
      word("field", &O::field, "Discharge",
           "how the field is measured: walkers (DLA's first contacts: exact, insulators shape it, slower as eta "
           "grows), conductor (3D: point charges that hold the structure at one potential: fast at any eta, the "
           "model's dimensions, blind to insulators) or charges (equal point charges: fastest, too dense a "
           "structure); docs/breakdown.md"),
      integer("walkers", &O::walkers, closed(1, kMaxBreakdownWalkers), "", "Discharge",
              "walkers that measure the field before each particle (more: a sharper field, slower); by eta, 1 at "
              "eta 1, 8 below, doubling with each step of eta above, to 64",
              SpecialValue{0, "chosen by eta"}),
      flag("stop_at_strike", &O::stop_at_strike, "Discharge",
           "end growth when a particle comes within a spacing of the target (the strike)", "no_stop_at_strike"),
  };
  return table;
}

//! The first batch of walkers a particle's field is measured with by default: 8 up to eta 1,
//! doubling with each whole step of eta past it, to 64. Growth stops at the first batch in
//! which a site has weight, which favours lucky sites the more, the smaller the batch; past
//! eta 2 a site needs hundreds of walkers to have weight anyway, so a larger batch costs little
//! (docs/breakdown.md: the bias).
inline int default_breakdown_walkers(double eta) {
  return eta <= 1.0 ? 8 : eta <= 2.0 ? 16 : eta <= 3.0 ? 32 : 64;
}

//! The walkers measured before each particle for these options.
inline int walkers_for(const BreakdownOptions& o) {
  return o.walkers > 0 ? o.walkers : o.eta == 1.0 ? 1 : default_breakdown_walkers(o.eta);
}

//! What a breakdown run did beside the structure.
struct BreakdownStats {
  WalkStats walk;                 //!< every walker's steps, contacts and relaunches
  std::uint64_t absorbed = 0;     //!< walkers that came back to the target and started again
  std::int32_t strike = -1;       //!< the first particle within a spacing of the target; -1: none
  std::uint64_t channel = 0;      //!< particles on the main channel, the seed to the strike; 0: none
  //! growth sites weighed, summed over the attachments: touched parents (walkers), free
  //! candidate sites (charges), or the chosen parents' free sites (conductor)
  std::uint64_t sites = 0;
  //! conductor: the charges solved afresh by conjugate gradients
  std::uint64_t solves = 0;
  //! Where each particle goes as it attaches, seeds first (walk.h's DlaStats::feed); null: nowhere.
  ParticleFeed* feed = nullptr;
};

//! Throws InvalidInput at the first option that cannot work: eta, walkers, the target against
//! the walk's dimensions, seeds and spacing (electrodes that touch).
void validate(const BreakdownOptions& options, const DlaOptions& walk);

//! Grows a discharge from `walk.seeds` (the source) with DLA's walk options, constrained by
//! `constraint` if given (an insulator walkers cannot cross). Validates first. The cluster's
//! `strike` is the particle that reached the target (-1: none). Ctrl-C (`stop`) and a false
//! from `progress` keep what grew, marked incomplete. The result is the same for every
//! `walk.threads`, byte for byte. Throws PartialGrowth when growth fails part way.
Cluster breakdown(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                  const ProgressFn& progress = {}, const StopFlag* stop = nullptr, BreakdownStats* stats = nullptr);

namespace detail {
//! The particles on the main channel, from the strike back to its seed; 0 without a strike.
inline std::uint64_t channel_length(const Cluster& cluster) {
  std::uint64_t length = 0;
  for (std::int32_t i = cluster.strike; i >= 0; i = cluster.particles[static_cast<std::size_t>(i)].parent) ++length;
  return length;
}
}  // namespace detail

}  // namespace dla
