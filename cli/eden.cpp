// `dla3d eden`: the Eden model's options, turned into the library's EdenRunOptions.

#include "options.h"

namespace dla::cli {

namespace {

struct EdenWords {
  long long sites = 0;
  int dimensions = 2;
  std::string lattice, mask;
  std::unique_ptr<DescribedOptions<LinkOptions>> links;  // links_option_table(true)
  CLI::Option* dimensions_option;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<EdenOptions>> options;  // eden_option_table()
  std::unique_ptr<OutputWords> files;
};

void finish(EdenRunOptions& e, const EdenWords& w) {
  if (w.sites < 1) throw InvalidInput("--sites " + std::to_string(w.sites) + " is not at least 1");
  e.eden.sites = static_cast<std::size_t>(w.sites);
  if (w.dimensions != 2 && w.dimensions != 3)
    throw InvalidInput("--dimensions " + std::to_string(w.dimensions) + " is not 2 or 3");
  e.eden.lattice = w.lattice.empty() ? (w.dimensions == 3 ? Lattice::cubic6 : Lattice::square4) : parse_word<Lattice>(w.lattice);
  if (!w.lattice.empty() && w.dimensions_option->count() && dimensions_of(e.eden.lattice) != w.dimensions)
    throw InvalidInput("--lattice " + w.lattice + " is not a lattice in " + std::to_string(w.dimensions) + "D");
  w.options->finish(e.eden);
  if (w.mask.size() == 1 && w.mask.find_first_of("ABCD") == 0) {
    e.eden.mask = parse_word<EdenMask>(w.mask);
  } else {
    e.mask_file = w.mask;  // read, and checked, when the run is prepared
  }
  e.links = links_of(*w.links);
  w.files->finish(e.files);
  validate(e);
}

}  // namespace

Subcommand add_eden_command(CLI::App& app, const Model& model) {
  auto w = std::make_shared<EdenWords>();
  auto e = std::make_shared<EdenRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  const char* group = "Eden";
  w->sites = static_cast<long long>(e->eden.sites);
  command->add_option("-n,--sites", w->sites, "sites at most, the seed included")->capture_default_str()->group(group);
  w->dimensions_option = command->add_option("--dimensions", w->dimensions, "2, or 3 for a cubic lattice")
                             ->capture_default_str()->group(group);
  command->add_option("--lattice", w->lattice, "square4, square8 or hex in 2D; cubic6, cubic18 or cubic26 in 3D "
                                               "(the number: neighbours); default square4, in 3D cubic6")
      ->group(group);
  w->options = std::make_unique<DescribedOptions<EdenOptions>>(*command, eden_option_table(), e->eden, &w->described);
  command->add_option("--mask", w->mask, "drop: A, B, C or D (the paper's masks: 4, 8, 12 and 24 sites around), "
                                         "or a file drawing one; default A")->group(group);
  command->add_option("--mask-threshold", e->eden.mask_threshold, "drop: occupied mask sites a site needs, 1 to the mask's size")
      ->capture_default_str()->group(group);
  command->add_option("--spacing", e->eden.spacing, "distance between neighbouring sites, [1e-25, 1e25]")
      ->capture_default_str()->group(group);
  command->add_option("--rng-seed", e->eden.rng_seed, "seed of the random generator: the same seed gives "
                                                      "the same files")
      ->capture_default_str()->group(group);
  w->links = add_links_option(*command, true);
  w->files = std::make_unique<OutputWords>(*command, e->files, *quiet);
  return {command,
          [w, e, quiet](CommandLine& line, const std::vector<std::string>&) {
            finish(*e, *w);
            line.quiet = *quiet;
            line.run = *e;
          },
          w->described};
}

}  // namespace dla::cli
