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

OutputWords::OutputWords(CLI::App& app, OutputOptions& f, bool& quiet, std::string formats)
    : formats_(formats.empty() ? format_words(f.formats) : std::move(formats)) {
  const char* outputs = "Output";
  app.add_option("-o,--output", f.output, "prefix of the files written")->capture_default_str()->group(outputs);
  app.add_option("--formats", formats_, "files to write, a comma list of pov, csv, spheres (PREFIX_spheres.csv: "
                                        "x,y,z,r), mstm (MSTM's PREFIX_mstm.pos), ddscat (DDSCAT's "
                                        "PREFIX_ddscat.dat), ply, json, glb, obj, tips "
                                        "(PREFIX_tips.ply, and with pov PREFIX_tips.inc), svg and png (2D), html (the web viewer), "
                                        "and the watertight solid: stl, 3mf, vdb, solid-glb, solid-obj")->capture_default_str()->group(outputs);
  // Binary became the default on 2026-11-24; the old flag still runs the scripts and resumes
  // the checkpoints that name it. Not in --help.
  app.add_flag_callback("--binary", [&f] { f.ply_encoding = PlyEncoding::binary; })->group("");
  options_ = std::make_unique<DescribedOptions<OutputOptions>>(app, output_option_table(), f, nullptr);
  const char* looks = "Look";
  app.add_option("--leaf", f.leaf, "glb: a binary glTF whose mesh goes at each instancing point (as tips picks "
                                  "them), along its direction and scaled by its pscale; its +Y is the leaf's stem")
      ->type_name("FILE.glb")->group(looks);
  exclude_paint_option_ =
      app.add_option("--tips-exclude-paint", exclude_paint_, "tips: leave out the points whose closest point of the "
                                                             "mesh's surface is painted this colour (a name or ff8000), "
                                                             "within TOLERANCE per channel, [0, 1), default 0.3")
          ->type_name("COLOR[,TOLERANCE]")->group(looks);
  app.add_flag("-q,--quiet", quiet, "no progress bar and no summary")->group(outputs);
  // `dla3d frames` (whose default is glb alone) draws a finished CSV: nothing attaches to stream.
  if (formats_ != "glb")
    app.add_option("--stream", "write each particle as it attaches to FILE (a pipe for a live view), binary: "
                               "docs/studio.md#the-stream")
        ->type_name("FILE")->group(outputs);
}

void OutputWords::finish(OutputOptions& f) const {
  options_->finish(f);
  if (exclude_paint_option_->count()) f.instances.exclude_paint = parse_paint(exclude_paint_, "tips_exclude_paint");
  f.formats = parse_formats(formats_);
}

SeedWords::SeedWords(CLI::App& app, MeshSeeds& seeds, const char* group, CLI::Option* placed_by,
                     const std::string& seeds_help, const std::string& surface_help)
    : placed_by_(placed_by) {
  count_option_ = app.add_option("--seeds", count_, seeds_help)->type_name("K|all")->group(group)->excludes(placed_by);
  CLI::Option* surface = app.add_flag("--seed-surface", seeds.surface, surface_help)
                             ->group(group)->excludes(count_option_)->excludes(placed_by);
  paint_option_ = app.add_option("--seed-paint", paint_, "seeds on the part of the surface painted this colour (a name or "
                                                         "ff8000), within TOLERANCE per channel, [0, 1), default 0.3")
                      ->type_name("COLOR[,TOLERANCE]")->group(group)->excludes(placed_by);
  app.add_option("--seed-mesh", seeds.meshes, "seeds where this mesh's surface meets the mesh (repeat for "
                                              "several): growth from where objects enter")
      ->type_name(kMeshFile)->allow_extra_args(false)->group(group)->excludes(placed_by)
      ->excludes(paint_option_)->excludes(surface);
}

void SeedWords::finish(MeshSeeds& seeds, bool has_mesh) const {
  if (!has_mesh && count_option_->count())
    throw InvalidInput("--seeds places seeds in a mesh given with --stl; without one, use " + placed_by_->get_name());
  if (!has_mesh && seeds.surface) throw InvalidInput("--seed-surface seeds a mesh's surface: give one with --stl");
  if (!has_mesh && paint_option_->count())
    throw InvalidInput("--seed-paint seeds the painted part of a mesh: give one with --stl");
  if (paint_option_->count()) seeds.paint = parse_paint(paint_);
  if (count_ == "all") {
    // Without paint or other meshes, all of the surface.
    seeds.surface = !paint_option_->count() && seeds.meshes.empty();
  } else if (count_option_->count()) {
    const bool digits = !count_.empty() && count_.size() <= 9 && count_.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) throw InvalidInput("--seeds '" + count_ + "' is neither a count of seeds nor all");
    seeds.count = std::stoul(count_);
    if (seeds.count == 0) throw InvalidInput("--seeds 0: there must be a seed");
  }
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

void add_links_option(CLI::App& command, const char* group, std::string& words, bool lattice) {
  command
      .add_option("--links", words,
                  std::string("also link each particle, as it attaches, to up to K (default 1) earlier ones within D "
                              "spacings and at least 8 tree steps away: loops (docs/loops.md)") +
                      (lattice ? "; lattice: every pair of neighbouring sites" : ""))
      ->type_name(lattice ? "D[,K]|lattice" : "D[,K]")
      ->group(group);
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
  add_links_option(command, group, w.links);
}

}  // namespace dla::cli
