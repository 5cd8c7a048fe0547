// `dla3d colonize`: space colonization's options (colonize_option_table()), with --fill and
// --shell refused with why.

#include "options.h"

namespace dla::cli {

Subcommand add_colonize_command(CLI::App& app, const Model& model) {
  struct Words {
    std::vector<OptionDescription> described;
    std::unique_ptr<DescribedOptions<ColonizeRunOptions>> options;
    std::unique_ptr<OutputWords> files;
  };
  auto w = std::make_shared<Words>();
  auto c = std::make_shared<ColonizeRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  w->options = std::make_unique<DescribedOptions<ColonizeRunOptions>>(*command, colonize_option_table(), *c, &w->described);
  add_refused_mesh_controls(*command, "Vessel and collision", "colonize");
  w->files = std::make_unique<OutputWords>(*command, c->files, *quiet);
  return {command,
          [w, c, quiet](CommandLine& line, const std::vector<std::string>&) {
            w->options->finish(*c);
            w->files->finish(c->files);
            validate(*c);
            line.quiet = *quiet;
            line.run = *c;
          },
          w->described};
}

}  // namespace dla::cli
