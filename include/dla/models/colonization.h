#pragma once
//! \file colonization.h
//! Space colonization (Runions et al. 2005; the "Hyphae" write-up): attractor points pull the
//! nearest node of a growing tree, one step at a time, and die when a node comes close. The
//! result is the Cluster that DLA returns (roots as seeds), so every look and writer applies.
//! See docs/colonization.md.
//!
//! Each iteration:
//! 1. each live attractor knows its closest node (within the influence radius, if finite);
//! 2. each node that some attractors chose grows one step along the normalised sum of the
//!    unit directions to them, plus the tropism, moved by the noise;
//! 3. attractors within the kill distance of a new node die;
//! until no attractor is left, no node grows, or a limit is met. With closed venation
//! (closed_venation.h), step 1 pulls every node of each attractor's relative neighbourhood, and
//! step 3 removes an attractor once all of them have reached it, linking them there.
//!
//! The closest nodes are kept, not rescanned: each iteration's new nodes update only the
//! attractors they come closer to than their current node, found in an index over the
//! attractors that skips whole ranges no new node can change (attractor_tree.h). The sums of
//! directions are kept per node in fixed point, exact whatever the order of updates: the result
//! is the full rescan's, node for node.

#include "dla/core/cluster.h"
#include "dla/mesh/constraint.h"
#include "dla/core/errors.h"
#include "dla/core/option_description.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/index/attractor_tree.h"
#include "dla/models/closed_venation.h"
#include "dla/models/model_shell.h"
#include "dla/mesh/surface_distance.h"
#include "dla/core/words.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! Where scattered attractors lie (`--attractors-in`).
enum class AttractorRegion {
  sphere,   //!< a ball (a disk in 2D) of `radius` around `center`
  box,      //!< the box [box_min, box_max] (a rectangle in z = 0 in 2D)
  mesh,     //!< uniform in a mesh's enclosed volume (3D)
  surface,  //!< uniform by area on a mesh's surface, half a spacing inside it (3D)
};
inline constexpr WordTable<AttractorRegion, 4> kAttractorRegionWords{
    "attractor region",
    {{{AttractorRegion::sphere, "sphere"}, {AttractorRegion::box, "box"}, {AttractorRegion::mesh, "mesh"},
      {AttractorRegion::surface, "surface"}}}};
constexpr const auto& words_of(AttractorRegion) { return kAttractorRegionWords; }

//! The most attractors a tree grows among.
constexpr std::size_t kMaxAttractors = 100'000'000;

//! Attractors scattered at random, seeded.
struct AttractorOptions {
  std::size_t count = 10000;                  //!< how many, 1 to kMaxAttractors (10^8)
  AttractorRegion region = AttractorRegion::sphere;
  Vec3 center = Vec3::Zero();                 //!< the sphere's centre, scene units
  double radius = 50.0;                       //!< the sphere's radius, scene units, > 0
  Vec3 box_min = Vec3::Constant(-50.0);       //!< the box's corners, scene units
  Vec3 box_max = Vec3::Constant(50.0);
  //! Grading towards the sphere's centre, >= 0: 0 is uniform; f puts a point at radius
  //! R u^((1 + f) / d) for u uniform in [0, 1) (d the dimensions), denser towards the centre
  //! as f grows, so that roots spread out do not run dry (the Hyphae write-up's fourth test).
  double falloff = 0.0;
  //! With the `surface` region, only its part painted this colour (`attractor_paint`): the
  //! tree grows towards what was painted.
  std::optional<Paint> paint;
};

//! Where the attractors lie, described once (option_description.h); their count, centre, box,
//! file and paint are the front ends'.
inline const OptionTable<AttractorOptions>& attractor_option_table() {
  using O = AttractorOptions;
  static constexpr std::string_view group = "Attractors and roots";
  static const OptionTable<O> table{
      word("attractors_in", &O::region, group,
           "where they lie: sphere, box, mesh (inside the --stl vessel, else the --collide mesh) or surface (on it)"),
      real("attractor_radius", &O::radius, closed(1e-300, 1e300), "scene units", group, "the sphere's radius"),
      real("attractor_falloff", &O::falloff, closed(0, 100), "", group,
           "grading towards the sphere's centre: 0 is uniform, more is denser towards it"),
  };
  return table;
}

inline void validate(const AttractorOptions& o) {
  require_in_ranges(attractor_option_table(), o);
  if (o.count < 1 || o.count > kMaxAttractors)
    throw InvalidInput("attractors " + std::to_string(o.count) + " is not in [1, 1e8]");
  // Whether the points fit the tree's spacing is colonize()'s to check.
  if (!o.center.allFinite() || !o.box_min.allFinite() || !o.box_max.allFinite())
    throw InvalidInput("the attractors' centre or box is not finite");
  if (o.region == AttractorRegion::box && !(o.box_min.array() < o.box_max.array()).head<2>().all())
    throw InvalidInput("the attractor box's min corner is not below its max corner");
  if (o.paint && o.region != AttractorRegion::surface)
    throw InvalidInput("`attractor_paint` puts the attractors on the painted part of the surface: `attractors_in` surface");
}

//! `options.count` points drawn with the generator seeded by `seed`, in z = 0 for 2D. The
//! `mesh` and `surface` regions draw from `mesh` (a solid one: a vessel or a collision object's),
//! in 3D only; throws InvalidInput without one.
std::vector<Vec3> scatter_attractors(const AttractorOptions& options, std::uint64_t seed, int dimensions,
                                     const MeshConstraint* mesh = nullptr);

//! `count` of `points` (attractors read from a file) chosen at random without repeats, in
//! their order, with the generator seeded by `seed`. Throws InvalidInput if there are fewer.
std::vector<Vec3> sample_attractors(const std::vector<Vec3>& points, std::size_t count, std::uint64_t seed);

//! What a collision object does to a new node (`--collision`).
enum class CollisionMode {
  push,   //!< a node that would lie inside the object goes to its surface: growth flows around it
  stick,  //!< every new node goes to the surface: growth crawls over it (veins on an arm)
};
inline constexpr WordTable<CollisionMode, 2> kCollisionModeWords{
    "collision",
    {{{CollisionMode::push, "push"}, {CollisionMode::stick, "stick"}}}};
constexpr const auto& words_of(CollisionMode) { return kCollisionModeWords; }

//! A collision object: a mesh given as a signed distance, negative inside. The distance is the
//! exact one to the closest point of a triangle (surface_distance.h); the sign is the winding
//! number of the repaired mesh (inside_test.h), right on open and self-intersecting meshes.
class CollisionObject {
 public:
  //! Repairs `mesh` as a constraint inside it would (closing holes), for `spacing`.
  CollisionObject(const TriangleMesh& mesh, double spacing, CollisionMode mode)
      : solid_(mesh, ConstraintOptions{}, spacing), mode_(mode) {}

  CollisionMode mode() const { return mode_; }
  const TriangleMesh& mesh() const { return solid_.mesh(); }
  //! The object as a solid: attractors and roots can be drawn in it or on its surface.
  const MeshConstraint& solid() const { return solid_; }

  //! The signed distance at p (negative inside), and the surface's closest point.
  double signed_distance(const Vec3& p, Vec3* closest = nullptr) const {
    const Vec3 c = solid_.surface().closest_point(p);
    if (closest) *closest = c;
    const double d = (p - c).norm();
    return inside(p) ? -d : d;
  }

  //! Where a new node stepping from `from` to p goes. With push, onto the surface if p is
  //! inside. With stick, onto the surface (p - sdf(p) grad(p), the closest point), and then a
  //! whole `step` along the surface that way: a step into the surface would otherwise shrink to
  //! nothing, and the veins to a heap of twigs.
  Vec3 apply(const Vec3& from, const Vec3& p, double step) const {
    if (mode_ == CollisionMode::push) return inside(p) ? solid_.surface().closest_point(p) : p;
    const Vec3 closest = solid_.surface().closest_point(p);
    const Vec3 along = closest - from;
    if (along.squaredNorm() <= 1e-18 * step * step) return closest;
    return solid_.surface().closest_point(from + step * along.normalized());
  }

 private:
  //! The winding number, asked only where the inside grid cannot tell.
  bool inside(const Vec3& p) const {
    const Region region = solid_.inside_test().region(p);
    return region == Region::surface ? solid_.inside_test().contains(p) : region == Region::inside;
  }

  MeshConstraint solid_;
  CollisionMode mode_;
};

//! Which nodes an attractor pulls, and when it dies (`--venation`; Runions et al. 2005).
enum class Venation {
  open,    //!< its closest node; it dies when any node comes within the kill distance: a tree
  closed,  //!< every node of its relative neighbourhood; it dies when all have come within the
           //!< kill distance, and veins that reach it from different sides join there: loops
};
inline constexpr WordTable<Venation, 2> kVenationWords{
    "venation",
    {{{Venation::open, "open"}, {Venation::closed, "closed"}}}};
constexpr const auto& words_of(Venation) { return kVenationWords; }

//! How the tree grows among its attractors. Distances are in spacings: the step, the node
//! spacing, is the tree's spacing.
struct ColonizationOptions {
  double spacing = 1.0;          //!< step length, scene units
  double kill_distance = 2.0;    //!< an attractor dies once a node is this close or closer,
                                 //!< spacings, in [1, 1e6]: at least a step, so a tip cannot
                                 //!< step over its attractor and back for ever
  //! An attractor pulls its closest node only within this distance, spacings, above the kill
  //! distance; infinity (the default, the Hyphae write-up's version): every attractor pulls,
  //! and with closed venation, whose neighbourhoods need a bound, 4 times the kill distance
  //! (kClosedInfluence; influence_of()).
  double influence = std::numeric_limits<double>::infinity();
  std::size_t max_nodes = 100000;       //!< nodes, roots included, at most; 1 to 2e9
  std::size_t max_iterations = 1000000; //!< growth steps at most, >= 1
  double noise_amplitude = 0.0;  //!< each new node moves by up to this, spacings, in [0, 10]
  double noise_scale = 8.0;      //!< the size of the noise's features, spacings, > 0
  Vec3 tropism = Vec3::Zero();   //!< added to each step's unit direction (gravity, light),
                                 //!< each coordinate in [-10, 10]
  int dimensions = 3;            //!< 2: attractors, roots and steps in z = 0 (leaf venation)
  //! Closed venation bounds an attractor's neighbourhood by the influence (4 times the kill
  //! distance unless given).
  Venation venation = Venation::open;
  std::uint64_t rng_seed = 1;    //!< seeds the noise
  //! A collision object (3D only), not owned: each new node is pushed out of it or stuck to
  //! it, after the noise. A node that would land within a tenth of a step of its parent does
  //! not grow.
  const CollisionObject* collide = nullptr;
  //! A vessel (3D only), not owned: growth stays on its growing side. A step that would cross
  //! its surface is refused (the node does not grow; its attractors may pull it again), or with
  //! ConstraintMode::clip cut short of the surface.
  const MeshConstraint* vessel = nullptr;
};

//! Closed venation's influence when none is given, in kill distances: Runions et al.'s
//! neighbourhoods reach a few kill distances.
inline constexpr double kClosedInfluence = 4.0;

//! The influence growth uses, in spacings: `influence`, or for closed venation without one
//! kClosedInfluence kill distances.
inline double influence_of(const ColonizationOptions& o) {
  return o.venation == Venation::closed && !std::isfinite(o.influence) ? kClosedInfluence * o.kill_distance
                                                                        : o.influence;
}

//! Space colonization's options with a single value, described once (option_description.h); its
//! counts, spacing, influence, noise and tropism are the front ends'.
inline const OptionTable<ColonizationOptions>& colonization_option_table() {
  using O = ColonizationOptions;
  static const OptionTable<O> table{
      real("kill_distance", &O::kill_distance, closed(1, 1e6), "spacings", "Colonization",
           "an attractor dies once a node is this close"),
      word("venation", &O::venation, "Colonization",
           "open: an attractor pulls its nearest node, a tree; closed: every node of its relative neighbourhood, "
           "and veins that reach it join: loops (Runions et al.)"),
      integer("dimensions", &O::dimensions, closed(2, 3), "", "Colonization", "3, or 2 for venation in the plane z = 0"),
  };
  return table;
}

inline void validate(const ColonizationOptions& o) {
  require_in_ranges(colonization_option_table(), o);
  detail::require_in("spacing", o.spacing, kMinSpacing, kMaxSpacing);
  if (!(o.influence > o.kill_distance))
    throw InvalidInput("influence " + detail::format_number(o.influence) + " is not above the kill distance " +
                       detail::format_number(o.kill_distance));
  if (o.max_nodes < 1 || o.max_nodes > 2'000'000'000u)
    throw InvalidInput("max nodes " + std::to_string(o.max_nodes) + " is not in [1, 2e9]");
  if (o.max_iterations < 1) throw InvalidInput("max iterations is 0: growth needs at least one");
  detail::require_in("noise amplitude", o.noise_amplitude, 0.0, 10.0);
  detail::require_in("noise scale", o.noise_scale, 1e-3, 1e6);
  if (!o.tropism.allFinite() || o.tropism.cwiseAbs().maxCoeff() > 10.0)
    throw InvalidInput("tropism has a coordinate that is not in [-10, 10]");
  if (o.collide && o.dimensions != 3) throw InvalidInput("a collision mesh needs 3 dimensions");
  if (o.vessel && o.dimensions != 3) throw InvalidInput("a vessel needs 3 dimensions");
}

//! Grows a tree from `roots` among `attractors` (both in z = 0 for 2D). Validates the options
//! first; throws InvalidInput for no root, or a root or attractor that is not finite.
//! `progress` is called as model_shell.h says; returning false, or `stop` set, ends growth
//! with the tree marked incomplete. Throws PartialGrowth when memory runs out.
Cluster colonize(const ColonizationOptions& o, std::vector<Vec3> attractors, const std::vector<Vec3>& roots,
                 const ProgressFn& progress = {}, const StopFlag* stop = nullptr);

}  // namespace dla
