// dla3d: grows a DLA structure and writes it as a POV-Ray scene, CSV, PLY and a JSON sidecar.

#include "dla/analysis.h"
#include "dla/checkpoint.h"
#include "dla/constraint.h"
#include "dla/csv_writer.h"
#include "dla/growth.h"
#include "dla/mesh.h"
#include "dla/ply_writer.h"
#include "dla/pov_writer.h"
#include "dla/run_report.h"
#include "dla/version.h"

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <csignal>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

//! "x,y,z" (or more numbers for a box) as doubles; throws InvalidInput naming the flag.
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
    throw dla::InvalidInput(flag + " '" + text + "' is not " + std::to_string(count) +
                            " comma-separated numbers");
  return values;
}

dla::Vec3 parse_vec3(const std::string& flag, const std::string& text) {
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {v[0], v[1], v[2]};
}

//! A non-negative amount rounded to a whole number, thousands grouped.
std::string with_commas(double value) { return dla::detail::format_count(static_cast<std::uint64_t>(value + 0.5)); }

//! A one-line progress bar on stderr, drawn only on a terminal and only once a run has taken
//! a second.
class ProgressBar {
 public:
  ProgressBar(std::size_t total, bool enabled) : total_(total), enabled_(enabled), start_(Clock::now()) {}

  void update(std::size_t done) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double fraction = total_ ? static_cast<double>(done) / total_ : 1.0;
    const double rate = done / elapsed;
    const double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '=');
    bar.resize(width, ' ');
    std::fprintf(stderr, "\r\033[K%3d%% [%s] %s/%s  %s/s  ETA %d:%02d", static_cast<int>(fraction * 100),
                 bar.c_str(), with_commas(done).c_str(), with_commas(total_).c_str(),
                 with_commas(rate).c_str(), static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
    drawn_ = true;
  }

  void clear() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }

 private:
  std::size_t total_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_;
  Clock::time_point last_{};
};

//! Fails early, before a long run, if `path` cannot be created (its temporary name is tried).
void check_writable(const std::string& path) {
  const std::string probe = path + ".tmp";
  {
    std::ofstream out(probe);
    if (!out) throw dla::IOError("cannot write '" + path + "': " + std::strerror(errno));
  }
  std::remove(probe.c_str());
}

//! A spacing of about a two-hundredth of the mesh box's longest side, rounded to two digits.
double default_spacing(const dla::Box& box) {
  const double raw = (box.max - box.min).maxCoeff() / 200.0;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)) - 1.0);
  return std::round(raw / unit) * unit;
}

//! The axis of the mesh box's longest side, y on a tie: standing figures and vessels come out
//! upright.
dla::Axis longest_axis(const dla::Box& box) {
  const dla::Vec3 size = box.max - box.min;
  if (size.z() > size.y() && size.z() > size.x()) return dla::Axis::z;
  if (size.x() > size.y()) return dla::Axis::x;
  return dla::Axis::y;
}

//! A structure read back from dla3d's CSV (id,x,y,z,parent,seed). The spacing is the median
//! branch length; the structure is planar if every z is 0.
dla::Cluster read_structure_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw dla::IOError("cannot read '" + path + "': " + std::strerror(errno));
  std::string line;
  if (!std::getline(in, line) || line.rfind("id,x,y,z,parent,seed", 0) != 0)
    throw dla::InvalidInput(path + ": is not a dla3d CSV (no 'id,x,y,z,parent,seed' header)");
  dla::Cluster cluster;
  cluster.dimensions = 2;
  std::vector<double> lengths;
  for (std::size_t row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    std::vector<double> v;
    try {
      v = parse_numbers("row", line, 6);
    } catch (const dla::InvalidInput&) {
      throw dla::InvalidInput(path + ": line " + std::to_string(row) + " is not 6 numbers");
    }
    dla::Particle p{{v[1], v[2], v[3]}, static_cast<std::int32_t>(v[4]), static_cast<std::int32_t>(v[5])};
    const auto index = static_cast<double>(cluster.particles.size());
    if (v[0] != index || !(p.parent == -1 || (p.parent >= 0 && p.parent < v[0])) || !p.position.allFinite())
      throw dla::InvalidInput(path + ": line " + std::to_string(row) + " is not a particle after the ones before it");
    if (p.parent < 0) {
      ++cluster.seed_count;
    } else {
      lengths.push_back((p.position - cluster.particles[static_cast<std::size_t>(p.parent)].position).norm());
    }
    if (p.position.z() != 0.0) cluster.dimensions = 3;
    cluster.particles.push_back(p);
  }
  if (lengths.empty()) throw dla::InvalidInput(path + ": has no branches to measure");
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  cluster.spacing = lengths[lengths.size() / 2];
  return cluster;
}

//! `dla3d analyze PREFIX.csv`: the fractal dimension of a grown structure, as JSON on stdout.
int analyze(const std::string& path) {
  const dla::Cluster cluster = read_structure_csv(path);
  const dla::FractalFit gyration = dla::fractal_dimension_by_gyration(cluster);
  const dla::FractalFit mass = dla::fractal_dimension_by_mass_radius(cluster);
  const auto value = [](const dla::FractalFit& fit) {
    return fit.samples >= 2 ? dla::detail::format_number(fit.dimension) : std::string("null");
  };
  std::printf("{\n  \"file\": \"%s\",\n  \"particles\": %zu,\n  \"seeds\": %zu,\n  \"spacing\": %s,\n"
              "  \"dimensions\": %d,\n  \"radius_of_gyration\": %s,\n  \"fractal_dimension_gyration\": %s,\n"
              "  \"fractal_dimension_mass_radius\": %s\n}\n",
              path.c_str(), cluster.particles.size(), cluster.seed_count,
              dla::detail::format_number(cluster.spacing).c_str(), cluster.dimensions,
              dla::detail::format_number(dla::radius_of_gyration(cluster)).c_str(), value(gyration).c_str(),
              value(mass).c_str());
  return 0;
}

//! `dla3d convert IN OUT.stl`: the project's own mesh reading, to make bust.stl at setup.
int convert(const std::string& in, const std::string& out, bool quiet) {
  if (out.size() < 4 || (out.compare(out.size() - 4, 4, ".stl") != 0 && out.compare(out.size() - 4, 4, ".STL") != 0))
    throw dla::InvalidInput("convert writes binary STL: '" + out + "' does not end in .stl");
  const dla::TriangleMesh mesh = dla::read_mesh(in);
  dla::write_stl(mesh, out);
  if (!quiet)
    std::fprintf(stderr, "dla3d: wrote %s: %s triangles from %s\n", out.c_str(),
                 with_commas(static_cast<double>(mesh.triangles.size())).c_str(), in.c_str());
  return 0;
}

//! The signal (SIGINT, SIGTERM) that asked the run to stop, 0 if none. A second one ends the
//! process at once.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int signal) {
  stop_signal = signal;
  std::signal(signal, SIG_DFL);
}

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

//! Runs dla3d with `args` (argv without the program name); with `resumed`, grows on from that
//! checkpoint, whose command `args` then is.
int run(const std::vector<std::string>& args, const dla::Checkpoint* resumed = nullptr) {
  std::vector<char*> argv{const_cast<char*>("dla3d")};
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  const int argc = static_cast<int>(argv.size());
  CLI::App app{"Grows a branching structure by off-lattice diffusion-limited aggregation and writes\n"
               "it as a POV-Ray scene (PREFIX.pov, PREFIX.inc), PREFIX.csv, PREFIX.ply and PREFIX.json.",
               "dla3d"};
  app.set_version_flag("--version", std::string("dla3d ") + dla::version);
  app.get_formatter()->column_width(34);

  dla::GrowthOptions options;
  dla::PovOptions pov;
  long long particles = static_cast<long long>(options.particles);
  std::string output = "dla";
  std::vector<std::string> seed_at;
  std::string spawn = std::string(to_string(options.spawn));
  std::string spawn_axis = std::string(to_string(options.spawn_axis));
  std::string box, drift, index = std::string(to_string(options.index));
  bool quiet = false;
  std::string mesh_path;
  dla::ConstraintOptions constraint_options;
  std::string side = std::string(to_string(constraint_options.side));
  std::string constraint_mode = std::string(to_string(constraint_options.mode));
  std::size_t seed_count = 0;
  bool scene_mesh = true;
  std::string up = std::string(to_string(pov.up));

  const char* growth = "Growth";
  app.add_option("-n,--particles", particles, "particles to attach, seeds not counted")
      ->capture_default_str()->group(growth);
  CLI::Option* spacing = app.add_option(
      "--spacing", options.spacing,
      "distance between a particle and its parent; also the contact distance; with a mesh, "
      "default: its longest side / 200")->capture_default_str()->group(growth);
  app.add_option("--stickiness", options.stickiness, "probability of sticking at a contact, in (0, 1]")
      ->capture_default_str()->group(growth);
  app.add_option("--dimensions", options.dimensions, "3, or 2 for growth in the plane z = 0")
      ->capture_default_str()->group(growth);
  CLI::Option* seed_at_option =
      app.add_option("--seed-at", seed_at, "a seed at x,y,z (repeat for several); default: one at the origin")
          ->type_name("X,Y,Z")->allow_extra_args(false)->group(growth);
  app.add_option("--rng-seed", options.rng_seed, "seed of the random generator: the same seed gives the same files")
      ->capture_default_str()->group(growth);
  app.add_option("--min-step", options.min_step, "step length next to the structure, in spacings, (0, 1]")
      ->capture_default_str()->group(growth);
  app.add_option("--index", index, "nearest-particle look-up: grid, kdtree or brute")
      ->capture_default_str()->group(growth);
  app.add_option("--threads", options.threads,
                 "walkers run at once, 1-256 (grid index); the files do not depend on it")
      ->capture_default_str()->group(growth);

  const char* meshes = "Mesh constraint";
  app.add_option("--stl,--mesh", mesh_path, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
      ->type_name("FILE")->group(meshes);
  app.add_option("--side", side, "inside, outside or both (the mesh is only a wall; not closed)")
      ->capture_default_str()->group(meshes);
  app.add_option("--constraint", constraint_mode, "a branch crossing the mesh: reject (walk on) or clip (end at it)")
      ->capture_default_str()->group(meshes);
  CLI::Option* seeds_option =
      app.add_option("--seeds", seed_count, "place this many seeds on the growing side, far apart; default 1")
          ->type_name("K")->group(meshes)->excludes(seed_at_option);
  app.add_flag("--scene-mesh,!--no-scene-mesh", scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
      ->capture_default_str()->group(meshes);

  const char* spawning = "Spawn";
  CLI::Option* spawn_option =
      app.add_option("--spawn", spawn, "where walkers start: sphere, disk, box, or with a mesh inside or radial; "
                                       "with --side inside, default inside")
          ->capture_default_str()->group(spawning);
  app.add_option("--spawn-axis", spawn_axis, "disk: the axis the disk sits on, x, y or z")
      ->capture_default_str()->group(spawning);
  app.add_option("--disk-radius", options.disk_radius, "disk: radius as a fraction of the launch radius")
      ->capture_default_str()->group(spawning);
  app.add_option("--box", box, "box: a fixed box; default: the cube around the launch sphere")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(spawning);
  app.add_option("--drift", drift, "bias of every step, per unit step length, length < 1")
      ->type_name("X,Y,Z")->group(spawning);

  const char* outputs = "Output";
  app.add_option("-o,--output", output, "prefix of the files written")->capture_default_str()->group(outputs);
  app.add_option("--base-radius", pov.base_radius, "POV-Ray: branch radius at a strand's start, in spacings")
      ->capture_default_str()->group(outputs);
  app.add_option("--tip-radius", pov.tip_radius, "POV-Ray: branch radius at a strand's tip, in spacings")
      ->capture_default_str()->group(outputs);
  CLI::Option* up_option =
      app.add_option("--up", up, "POV-Ray: the axis that is up in the picture, x, y or z; with a mesh, "
                                 "default: its longest side's")->capture_default_str()->group(outputs);
  app.add_flag("-q,--quiet", quiet, "no progress bar and no summary")->group(outputs);

  const char* runs = "Long runs";
  std::string checkpoint_path, resume_path;
  double checkpoint_every = 60.0;
  app.add_option("--checkpoint", checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  app.add_option("--checkpoint-every", checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  CLI::Option* resume_option =
      app.add_option("--resume", resume_path, "grow on from a checkpoint, with the options it was started with")
          ->type_name("FILE")->group(runs);

  std::string convert_in, convert_out;
  CLI::App* convert_command =
      app.add_subcommand("convert", "read a mesh (STL, OFF, OBJ, PLY) and write it as binary STL, then stop");
  convert_command->add_option("in", convert_in, "the mesh to read")->required();
  convert_command->add_option("out", convert_out, "the .stl to write")->required();
  std::string analyze_csv;
  CLI::App* analyze_command = app.add_subcommand(
      "analyze", "print the fractal dimension of a grown structure (by gyration and by mass-radius) as JSON");
  analyze_command->add_option("csv", analyze_csv, "a CSV that dla3d wrote")->required();
  app.require_subcommand(0, 1);

  try {
    app.parse(argc, argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "dla3d: error: %s (see dla3d --help)\n", e.what());
    return 2;
  }

  if (convert_command->parsed()) {
    try {
      return convert(convert_in, convert_out, quiet);
    } catch (const dla::InvalidInput& e) {
      std::fprintf(stderr, "dla3d: error: %s\n", e.what());
      return 2;
    }
  }

  if (analyze_command->parsed()) return analyze(analyze_csv);

  if (resume_option->count()) {
    if (resumed) throw dla::InvalidInput("a checkpoint's command cannot itself resume");
    // Only -q and --threads may go with --resume: every other option comes from the checkpoint.
    // The thread count changes how fast it goes on, never what it grows.
    const auto is_threads = [](const std::string& arg) { return arg == "--threads" || arg.rfind("--threads=", 0) == 0; };
    std::size_t others = 0;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--resume" || args[i] == "--threads") ++i;
      else if (args[i].rfind("--resume=", 0) != 0 && !is_threads(args[i]) && args[i] != "-q" && args[i] != "--quiet")
        ++others;
    }
    if (others > 0) {
      std::fprintf(stderr, "dla3d: error: --resume takes no other options but -q and --threads: they come from the checkpoint\n");
      return 2;
    }
    const dla::Checkpoint checkpoint = dla::read_checkpoint(resume_path);
    std::vector<std::string> command;
    for (std::size_t i = 0; i < checkpoint.command.size(); ++i) {
      if (checkpoint.command[i] == "--threads" && app.count("--threads")) ++i;  // replaced below
      else if (!(is_threads(checkpoint.command[i]) && app.count("--threads"))) command.push_back(checkpoint.command[i]);
    }
    if (app.count("--threads")) command.insert(command.end(), {"--threads", std::to_string(options.threads)});
    if (quiet) command.push_back("-q");
    return run(command, &checkpoint);
  }

  std::unique_ptr<dla::MeshConstraint> constraint;
  std::uint64_t input_hash = 0;
  try {
    if (!(checkpoint_every >= 0.0))
      throw dla::InvalidInput("--checkpoint-every " + dla::detail::format_number(checkpoint_every) + " is negative");
    if (particles < 0) throw dla::InvalidInput("--particles " + std::to_string(particles) + " is negative");
    options.particles = static_cast<std::size_t>(particles);
    if (!seed_at.empty()) {
      options.seeds.clear();
      for (const std::string& s : seed_at) options.seeds.push_back(parse_vec3("--seed-at", s));
    }
    options.spawn = dla::parse_spawn_mode(spawn);
    options.spawn_axis = dla::parse_axis(spawn_axis);
    options.index = dla::parse_index_kind(index);
    pov.up = dla::parse_axis(up);
    if (!box.empty()) {
      const std::vector<double> b = parse_numbers("--box", box, 6);
      options.spawn_box = dla::Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
      if (options.spawn != dla::SpawnMode::box)
        throw dla::InvalidInput("--box is for --spawn box, not --spawn " + spawn);
    }
    if (!drift.empty()) options.drift = parse_vec3("--drift", drift);
    if (output.empty()) throw dla::InvalidInput("--output is empty");
    constraint_options.side = dla::parse_side(side);
    constraint_options.mode = dla::parse_constraint_mode(constraint_mode);
    if (mesh_path.empty() && seeds_option->count())
      throw dla::InvalidInput("--seeds places seeds in a mesh given with --stl; without one, use --seed-at");
    dla::validate(pov);
    check_writable(output + ".json");  // before a mesh's set-up and a long run
    if (!checkpoint_path.empty()) check_writable(checkpoint_path);
    if (!mesh_path.empty()) {
      const dla::TriangleMesh mesh = dla::read_mesh(mesh_path, &input_hash);
      if (resumed && resumed->input_hash != input_hash)
        throw dla::InvalidInput(mesh_path + " has changed since the checkpoint was written: the run cannot go on");
      const dla::Box box = dla::bounding_box(mesh);
      if (!spacing->count()) options.spacing = default_spacing(box);
      if (!up_option->count()) pov.up = longest_axis(box);
      dla::detail::require_positive("spacing", options.spacing);
      try {
        constraint = std::make_unique<dla::MeshConstraint>(mesh, constraint_options, options.spacing);
      } catch (const dla::InvalidInput& e) {
        throw dla::InvalidInput(mesh_path + ": " + e.what());
      }
      if (!quiet)
        std::fprintf(stderr, "dla3d: %s: %s triangles; %s; spacing %g\n", mesh_path.c_str(),
                     with_commas(static_cast<double>(mesh.triangles.size())).c_str(),
                     constraint->repair_report().summary().c_str(), options.spacing);
      if (!spawn_option->count())
        options.spawn = constraint_options.side == dla::Side::inside ? dla::SpawnMode::inside : dla::SpawnMode::sphere;
      if (!seed_at_option->count()) options.seeds = constraint->place_seeds(seed_count ? seed_count : 1, options.rng_seed);
      dla::validate(options, *constraint);
    } else {
      dla::validate(options);
    }
  } catch (const dla::InvalidInput& e) {
    std::fprintf(stderr, "dla3d: error: %s\n", e.what());
    return 2;
  }

  ProgressBar bar(options.particles, !quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  Clock::time_point saved = start;
  // A save that fails (a full disk) is reported once and does not stop the run.
  bool save_failed = false;
  const auto save = [&](const dla::Cluster& so_far) {
    if (checkpoint_path.empty()) return;
    try {
      dla::write_checkpoint({args, input_hash, so_far}, checkpoint_path);
    } catch (const dla::IOError& e) {
      if (!save_failed) std::fprintf(stderr, "\r\033[Kdla3d: warning: %s; growth goes on\n", e.what());
      save_failed = true;
    }
  };
  const auto progress = [&](const dla::Cluster& so_far) {
    bar.update(dla::attached(so_far));
    if (stop_signal) return false;
    if (!checkpoint_path.empty() && Clock::now() - saved >= std::chrono::duration<double>(checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  const dla::Cluster cluster =
      resumed ? (constraint ? dla::resume(options, *constraint, resumed->cluster, progress)
                            : dla::resume(options, resumed->cluster, progress))
              : (constraint ? dla::grow(options, *constraint, progress) : dla::grow(options, progress));
  bar.clear();
  dla::RunTimings timings;
  timings.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();

  std::string command = "dla3d";
  for (const std::string& arg : args) command += " " + arg;
  pov.comment = command;
  const Clock::time_point write_start = Clock::now();
  dla::write_csv(cluster, output + ".csv");
  dla::write_ply(cluster, output + ".ply");
  dla::write_pov(cluster, output, pov, constraint && scene_mesh ? &constraint->mesh() : nullptr);
  timings.write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
  dla::write_run_report(cluster, options, pov, timings, output + ".json", constraint.get(), mesh_path);
  if (!cluster.complete) save(cluster);  // after the files: they matter more

  if (!quiet) {
    const double attached = static_cast<double>(cluster.particles.size() - cluster.seed_count);
    std::fprintf(stderr,
                 "dla3d: grew %s particles in %.2f s (%s particles/s); bounding radius %.1f, "
                 "radius of gyration %.1f\n"
                 "dla3d: wrote %s.pov %s.inc %s.csv %s.ply %s.json; render: povray +W1280 +H960 +A %s.pov\n",
                 with_commas(attached).c_str(), timings.grow_seconds,
                 with_commas(timings.grow_seconds > 0 ? attached / timings.grow_seconds : 0.0).c_str(),
                 dla::bounding_radius(cluster), dla::radius_of_gyration(cluster), output.c_str(),
                 output.c_str(), output.c_str(), output.c_str(), output.c_str(), output.c_str());
  }
  if (!cluster.complete) {
    const int signal = stop_signal;
    std::fprintf(stderr, "dla3d: stopped by %s after %s of %s particles; the files hold them%s%s\n",
                 signal_name(signal), with_commas(static_cast<double>(dla::attached(cluster))).c_str(),
                 with_commas(static_cast<double>(options.particles)).c_str(),
                 checkpoint_path.empty() ? "" : "; go on with: dla3d --resume ", checkpoint_path.c_str());
    return 128 + signal;
  }
  if (!checkpoint_path.empty()) std::remove(checkpoint_path.c_str());  // the run is whole: nothing to resume
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const dla::InvalidInput& e) {
    std::fprintf(stderr, "dla3d: error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "dla3d: error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dla3d: error: %s\n", e.what());
  }
  return 1;
}
