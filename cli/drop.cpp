// `dla3d drop`: random-drop ballistic aggregation's options (drop_run_option_table()), with
// --fill and --shell refused with why.

#include "options.h"

namespace dla::cli {

Subcommand add_drop_command(CLI::App& app, const Model& model) {
  struct Words {
    std::vector<OptionDescription> described;
    std::unique_ptr<DescribedOptions<DropRunOptions>> options;
    std::unique_ptr<OutputWords> files;
  };
  auto w = std::make_shared<Words>();
  auto d = std::make_shared<DropRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  w->options = std::make_unique<DescribedOptions<DropRunOptions>>(*command, drop_run_option_table(), *d, &w->described);
  add_refused_mesh_controls(*command, "Mesh constraint", "drop");
  w->files = std::make_unique<OutputWords>(*command, d->files, *quiet);
  return {command,
          [w, d, quiet](CommandLine& line, const std::vector<std::string>&) {
            w->options->finish(*d);
            w->files->finish(d->files);
            validate(*d);
            line.quiet = *quiet;
            line.run = *d;
          },
          w->described};
}

}  // namespace dla::cli
