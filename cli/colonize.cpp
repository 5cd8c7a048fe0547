// `dla3d colonize`: space colonization's options, turned into the library's ColonizeRunOptions.

#include "options.h"

namespace dla::cli {

namespace {

struct ColonizeWords {
  std::vector<std::string> root_at;
  std::string attractor_center, attractor_box, attractor_paint, noise, tropism;
  long long max_nodes, attractor_count, max_iterations, root_count = 0;
  CLI::Option *attractors, *roots;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<ColonizeRunOptions>> options;  // colonize_option_table()
  std::unique_ptr<DescribedOptions<MeshSeeds>> seeds;  // mesh_seeds_option_table()
  std::unique_ptr<OutputWords> files;
};

void finish(ColonizeRunOptions& c, const ColonizeWords& w) {
  w.options->finish(c);
  w.files->finish(c.files);
  validate(c.files, c.colonization.dimensions, !c.stl.empty());
  if (w.max_nodes < 1) throw InvalidInput("--max-nodes " + std::to_string(w.max_nodes) + " is not at least 1");
  if (w.max_iterations < 1) throw InvalidInput("--max-iterations " + std::to_string(w.max_iterations) + " is not at least 1");
  if (w.attractor_count < 1) throw InvalidInput("--attractors " + std::to_string(w.attractor_count) + " is not at least 1");
  if (w.roots->count() && w.root_count < 1) throw InvalidInput("--roots " + std::to_string(w.root_count) + ": there must be a root");
  c.colonization.max_nodes = static_cast<std::size_t>(w.max_nodes);
  c.colonization.max_iterations = static_cast<std::size_t>(w.max_iterations);
  c.attractors.count = static_cast<std::size_t>(w.attractor_count);
  c.root_count = static_cast<std::size_t>(w.root_count);
  c.sample_attractors = w.attractors->count() > 0 && !c.attractors_from.empty();
  if (!w.attractor_center.empty()) c.attractors.center = parse_vec3("--attractor-center", w.attractor_center);
  if (!w.attractor_box.empty()) {
    const Box box = parse_box("--attractor-box", w.attractor_box);
    c.attractors.box_min = box.min;
    c.attractors.box_max = box.max;
  }
  if (!w.attractor_paint.empty()) c.attractors.paint = parse_paint(w.attractor_paint, "attractor_paint");
  if (!w.noise.empty()) {
    const std::vector<double> n = parse_numbers("--noise", w.noise, 2);
    c.colonization.noise_amplitude = n[0];
    c.colonization.noise_scale = n[1];
  }
  if (!w.tropism.empty()) c.colonization.tropism = parse_vec3("--tropism", w.tropism);
  c.root_at = parse_points("--root-at", w.root_at);
  w.seeds->finish(c.seeds);
  validate(c);
}

}  // namespace

Subcommand add_colonize_command(CLI::App& app, const Model& model) {
  auto w = std::make_shared<ColonizeWords>();
  auto c = std::make_shared<ColonizeRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  const char* colonizing = "Colonization";
  w->max_nodes = static_cast<long long>(c->colonization.max_nodes);
  w->attractor_count = static_cast<long long>(c->attractors.count);
  w->max_iterations = static_cast<long long>(c->colonization.max_iterations);
  command->add_option("-n,--max-nodes", w->max_nodes, "nodes at most, roots included")
      ->capture_default_str()->group(colonizing);
  command->add_option("--max-iterations", w->max_iterations, "growth steps at most")
      ->capture_default_str()->group(colonizing);
  command->add_option("--spacing", c->colonization.spacing, "the step: distance between a node and its parent, "
                                                             "[1e-25, 1e25]")->capture_default_str()->group(colonizing);
  command->add_option("--influence", c->colonization.influence, "an attractor pulls its nearest node only this close, "
                                                                 "in spacings, above the kill distance; default: any, and for --venation closed 4 "
                                                                 "times --kill-distance")
      ->group(colonizing);
  command->add_option("--noise", w->noise, "each new node moves by up to A spacings, in features S spacings wide; "
                                           "A in [0, 10], S > 0")->type_name("A,S")->group(colonizing);
  command->add_option("--tropism", w->tropism, "added to each step's unit direction (gravity, light), "
                                               "each in [-10, 10]")->type_name("X,Y,Z")->group(colonizing);
  command->add_option("--rng-seed", c->colonization.rng_seed, "seeds the attractors, the roots and the noise")
      ->capture_default_str()->group(colonizing);
  const char* attracting = "Attractors and roots";
  w->attractors = command->add_option("--attractors", w->attractor_count, "how many attractors, [1, 1e8]")
                      ->capture_default_str()->group(attracting);
  w->options = std::make_unique<DescribedOptions<ColonizeRunOptions>>(*command, colonize_option_table(), *c, &w->described);
  CLI::Option* attractors_in = command->get_option("--attractors-in");
  command->add_option("--attractors-from", c->attractors_from, "read them from a file: CSV rows x,y,z (or a "
                                                               "header naming x, y, z) or PLY points; with "
                                                               "--attractors N, a seeded sample of N")
      ->type_name("FILE")->group(attracting)->excludes(attractors_in);
  command->add_option("--attractor-center", w->attractor_center, "the sphere's centre; default the origin")
      ->type_name("X,Y,Z")->group(attracting);
  command->add_option("--attractor-box", w->attractor_box, "the box; default -50,-50,-50,50,50,50")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(attracting);
  command->add_option("--attractor-paint", w->attractor_paint, "with --attractors-in surface: only on the part "
                                                               "of the --stl or --collide mesh painted this colour "
                                                               "(a name or ff8000), within TOLERANCE per channel, "
                                                               "[0, 1), default 0.3")
      ->type_name("COLOR[,TOLERANCE]")->group(attracting)->excludes("--attractors-from");
  CLI::Option* root_at_option =
      command->add_option("--root-at", w->root_at, "a root at x,y,z (repeat for several); default: one at "
                                                   "the attractors' lowest point (-y)")
          ->type_name("X,Y,Z")->allow_extra_args(false)->group(attracting);
  w->roots = command->add_option("--roots", w->root_count, "K roots at random, where --roots-in says")
                 ->type_name("K")->group(attracting)->excludes(root_at_option);
  const char* colliding = "Vessel and collision";
  command->add_option("--stl", c->stl, "a vessel (STL, OFF, OBJ or PLY) that growth stays inside: a "
                                       "step that would cross its surface is refused")
      ->type_name(kMeshFile)->group(colliding);
  command->add_option("--collide", c->collide, "a collision mesh (STL, OFF, OBJ or PLY) that new nodes "
                                               "are pushed out of or stuck to")
      ->type_name(kMeshFile)->group(colliding);
  w->seeds = std::make_unique<DescribedOptions<MeshSeeds>>(*command, mesh_seeds_option_table(true), c->seeds, &w->described);
  add_refused_mesh_controls(*command, colliding, "colonize");
  w->files = std::make_unique<OutputWords>(*command, c->files, *quiet);
  return {command,
          [w, c, quiet](CommandLine& line, const std::vector<std::string>&) {
            finish(*c, *w);
            line.quiet = *quiet;
            line.run = *c;
          },
          w->described};
}

}  // namespace dla::cli
