// `dla3d breakdown`: the dielectric breakdown model's options (breakdown_run_option_table():
// DLA's walk, mesh, spawn and seeds, the Discharge group and the target), with --fill refused
// with why.

#include "options.h"

namespace dla::cli {

Subcommand add_breakdown_command(CLI::App& app, const Model& model) {
  struct Words {
    std::vector<OptionDescription> described;
    std::unique_ptr<DescribedOptions<BreakdownRunOptions>> options;
    std::unique_ptr<OutputWords> files;
  };
  auto w = std::make_shared<Words>();
  auto b = std::make_shared<BreakdownRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  w->options =
      std::make_unique<DescribedOptions<BreakdownRunOptions>>(*command, breakdown_run_option_table(), *b, &w->described);
  w->files = std::make_unique<OutputWords>(*command, b->files, *quiet);
  command->add_option_function<std::string>(
             "--fill", [](const std::string&) { refuse_for("breakdown", "fill"); },
             "DLA's: grow until a mesh is full (not for breakdown)")
      ->type_name("F")->group("Mesh constraint");
  return {command,
          [w, b, quiet](CommandLine& line, const std::vector<std::string>&) {
            w->options->finish(*b);
            w->files->finish(b->files);
            validate(*b);
            line.quiet = *quiet;
            line.run = *b;
          },
          w->described};
}

}  // namespace dla::cli
