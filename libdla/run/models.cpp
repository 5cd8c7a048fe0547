// What the run options of several models share: seeds on a mesh, refusals, the checks of
// any model's options (models.h); each model's own checks are in its file (dla_run.cpp, ...).

#include "model_runs.h"

namespace dla {

const OutputOptions& output_of(const RunOptions& options) {
  // Only read through: the model's accessor serves the front ends that set the files too.
  return options.model().files(const_cast<RunOptions&>(options));
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
                       (model == "drop"        ? " grows to its count, `particles`"
                        : model == "breakdown" ? " grows to its count, `particles`, or to its strike"
                                               : " ends when its attractors are gone, or at `max_nodes`"));
  if (option == "shell" && model == "colonize")
    throw InvalidInput("`shell` keeps DLA's walkers near a surface; colonization grows towards its attractors: put "
                       "them on it with `attractors_in` surface");
  if (option == "shell" && model == "drop")
    throw InvalidInput("`shell` keeps DLA's walkers near a surface; drops fall through space");
  throw InvalidInput("`" + name + "` is not an option of " + std::string(model));
}

const OptionTable<MeshSeeds>& mesh_seeds_option_table(bool roots) {
  using O = MeshSeeds;
  const auto table = [](std::string_view group, std::string_view seeds, std::string_view surface) {
    return OptionTable<O>{
        excluding(parsed<O>(
            "seeds", OptionKind::text, "K|all", group, seeds,
            [](O& o, const std::string& words) {
              o.all = words == "all";
              o.count = 0;
              if (o.all || words.empty()) return;
              const bool digits = !words.empty() && words.size() <= 9 && words.find_first_not_of("0123456789") == std::string::npos;
              if (!digits) throw InvalidInput("`seeds` '" + words + "' is neither a count of seeds nor all");
              o.count = std::stoul(words);
              if (o.count == 0) throw InvalidInput("`seeds` 0: there must be a seed");
            },
            [](const O& o) { return o.all ? std::string("all") : o.count ? std::to_string(o.count) : std::string(); }),
            {"seed_at", "root_at"}),
        excluding(flag("seed_surface", &O::surface, group, surface), {"seeds", "seed_at", "root_at"}),
        excluding(with_paint_role(colour("seed_paint", &O::paint, group,
                                         "seeds on the part of the surface painted this colour (a name or ff8000), "
                                         "within TOLERANCE per channel, [0, 1), default 0.3"),
                                  PaintRole::seeds),
                  {"seed_at", "root_at"}),
        excluding(repeated<O>(
                      "seed_mesh", OptionKind::file, kMeshFileForm, group,
                      "seeds where this mesh's surface meets the mesh (repeat for several): growth from where "
                      "objects enter",
                      [](O& o, const std::vector<std::string>& paths) { o.meshes = paths; },
                      [](const O& o) { return o.meshes; }),
                  {"seed_at", "root_at", "seed_paint", "seed_surface"}),
    };
  };
  static const OptionTable<O> seeds = table(
      "Mesh constraint",
      "place K seeds on the growing side, far apart (default 1), or all: the surface, the paint or the --seed-mesh "
      "curves at the spacing (their default)",
      "start from the whole surface (or the painted part): seeds a spacing apart, half a spacing off it on the "
      "growing side");
  static const OptionTable<O> root_seeds = table(
      "Vessel and collision",
      "roots on the mesh (the vessel, else the collision mesh): K far apart, or all: the surface, the paint or the "
      "--seed-mesh curves at the spacing",
      "roots over the whole surface (or the painted part), a spacing apart");
  return roots ? root_seeds : seeds;
}

namespace detail {

void validate_mesh_seeds(const MeshSeeds& seeds, bool mesh, const char* placed_by) {
  if (!mesh) {
    if (seeds.count || seeds.all)
      throw InvalidInput(std::string("`seeds` places seeds in a mesh given with `stl`; without one, use `") + placed_by + "`");
    if (seeds.surface) throw InvalidInput("`seed_surface` seeds a mesh's surface: give one with `stl`");
    if (seeds.paint) throw InvalidInput("`seed_paint` seeds the painted part of a mesh: give one with `stl`");
    if (!seeds.meshes.empty()) throw InvalidInput("`seed_mesh` seeds where a mesh meets the one given with `stl`: give one");
  }
  if (seeds.surface && (seeds.count || seeds.all))
    throw InvalidInput("`seeds` and `seed_surface` both say how the surface is seeded: give one");
  if (seeds.surface && !seeds.meshes.empty())
    throw InvalidInput("`seed_surface` seeds the surface; `seed_mesh` where other meshes meet it: give one");
  if (seeds.paint && !seeds.meshes.empty())
    throw InvalidInput("`seed_paint` and `seed_mesh` both say where the seeds go: give one");
}

}  // namespace detail

void validate(const RunOptions& options) {
  options.model().validate(options);
}

}  // namespace dla
