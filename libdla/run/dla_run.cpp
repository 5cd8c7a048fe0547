// DLA's run (run.h): its options checked, the mesh or text read and the defaults they give
// taken, the seeds placed; grown, summed up and recorded.

#include "dla_run.h"

namespace dla {

DlaOptions walk_options(const DlaRunOptions& o) {
  DlaOptions g = o.growth;
  if (o.particles) g.particles = *o.particles;
  if (o.spacing) g.spacing = *o.spacing;
  if (o.spawn) g.spawn = *o.spawn;
  if (o.seed_at) g.seeds = *o.seed_at;
  return g;
}

void validate(const DlaRunOptions& o) {
  const bool mesh = o.has_mesh();
  validate(o.files, o.growth.dimensions, mesh);
  detail::validate_links(o.links);
  if (o.growth.fill == 0.0 && o.growth.fill_distance != DlaOptions{}.fill_distance)
    throw InvalidInput("`fill_distance` is for `fill`");
  if (o.growth.spawn_box && o.spawn.value_or(o.growth.spawn) != SpawnMode::box)
    throw InvalidInput("`box` is for `spawn` box, not `spawn` " + std::string(to_string(o.spawn.value_or(o.growth.spawn))));
  detail::validate_mesh_seeds(o.seeds, mesh, "seed_at");
  if (!mesh) {
    if (o.constraint.shell != 0.0) throw InvalidInput("`shell` keeps growth near a mesh's surface: give one with `stl`");
    const DlaOptions growth = walk_options(o);
    validate(growth);
    if (spawns_from_mesh(growth.spawn))
      throw InvalidInput("spawn " + std::string(to_string(growth.spawn)) + " needs a mesh (`stl`)");
    if (growth.fill != 0.0) throw InvalidInput("`fill` fills a mesh's volume: give one with `stl`");
    return;
  }
  if (o.constraint.shell != 0.0) detail::require_in("`shell`", o.constraint.shell, 1.0, 1000.0);
  if (o.seed_at && o.seeds.count) throw InvalidInput("`seeds` and `seed_at` both place the seeds: give one");
  if (o.seed_at && o.seeds.on_surface())
    throw InvalidInput("`seed_at` and `seed_surface`, `seed_paint` or `seed_mesh` both place the seeds: give one");
  if (o.spacing) detail::require_in("spacing", *o.spacing, kMinSpacing, kMaxSpacing);
}

namespace detail {

std::unique_ptr<Run> prepare_dla(const DlaRunOptions& options, const MeshReader& read, const Resumed& resumed) {
  return std::make_unique<DlaRun>(options, read, resumed);
}

}  // namespace detail

}  // namespace dla
