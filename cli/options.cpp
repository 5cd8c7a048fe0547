#include "options.h"

#include <sstream>

namespace dla::cli {

std::vector<double> parse_numbers(const std::string& flag, const std::string& text, std::size_t count) {
  std::vector<double> values;
  bool numbers = true;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    try {
      values.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    numbers = numbers && used > 0 && used == item.size();
  }
  if (!numbers || values.size() != count)
    throw InvalidInput(flag + " '" + text + "' is not " + std::to_string(count) + " comma-separated numbers");
  return values;
}

Vec3 parse_vec3(const std::string& flag, const std::string& text) {
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {v[0], v[1], v[2]};
}

std::vector<Vec3> parse_points(const std::string& flag, const std::vector<std::string>& texts) {
  std::vector<Vec3> points;
  for (const std::string& text : texts) points.push_back(parse_vec3(flag, text));
  return points;
}

Box parse_box(const std::string& flag, const std::string& text) {
  const std::vector<double> b = parse_numbers(flag, text, 6);
  return Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
}

std::size_t parse_count(const std::string& flag, long long value) {
  if (value < 0) throw InvalidInput(flag + " " + std::to_string(value) + " is negative");
  return static_cast<std::size_t>(value);
}

OutputWords::OutputWords(CLI::App& app, OutputOptions& f, bool& quiet, std::string formats) {
  if (!formats.empty()) formats_ = parse_formats(formats);
  OutputOptions defaults = f;
  if (formats_) defaults.formats = *formats_;
  files_ = std::make_unique<DescribedOptions<OutputOptions>>(app, files_option_table(), defaults, nullptr);
  // Binary became the default on 2026-11-24; the old flag still runs the scripts and resumes
  // the checkpoints that name it. Not in --help.
  app.add_flag_callback("--binary", [&f] { f.ply_encoding = PlyEncoding::binary; })->group("");
  options_ = std::make_unique<DescribedOptions<OutputOptions>>(app, output_option_table(), f, nullptr);
  app.add_flag("-q,--quiet", quiet, "no progress bar and no summary")->group("Output");
  // `dla3d frames` (whose default is glb alone) draws a finished CSV: nothing attaches to stream.
  if (!formats_)
    app.add_option("--stream", "write each particle as it attaches to FILE (a pipe for a live view), binary: "
                               "docs/studio.md#the-stream")
        ->type_name("FILE")->group("Output");
}

void OutputWords::finish(OutputOptions& f) const {
  if (formats_) f.formats = *formats_;
  files_->finish(f);
  options_->finish(f);
}

void add_refused_mesh_controls(CLI::App& app, const char* group, std::string_view model) {
  for (const char* option : {"fill", "shell"}) {
    app.add_option_function<std::string>(
           std::string("--") + option, [model, option](const std::string&) { refuse_for(model, option); },
           std::string(option) == "fill" ? "DLA's: grow until a mesh is full (not for " + std::string(model) + ")"
                                         : "DLA's: keep growth near the surface (not for " + std::string(model) + ")")
        ->type_name(std::string(option) == "fill" ? "F" : "T")->group(group);
  }
}

std::unique_ptr<DescribedOptions<LinkOptions>> add_links_option(CLI::App& command, bool lattice) {
  return std::make_unique<DescribedOptions<LinkOptions>>(command, links_option_table(lattice), LinkOptions{}, nullptr);
}

void add_seeded_options(CLI::App& command, const char* group, SeededWords& w, int& dimensions, double& spacing,
                        std::uint64_t& rng_seed, const std::string& spacing_help) {
  command.add_option("-n,--particles", w.particles, "particles to attach, seeds not counted")
      ->capture_default_str()->group(group);
  command.add_option("--dimensions", dimensions, "3, or 2 for growth in the plane z = 0")->capture_default_str()->group(group);
  w.spacing = command.add_option("--spacing", spacing, "distance between a particle and its parent; no two come closer; "
                                                       "[1e-25, 1e25]" + spacing_help)->capture_default_str()->group(group);
  w.seed_at_option = command.add_option("--seed-at", w.seed_at, "a seed at x,y,z (repeat for several); default: one at the origin "
                                                                "(with a mesh, one on its growing side)")
      ->type_name("X,Y,Z")->allow_extra_args(false)->group(group);
  command.add_option("--rng-seed", rng_seed, "seed of the random generator: the same seed gives the same files")
      ->capture_default_str()->group(group);
  w.links = add_links_option(command);
}

}  // namespace dla::cli
