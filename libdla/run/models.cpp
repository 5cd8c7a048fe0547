// The run options of every model: their checks, and colonization's roots (models.h).

#include "dla/run/models.h"

#include "dla/core/random.h"

#include <algorithm>

namespace dla {

std::string_view to_string(RootRegion region) {
  return region == RootRegion::sphere ? "sphere" : region == RootRegion::mesh ? "mesh" : "surface";
}

RootRegion parse_root_region(std::string_view word) {
  constexpr RootRegion values[] = {RootRegion::sphere, RootRegion::mesh, RootRegion::surface};
  return detail::parse_word(word, values, "root region");
}

std::string_view model_name(const RunOptions& options) {
  constexpr std::string_view names[] = {"grow", "colonize", "eden", "drop", "ballistic"};
  return names[options.index()];
}

const OutputOptions& output_of(const RunOptions& options) {
  return std::visit([](const auto& o) -> const OutputOptions& { return o.files; }, options);
}

namespace {

std::string point_text(const Vec3& p) {
  return detail::format_number(p.x()) + "," + detail::format_number(p.y()) + "," + detail::format_number(p.z());
}

//! K roots at random on the sphere around the attractors: the scattering sphere, or the one
//! around the box they lie in (the Hyphae write-up's third test); in z = 0 for 2D.
std::vector<Vec3> roots_around(const ColonizeRunOptions& c, const std::vector<Vec3>& attractors, Rng& rng) {
  const AttractorOptions& a = c.attractors;
  const bool scattered =
      c.attractors_from.empty() && (a.region == AttractorRegion::sphere || a.region == AttractorRegion::box);
  Vec3 lo = a.box_min, hi = a.box_max;
  if (!scattered) {
    lo = hi = attractors.front();
    for (const Vec3& p : attractors) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const bool sphere = scattered && a.region == AttractorRegion::sphere;
  const Vec3 center = sphere ? a.center : Vec3(0.5 * (lo + hi));
  double radius = sphere ? a.radius : 0.5 * (hi - lo).norm();
  const int dimensions = c.colonization.dimensions;
  if (dimensions == 2 && !sphere) radius = 0.5 * (hi - lo).head<2>().norm();
  radius *= c.roots_scale;
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < c.root_count; ++k) {
    Vec3 root = center + radius * random_direction(rng, dimensions);
    if (dimensions == 2) root.z() = 0.0;
    roots.push_back(root);
  }
  return roots;
}

//! Where one root starts by default: the lowest point (along y) of the scattering sphere or
//! box, or else the lowest attractor.
Vec3 lowest_point(const ColonizeRunOptions& c, const std::vector<Vec3>& attractors) {
  const AttractorOptions& a = c.attractors;
  if (c.attractors_from.empty() && a.region == AttractorRegion::sphere) return a.center - Vec3(0.0, a.radius, 0.0);
  if (c.attractors_from.empty() && a.region == AttractorRegion::box)
    return {0.5 * (a.box_min.x() + a.box_max.x()), a.box_min.y(), 0.5 * (a.box_min.z() + a.box_max.z())};
  return *std::min_element(attractors.begin(), attractors.end(),
                           [](const Vec3& p, const Vec3& q) { return p.y() < q.y(); });
}

}  // namespace

DlaOptions walk_options(const DlaRunOptions& o) {
  DlaOptions g = o.growth;
  if (o.particles) g.particles = *o.particles;
  if (o.spacing) g.spacing = *o.spacing;
  if (o.spawn) g.spawn = *o.spawn;
  if (o.seed_at) g.seeds = *o.seed_at;
  return g;
}

std::vector<Vec3> colonize_roots(const ColonizeRunOptions& options, const std::vector<Vec3>& attractors,
                                 const MeshConstraint* mesh) {
  if (!options.root_at.empty()) return options.root_at;
  if (options.root_count == 0) {
    Vec3 root = lowest_point(options, attractors);
    if (options.colonization.dimensions == 2) root.z() = 0.0;
    return {root};
  }
  Rng rng(options.colonization.rng_seed, 0x726f6f7473ULL);  // a stream of its own: "roots"
  if (options.roots_in == RootRegion::sphere) return roots_around(options, attractors, rng);
  if (!mesh)
    throw InvalidInput("`roots_in` " + std::string(to_string(options.roots_in)) + " needs a mesh: `stl` or `collide`");
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < options.root_count; ++k)
    roots.push_back(options.roots_in == RootRegion::mesh ? mesh->draw_inside(rng) : mesh->draw_near_surface(rng));
  return roots;
}

std::vector<Vec3> seeds_on(const MeshConstraint& mesh, const MeshSeeds& seeds, std::uint64_t rng_seed,
                           const std::vector<TriangleMesh>& entering) {
  if (!seeds.on_surface()) return mesh.place_seeds(seeds.count ? seeds.count : 1, rng_seed);
  const std::vector<Vec3> cover = entering.empty() ? mesh.sample_surface(rng_seed, seeds.paint ? &*seeds.paint : nullptr)
                                                   : mesh.sample_intersection(entering, rng_seed);
  return seeds.count ? farthest_apart(cover, seeds.count) : cover;
}

void refuse_for(std::string_view model, std::string_view option) {
  const std::string name(option);
  if (option == "fill")
    throw InvalidInput("`fill` grows DLA until a mesh is full; " + std::string(model) +
                       (model == "drop" ? " grows to its count, `particles`" : " ends when its attractors are gone, or at `max_nodes`"));
  if (option == "shell" && model == "colonize")
    throw InvalidInput("`shell` keeps DLA's walkers near a surface; colonization grows towards its attractors: put "
                       "them on it with `attractors_in` surface");
  if (option == "shell" && model == "drop")
    throw InvalidInput("`shell` keeps DLA's walkers near a surface; drops fall through space");
  throw InvalidInput("`" + name + "` is not an option of " + std::string(model));
}

namespace {

//! Seeds or roots placed on a mesh need one, and one way of placing them.
void validate_mesh_seeds(const MeshSeeds& seeds, bool mesh, const char* placed_by) {
  if (!mesh) {
    if (seeds.count) throw InvalidInput(std::string("`seeds` places seeds in a mesh given with `stl`; without one, use `") + placed_by + "`");
    if (seeds.surface) throw InvalidInput("`seed_surface` seeds a mesh's surface: give one with `stl`");
    if (seeds.paint) throw InvalidInput("`seed_paint` seeds the painted part of a mesh: give one with `stl`");
    if (!seeds.meshes.empty()) throw InvalidInput("`seed_mesh` seeds where a mesh meets the one given with `stl`: give one");
  }
  if (seeds.surface && !seeds.meshes.empty())
    throw InvalidInput("`seed_surface` seeds the surface; `seed_mesh` where other meshes meet it: give one");
  if (seeds.paint && !seeds.meshes.empty())
    throw InvalidInput("`seed_paint` and `seed_mesh` both say where the seeds go: give one");
}

}  // namespace

void validate(const DlaRunOptions& o) {
  const bool mesh = o.has_mesh();
  validate(o.files, o.growth.dimensions, mesh);
  if (o.growth.spawn_box && o.spawn.value_or(o.growth.spawn) != SpawnMode::box)
    throw InvalidInput("`box` is for `spawn` box, not `spawn` " + std::string(to_string(o.spawn.value_or(o.growth.spawn))));
  validate_mesh_seeds(o.seeds, mesh, "seed_at");
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

void validate(const ColonizeRunOptions& c) {
  const ColonizationOptions& o = c.colonization;
  validate(c.files, o.dimensions, !c.stl.empty());
  if (c.roots_in != RootRegion::sphere && c.root_count == 0)
    throw InvalidInput("`roots_in` says where `roots` K puts its roots: give `roots`");
  detail::require_in("`roots_scale`", c.roots_scale, 0.01, 100.0);
  if (c.roots_scale != 1.0 && (c.root_count == 0 || c.roots_in != RootRegion::sphere))
    throw InvalidInput("`roots_scale` sizes the sphere of `roots` K (`roots_in` sphere): give `roots`");
  if (!c.root_at.empty() && c.root_count)
    throw InvalidInput("`root_at` and `roots` both place the roots: give one");
  validate_mesh_seeds(c.seeds, !c.stl.empty() || !c.collide.empty(), "root_at");
  if ((c.seeds.count || c.seeds.on_surface()) && (!c.root_at.empty() || c.root_count))
    throw InvalidInput("`seeds`, `seed_surface`, `seed_paint` and `seed_mesh` place the roots on the mesh; `root_at` "
                       "and `roots` elsewhere: give one");
  const bool on_mesh = c.attractors.region == AttractorRegion::mesh || c.attractors.region == AttractorRegion::surface;
  if ((on_mesh || c.roots_in != RootRegion::sphere) && c.stl.empty() && c.collide.empty())
    throw InvalidInput("attractors or roots in a mesh need one: give `stl` or `collide`");
  if (!c.attractors_from.empty() && on_mesh)
    throw InvalidInput("`attractors_from` reads the attractors; `attractors_in` scatters them: give one");
  if (!c.stl.empty() && o.dimensions != 3) throw InvalidInput("`stl` needs 3 dimensions");
  if (c.collision != CollisionMode::push && c.collide.empty())
    throw InvalidInput("`collision` says what `collide`'s mesh does: give one");
  if (!c.collide.empty() && o.dimensions != 3) throw InvalidInput("`collide` needs 3 dimensions");
  validate(o);
  validate(c.attractors);
  if (o.dimensions == 2) {
    if (c.attractors.center.z() != 0.0)
      throw InvalidInput("`dimensions` 2 grows in z = 0: the attractors' centre is not");
    for (const Vec3& r : c.root_at)
      if (r.z() != 0.0) throw InvalidInput("`dimensions` 2 grows in z = 0: a `root_at` is not");
  }
  if (c.root_count > o.max_nodes || c.root_at.size() > o.max_nodes)
    throw InvalidInput("more roots than `max_nodes`");
  for (const Vec3& r : c.root_at) detail::require_representable("`root_at` " + point_text(r), r, o.spacing);
}

void validate(const EdenRunOptions& e) {
  validate(e.files, dimensions_of(e.eden.lattice), false);
  if (e.mask_file.empty()) validate(e.eden);
}

void validate(const DropRunOptions& d) {
  const bool mesh = !d.stl.empty();
  validate_mesh_seeds(d.seeds, mesh, "seed_at");
  if (d.seed_at && (d.seeds.count || d.seeds.on_surface()))
    throw InvalidInput("`seed_at` and `seeds`, `seed_surface`, `seed_paint` or `seed_mesh` both place the seeds: give one");
  if (d.drop.zone == DropZone::mesh && !mesh) throw InvalidInput("`zone` mesh drops inside a mesh: give one with `stl`");
  if (!mesh || d.spacing) {  // else once the mesh gives the spacing
    DropOptions drop = d.drop;
    if (d.spacing) drop.spacing = *d.spacing;
    if (d.seed_at) drop.seeds = *d.seed_at;
    validate(drop);
  }
  validate(d.files, d.drop.dimensions, mesh);
}

void validate(const BallisticRunOptions& b) {
  validate(b.ballistic);
  validate(b.files, b.ballistic.dimensions, false);
}

void validate(const RunOptions& options) {
  std::visit([](const auto& o) { validate(o); }, options);
}

}  // namespace dla
