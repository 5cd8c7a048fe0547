// `dla3d ballistic`: ballistic aggregation's options, turned into the library's
// BallisticRunOptions.

#include "options.h"

namespace dla::cli {

Subcommand add_ballistic_command(CLI::App& app, const Model& model) {
  struct Words {
    SeededWords seeded;
    std::string direction;
    std::unique_ptr<OutputWords> files;
  };
  auto w = std::make_shared<Words>();
  auto b = std::make_shared<BallisticRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  const char* flying = "Ballistic";
  BallisticOptions& o = b->ballistic;
  add_seeded_options(*command, flying, w->seeded, o.dimensions, o.spacing, o.rng_seed, "");
  command->add_option("--direction", w->direction, "deposition: every particle flies along x,y,z; "
                                                   "default: each from a random direction")
      ->type_name("X,Y,Z")->group(flying);
  w->files = std::make_unique<OutputWords>(*command, b->files, *quiet);
  return {command, [w, b, quiet](CommandLine& line, const std::vector<std::string>&) {
            BallisticOptions& o = b->ballistic;
            o.particles = parse_count("--particles", w->seeded.particles);
            if (!w->seeded.seed_at.empty()) o.seeds = parse_points("--seed-at", w->seeded.seed_at);
            if (!w->direction.empty()) {
              o.direction = parse_vec3("--direction", w->direction);
              if (o.direction.squaredNorm() == 0.0) throw InvalidInput("--direction 0,0,0 has no direction");
            }
            b->links = links_of(*w->seeded.links);
            w->files->finish(b->files);
            validate(*b);
            line.quiet = *quiet;
            line.run = *b;
          }};
}

}  // namespace dla::cli
