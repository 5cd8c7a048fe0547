// `dla3d drop`: random-drop ballistic aggregation's options, turned into the library's
// DropRunOptions.

#include "options.h"

namespace dla::cli {

namespace {

struct DropWords {
  SeededWords seeded;
  std::string zone_box, bias = "uniform", side, constraint;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<DropOptions>> options;  // drop_option_table()
  std::unique_ptr<DescribedOptions<MeshSeeds>> seeds;  // mesh_seeds_option_table()
  std::unique_ptr<OutputWords> files;
};

void finish(DropRunOptions& d, const DropWords& w) {
  d.drop.particles = parse_count("--particles", w.seeded.particles);
  if (w.seeded.spacing->count()) d.spacing = d.drop.spacing;
  if (w.seeded.seed_at_option->count()) d.seed_at = parse_points("--seed-at", w.seeded.seed_at);
  w.options->finish(d.drop);
  d.drop.bias = parse_drop_bias(w.bias);
  if (!w.zone_box.empty()) d.drop.zone_box = parse_box("--zone-box", w.zone_box);
  d.constraint.side = parse_word<Side>(w.side);
  d.constraint.mode = parse_word<ConstraintMode>(w.constraint);
  w.seeds->finish(d.seeds);
  d.links = links_of(*w.seeded.links);
  w.files->finish(d.files);
  validate(d);
}

}  // namespace

Subcommand add_drop_command(CLI::App& app, const Model& model) {
  auto w = std::make_shared<DropWords>();
  auto d = std::make_shared<DropRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  const char* dropping = "Random drops";
  w->side = std::string(to_string(d->constraint.side));
  w->constraint = std::string(to_string(d->constraint.mode));
  add_seeded_options(*command, dropping, w->seeded, d->drop.dimensions, d->drop.spacing, d->drop.rng_seed,
                     "; with a mesh, default: its longest side / 100");
  w->options = std::make_unique<DescribedOptions<DropOptions>>(*command, drop_option_table(), d->drop, &w->described);
  command->add_option("--zone-radius", d->drop.zone_radius, "ball: a fixed radius about the seeds' centre, "
                                                            "scene units; default: growing, see --zone-margin")
      ->group(dropping);
  command->add_option("--zone-box", w->zone_box, "box: a fixed box; default: the square or cube around the ball")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(dropping);
  command->add_option("--drop", w->bias, "uniform; circle (on the zone's edge); same:N (N drops at one "
                                         "point); offset:N,R (N more, each within R of the last)")
      ->capture_default_str()->group(dropping);
  const char* meshes = "Mesh constraint";
  command->add_option("--stl,--mesh", d->stl, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
      ->type_name(kMeshFile)->group(meshes);
  command->add_option("--side", w->side, "inside, outside or both (the mesh is only a wall)")
      ->capture_default_str()->group(meshes);
  command->add_option("--constraint", w->constraint, "a branch crossing the mesh: reject (drop again) or clip (end at it)")
      ->capture_default_str()->group(meshes);
  w->seeds = std::make_unique<DescribedOptions<MeshSeeds>>(*command, mesh_seeds_option_table(), d->seeds, &w->described);
  command->add_flag("--scene-mesh,!--no-scene-mesh", d->scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
      ->capture_default_str()->group(meshes);
  add_refused_mesh_controls(*command, meshes, "drop");
  w->files = std::make_unique<OutputWords>(*command, d->files, *quiet);
  return {command,
          [w, d, quiet](CommandLine& line, const std::vector<std::string>&) {
            finish(*d, *w);
            line.quiet = *quiet;
            line.run = *d;
          },
          w->described};
}

}  // namespace dla::cli
