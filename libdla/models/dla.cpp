// The non-template entry points: validate the options and run the engine with the chosen
// index, so programs that call grow() compile the engine once, here.

#include "aggregation.h"

#include "dla/index/grid_index.h"
#include "dla/index/kdtree_index.h"
#include "dla/index/spatial_index.h"

namespace dla {

namespace {

Cluster grow_any(const DlaOptions& options, const ProgressFn& progress, const MeshConstraint* constraint,
                 const Cluster* partial, const StopFlag* stop, DlaStats* stats) {
  switch (options.index) {
    case IndexKind::grid: return grow_with<GridIndex>(options, progress, constraint, partial, stop, stats);
    case IndexKind::kdtree: return grow_with<KdTreeIndex>(options, progress, constraint, partial, stop, stats);
    case IndexKind::brute: return grow_with<BruteForceIndex>(options, progress, constraint, partial, stop, stats);
  }
  throw InvalidInput("unknown index");
}

//! Whether `partial` can be a structure these options grew and stopped: its seeds, scale and
//! tree are those the options give.
void validate_partial(const DlaOptions& options, const Cluster& partial) {
  if (partial.seed_count != options.seeds.size() || partial.particles.size() < partial.seed_count)
    throw InvalidInput("the saved structure has " + std::to_string(partial.seed_count) + " seeds, the options " +
                       std::to_string(options.seeds.size()));
  if (partial.spacing != options.spacing || partial.dimensions != options.dimensions)
    throw InvalidInput("the saved structure was grown with another spacing or dimension");
  if (attached(partial) > options.particles)
    throw InvalidInput("the saved structure has " + std::to_string(attached(partial)) + " particles, more than " +
                       std::to_string(options.particles));
  for (std::size_t i = 0; i < partial.particles.size(); ++i) {
    const Particle& p = partial.particles[i];
    const bool seed = i < partial.seed_count;
    const bool tree_ok = seed ? p.parent == -1 && p.seed == static_cast<std::int32_t>(i) && p.position == options.seeds[i]
                              : p.parent >= 0 && static_cast<std::size_t>(p.parent) < i &&
                                    p.seed == partial.particles[static_cast<std::size_t>(p.parent)].seed;
    if (!tree_ok || !p.position.allFinite())
      throw InvalidInput("the saved structure is not one these options grow (particle " + std::to_string(i) + ")");
  }
}

std::string point(const Vec3& p) {
  return "(" + detail::format_number(p.x()) + ", " + detail::format_number(p.y()) + ", " +
         detail::format_number(p.z()) + ")";
}

//! What needs a mesh and has none.
void require_no_mesh_options(const DlaOptions& options) {
  if (spawns_from_mesh(options.spawn))
    throw InvalidInput("spawn " + std::string(to_string(options.spawn)) + " needs a constraint mesh");
  if (options.fill != 0.0) throw InvalidInput("`fill` fills a mesh's volume: give one with `stl`");
}

//! The counts start afresh, but a resumed run's walks, which go on from those that grew what it
//! resumes; the particles go on to the same feed.
void start_counting(DlaStats* stats, bool resumed = false) {
  if (stats) *stats = {resumed ? stats->walk : WalkStats{}, 0, 0.0, stats->feed};
}

}  // namespace

Cluster grow(const DlaOptions& options, const ProgressFn& progress, const StopFlag* stop, DlaStats* stats) {
  validate(options);
  require_no_mesh_options(options);
  start_counting(stats);
  return grow_any(options, progress, nullptr, nullptr, stop, stats);
}

Cluster resume(const DlaOptions& options, const Cluster& partial, const ProgressFn& progress, const StopFlag* stop,
               DlaStats* stats) {
  validate(options);
  require_no_mesh_options(options);
  validate_partial(options, partial);
  start_counting(stats, true);
  return grow_any(options, progress, nullptr, &partial, stop, stats);
}

Cluster resume(const DlaOptions& options, const MeshConstraint& constraint, const Cluster& partial,
               const ProgressFn& progress, const StopFlag* stop, DlaStats* stats) {
  validate(options, constraint);
  validate_partial(options, partial);
  start_counting(stats, true);
  return grow_any(options, progress, &constraint, &partial, stop, stats);
}

void validate(const DlaOptions& options, const MeshConstraint& constraint) {
  validate(options);
  const Side side = constraint.options().side;
  if (options.dimensions != 3) throw InvalidInput("a constraint mesh needs growth in 3 dimensions");
  if (options.fill != 0.0 && side != Side::inside)
    throw InvalidInput("`fill` fills the volume a mesh encloses: it needs `side` inside, not `side` " +
                       std::string(to_string(side)));
  if (options.rotate_degrees != 0.0)
    throw InvalidInput("`rotate` turns the spawn and the drift about the seeds' centre, and a mesh does not turn "
                       "with them: leave out `rotate` or the mesh");
  if (options.spacing != constraint.spacing())
    throw InvalidInput("the constraint was built for spacing " + detail::format_number(constraint.spacing()) +
                       ", not " + detail::format_number(options.spacing));
  const bool shell = constraint.shell() > 0.0;
  if (options.fill != 0.0 && shell) throw InvalidInput("`fill` fills the volume a mesh encloses, not a shell over it");
  // In a shell, `inside` is uniform in the shell.
  if ((options.spawn == SpawnMode::radial || (options.spawn == SpawnMode::inside && !shell)) && side != Side::inside)
    throw InvalidInput("spawn " + std::string(to_string(options.spawn)) + " needs `side` inside, not `side` " +
                       std::string(to_string(side)));
  if (options.spawn == SpawnMode::surface && side == Side::both && !shell)
    throw InvalidInput("spawn surface needs a growing side, `side` inside or outside, not `side` both");
  for (std::size_t i = 0; i < options.seeds.size(); ++i)
    if (!constraint.on_growth_side(options.seeds[i]))
      throw InvalidInput("seed " + std::to_string(i + 1) + " at " + point(options.seeds[i]) + " is " +
                         (shell ? "not in the shell (within " + detail::format_number(constraint.shell()) +
                                      " of the surface" +
                                      (side == Side::inside    ? ", inside it)"
                                       : side == Side::outside ? ", outside it)"
                                                               : ")")
                                : std::string(side == Side::inside ? "outside" : "inside") + " the mesh, but growth is " +
                                      std::string(to_string(side)) + " it"));
}

Cluster grow(const DlaOptions& options, const MeshConstraint& constraint, const ProgressFn& progress,
             const StopFlag* stop, DlaStats* stats) {
  validate(options, constraint);
  start_counting(stats);
  return grow_any(options, progress, &constraint, nullptr, stop, stats);
}

// The engine for every index: the template dla.h declares, compiled here once.
template Cluster grow_with<GridIndex>(const DlaOptions&, const ProgressFn&, const MeshConstraint*, const Cluster*,
                                      const StopFlag*, DlaStats*);
template Cluster grow_with<KdTreeIndex>(const DlaOptions&, const ProgressFn&, const MeshConstraint*, const Cluster*,
                                        const StopFlag*, DlaStats*);
template Cluster grow_with<BruteForceIndex>(const DlaOptions&, const ProgressFn&, const MeshConstraint*,
                                            const Cluster*, const StopFlag*, DlaStats*);

}  // namespace dla
