#pragma once
//! \file aggregate.h
//! Aggregates of clusters (`dla3d aggregate`): soot, dust, colloids and flocs, where clusters
//! meet clusters rather than one particle a structure. Monomers (spheres of one radius or of a
//! lognormal or normal spread) start at random in a periodic box and join as they touch:
//! - dlca: clusters diffuse, a cluster of N monomers as often as N^mobility_exponent, and stick
//!   at first contact (diffusion-limited cluster-cluster aggregation);
//! - rlca: at stick_probability 0, the reaction-limited limit: no box; two clusters join as
//!   often as the monomers they offer to bond (the sum kernel N_i + N_j), at a contact drawn at
//!   random over every way they can touch (Jullien and Kolb 1984). Above 0, as dlca, but a
//!   contact sticks where it was made only with that chance, else at a random contact;
//! - ballistic: clusters fly straight, as fast as N^mobility_exponent, turning after a box length;
//! - tuned: no box; clusters are joined two at a time so that every one of them has
//!   N = k_f (R_g / a)^D_f exactly (Filippov et al. 2000; FracVAL, Morán et al. 2019).
//!
//! The result is the Cluster every model returns: the monomers in breadth-first order of the
//! contacts that joined them from the one nearest the centre of mass (each one's parent is a
//! monomer it touches), centred on the origin, with each monomer's radius in Cluster::radii.
//! See docs/aggregate.md.

#include "dla/core/cluster.h"
#include "dla/core/option_description.h"
#include "dla/core/words.h"

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace dla {

//! How clusters meet (`--mode`).
enum class AggregateMode { dlca, rlca, ballistic, tuned };
inline constexpr WordTable<AggregateMode, 4> kAggregateModeWords{
    "aggregation mode",
    {{{AggregateMode::dlca, "dlca"}, {AggregateMode::rlca, "rlca"}, {AggregateMode::ballistic, "ballistic"},
      {AggregateMode::tuned, "tuned"}}}};
constexpr const auto& words_of(AggregateMode) { return kAggregateModeWords; }

//! How the monomers' radii spread (`--sizes`).
enum class MonomerSizes {
  one,        //!< every monomer `radius`
  lognormal,  //!< geometric mean `radius`, geometric standard deviation `spread` (> 1 spreads)
  normal,     //!< mean `radius`, standard deviation `spread` * `radius`, cut at a tenth of the mean
};
inline constexpr WordTable<MonomerSizes, 3> kMonomerSizesWords{
    "monomer sizes",
    {{{MonomerSizes::one, "one"}, {MonomerSizes::lognormal, "lognormal"}, {MonomerSizes::normal, "normal"}}}};
constexpr const auto& words_of(MonomerSizes) { return kMonomerSizesWords; }

//! The most monomers an aggregate may have (about 60 bytes each while it grows).
inline constexpr double kMaxMonomers = 1e8;
//! The box's volume fraction at most: random sequential addition, which places the monomers,
//! jams near 0.38 in 3D (Widom 1966); well below, a box fills quickly.
inline constexpr double kMaxVolumeFraction = 0.3;

struct AggregateOptions {
  AggregateMode mode = AggregateMode::dlca;
  std::size_t monomers = 1000;        //!< N, the monomers of the aggregate
  double monomer_radius = 1.0;        //!< a: the monomers' (geometric) mean radius, scene units
  MonomerSizes sizes = MonomerSizes::one;
  double spread = 1.0;                //!< lognormal: the geometric standard deviation (1: none);
                                      //!< normal: the standard deviation over the mean
  double overlap = 0.0;               //!< touching monomers' centres (1 - overlap)(r_i + r_j) apart
  double volume_fraction = 0.01;      //!< the box's modes: the monomers' share of the box
  double stick_probability = 0.0;     //!< rlca: 0, the reaction-limited limit (no box); above, in the
                                      //!< box, the chance that a contact sticks where it is made, else
                                      //!< at a contact drawn at random
  double mobility_exponent = -0.5;    //!< a cluster of N moves as often as N^this
  double df = 1.8;                    //!< tuned: the fractal dimension D_f
  double kf = 1.3;                    //!< tuned: the prefactor k_f
  std::uint64_t rng_seed = 1;         //!< seeds every random choice
  int threads = 1;                    //!< the box: threads that test a large cluster's moves; the
                                      //!< aggregate does not depend on it
};

//! The aggregate's options, described once (option_description.h).
const OptionTable<AggregateOptions>& aggregate_option_table();

//! Throws InvalidInput, in one line naming the option, for options that cannot work: a range
//! left, a spread that means nothing to `sizes`, tuned targets that monomers cannot meet.
void validate(const AggregateOptions& options);

//! What growing the aggregate counted.
struct AggregateStats {
  std::uint64_t moves = 0;     //!< clusters moved (the box)
  std::uint64_t contacts = 0;  //!< contacts met, stuck or not
  std::uint64_t tries = 0;     //!< tuned and rlca without a box: placements tried
  std::uint64_t approaches = 0;  //!< rlca without a box: joins made along a line, as no random
                                 //!< contact drawn fitted
  double box = 0.0;            //!< the box's side, scene units (0: none)
  //! R_g / a beyond which a cluster feels the box's other clusters crowd it (a quarter of the
  //! box's side): fit_joins leaves such clusters out. Infinite without a box.
  double crowded = std::numeric_limits<double>::infinity();
  //! Each cluster a join made, as N and R_g / a (R_g of the centres): what the fractal law is
  //! fitted to (fit_fractal_law).
  std::vector<std::pair<double, double>> joins;
};

//! Grows the aggregate; `progress` sees the largest cluster so far. Stopped (`progress`
//! returning false, or `stop`), it returns that cluster, marked incomplete. Throws InvalidInput
//! when the tuned targets cannot be met with these monomers.
Cluster aggregate(const AggregateOptions& options, const ProgressFn& progress = {}, const StopFlag* stop = nullptr,
                  AggregateStats* stats = nullptr);

//! The fractal law N = k_f (R_g / a)^D_f fitted by least squares in log-log to clusters given
//! as (N, R_g / a) pairs; R_g is that of the monomers' centres (radius_of_gyration, cluster.h),
//! a the monomers' mean radius.
struct FractalLaw {
  double dimension = 0.0;  //!< D_f
  double prefactor = 0.0;  //!< k_f
};
FractalLaw fit_fractal_law(const std::vector<std::pair<double, double>>& sizes_and_radii);

//! The fractal law of the clusters an aggregate's joins made, those of at least `least`
//! monomers and not crowded by the box: the aggregate's D_f and k_f.
FractalLaw fit_joins(const AggregateStats& stats, double least = 16.0);

}  // namespace dla
