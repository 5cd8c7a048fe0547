// The non-template entry points: validate the options and run the engine with the chosen
// index, so programs that call grow() compile the engine once, here.

#include "dla/growth.h"

#include "dla/grid_index.h"
#include "dla/kdtree_index.h"
#include "dla/spatial_index.h"

namespace dla {

namespace {

Cluster grow_any(const GrowthOptions& options, const ProgressFn& progress, const MeshConstraint* constraint) {
  switch (options.index) {
    case IndexKind::grid: return grow_with<GridIndex>(options, progress, constraint);
    case IndexKind::kdtree: return grow_with<KdTreeIndex>(options, progress, constraint);
    case IndexKind::brute: return grow_with<BruteForceIndex>(options, progress, constraint);
  }
  throw InvalidInput("unknown index");
}

std::string point(const Vec3& p) {
  return "(" + detail::format_number(p.x()) + ", " + detail::format_number(p.y()) + ", " +
         detail::format_number(p.z()) + ")";
}

}  // namespace

Cluster grow(const GrowthOptions& options, const ProgressFn& progress) {
  validate(options);
  if (options.spawn == SpawnMode::inside || options.spawn == SpawnMode::radial)
    throw InvalidInput("spawn " + std::string(to_string(options.spawn)) + " needs a constraint mesh");
  return grow_any(options, progress, nullptr);
}

void validate(const GrowthOptions& options, const MeshConstraint& constraint) {
  validate(options);
  const Side side = constraint.options().side;
  if (options.dimensions != 3) throw InvalidInput("a constraint mesh needs growth in 3 dimensions");
  if (options.spacing != constraint.spacing())
    throw InvalidInput("the constraint was built for spacing " + detail::format_number(constraint.spacing()) +
                       ", not " + detail::format_number(options.spacing));
  if ((options.spawn == SpawnMode::inside || options.spawn == SpawnMode::radial) && side != Side::inside)
    throw InvalidInput("spawn " + std::string(to_string(options.spawn)) + " needs --side inside, not --side " +
                       std::string(to_string(side)));
  for (std::size_t i = 0; i < options.seeds.size(); ++i)
    if (!constraint.on_growth_side(options.seeds[i]))
      throw InvalidInput("seed " + std::to_string(i + 1) + " at " + point(options.seeds[i]) + " is " +
                         (side == Side::inside ? "outside" : "inside") + " the mesh, but growth is " +
                         std::string(to_string(side)) + " it");
}

Cluster grow(const GrowthOptions& options, const MeshConstraint& constraint, const ProgressFn& progress) {
  validate(options, constraint);
  return grow_any(options, progress, &constraint);
}

}  // namespace dla
