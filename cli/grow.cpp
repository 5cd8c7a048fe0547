// `dla3d [options]`: grows a structure (in or around a mesh if one is given) and writes the
// POV-Ray scene, CSV, PLY and JSON sidecar; saves and resumes checkpoints.

#include "commands.h"

#include "dla/constraint.h"
#include "dla/csv_writer.h"
#include "dla/mesh.h"
#include "dla/mesh_writers.h"
#include "dla/ply_writer.h"
#include "dla/pov_writer.h"
#include "dla/run_report.h"
#include "dla/surface_distance.h"
#include "dla/svg_writer.h"

#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <memory>

namespace dla::cli {

namespace {

using Clock = std::chrono::steady_clock;

//! A non-negative amount rounded to a whole number, thousands grouped.
std::string with_commas(double value) { return detail::format_count(static_cast<std::uint64_t>(value + 0.5)); }

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
    if (!out) throw InvalidInput("cannot write '" + path + "': " + std::strerror(errno));
  }
  std::remove(probe.c_str());
}

//! Refuses, before growing, a run that cannot fit in this machine's memory: a structure takes
//! about 45 bytes a particle while it grows (docs/performance.md).
void check_memory(std::size_t particles) {
  constexpr double bytes_per_particle = 48.0;
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double memory = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double needed = bytes_per_particle * static_cast<double>(particles);
  if (pages > 0 && needed > memory)
    throw InvalidInput("--particles " + detail::format_count(particles) + " needs about " +
                       detail::format_number(needed / 1e9) + " GB of memory; this machine has " +
                       detail::format_number(memory / 1e9) + " GB");
}

//! A spacing of about a hundredth of the mesh box's longest side, rounded to two digits.
double default_spacing(const Box& box) {
  const double raw = (box.max - box.min).maxCoeff() / 100.0;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)) - 1.0);
  return std::round(raw / unit) * unit;
}

//! The axis of the mesh box's longest side, y on a tie: standing figures and vessels come out
//! upright.
Axis longest_axis(const Box& box) {
  const Vec3 size = box.max - box.min;
  if (size.z() > size.y() && size.z() > size.x()) return Axis::z;
  if (size.x() > size.y()) return Axis::x;
  return Axis::y;
}

//! The arguments as one line a shell reads back: words with anything but plain characters
//! are single-quoted.
std::string command_line(const std::vector<std::string>& args) {
  std::string line = "dla3d";
  for (const std::string& arg : args) {
    const bool plain = !arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_-+=.,:/@%") == std::string::npos;
    if (plain) {
      line += " " + arg;
      continue;
    }
    line += " '";
    for (const char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  return line;
}

//! The files the run writes, in --formats order, for the summary line.
std::vector<std::string> file_names(const GrowCommand& command) {
  const Formats& f = command.formats;
  const std::string& o = command.output;
  std::vector<std::string> names;
  if (f.pov) names.insert(names.end(), {o + ".pov", o + ".inc"});
  if (f.csv) names.push_back(o + ".csv");
  if (f.ply) names.push_back(o + ".ply");
  if (f.glb) names.push_back(o + ".glb");
  if (f.obj) names.push_back(o + ".obj");
  if (f.tips) names.push_back(o + "_tips.ply");
  if (f.svg) names.push_back(o + ".svg");
  if (f.json) names.push_back(o + ".json");
  return names;
}

std::string first_file(const GrowCommand& command) { return file_names(command).front(); }

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

}  // namespace

int grow(const GrowCommand& command, const std::vector<std::string>& args, const Checkpoint* resumed,
         const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal) {
  GrowthOptions options = command.options;
  PovOptions pov = command.pov;
  const std::string& output = command.output;
  std::unique_ptr<MeshConstraint> constraint;
  std::uint64_t input_hash = 0;
  {
    check_writable(first_file(command));  // before a mesh's set-up and a long run
    if (!command.checkpoint_path.empty()) check_writable(command.checkpoint_path);
    if (!command.mesh_path.empty()) {
      const TriangleMesh mesh = read_mesh(command.mesh_path, &input_hash);
      if (resumed && resumed->input_hash != input_hash)
        throw InvalidInput(command.mesh_path + " has changed since the checkpoint was written: the run cannot go on");
      const Box box = bounding_box(mesh);
      if (!command.spacing_given) options.spacing = default_spacing(box);
      if (!command.up_given) pov.up = longest_axis(box);
      detail::require_in("spacing", options.spacing, kMinSpacing, kMaxSpacing);
      try {
        constraint = std::make_unique<MeshConstraint>(mesh, command.constraint, options.spacing);
      } catch (const InvalidInput& e) {
        throw InvalidInput(command.mesh_path + ": " + e.what());
      }
      // From the skin inside: thin parts (horns, fingers) get walkers by their surface.
      if (!command.spawn_given)
        options.spawn = command.constraint.side == Side::inside ? SpawnMode::surface : SpawnMode::sphere;
      if (!command.seeds_given)
        options.seeds = constraint->place_seeds(command.seed_count ? command.seed_count : 1, options.rng_seed);
      validate(options, *constraint);
    }
    check_memory(options.particles);
    // Only once every option is known good: bad input gets its one line and nothing else.
    if (constraint && !command.quiet)
      std::fprintf(stderr, "dla3d: %s: %s triangles; %s; spacing %g\n", command.mesh_path.c_str(),
                   with_commas(static_cast<double>(constraint->repair_report().input_triangles)).c_str(),
                   constraint->repair_report().summary().c_str(), options.spacing);
  }

  ProgressBar bar(options.particles, !command.quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  Clock::time_point saved = start;
  // A save that fails (a full disk) is reported once and does not stop the run.
  bool save_failed = false;
  const auto save = [&](const Cluster& so_far) {
    if (command.checkpoint_path.empty()) return;
    try {
      write_checkpoint({args, input_hash, so_far}, command.checkpoint_path);
    } catch (const IOError& e) {
      bar.clear();
      if (!save_failed) std::fprintf(stderr, "dla3d: warning: %s; growth goes on\n", e.what());
      save_failed = true;
    }
  };
  const auto progress = [&](const Cluster& so_far) {
    bar.update(attached(so_far));
    if (stop.load()) return false;
    if (!command.checkpoint_path.empty() &&
        Clock::now() - saved >= std::chrono::duration<double>(command.checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  Cluster cluster;
  std::string error;  // why growth failed part way, if it did
  try {
    cluster = resumed ? (constraint ? resume(options, *constraint, resumed->cluster, progress, &stop)
                                    : resume(options, resumed->cluster, progress, &stop))
                      : (constraint ? dla::grow(options, *constraint, progress, &stop)
                                    : dla::grow(options, progress, &stop));
  } catch (const PartialGrowth& e) {
    cluster = e.partial();
    error = e.what();
  }
  bar.clear();
  RunRecord record;
  record.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  record.command = command_line(args);
  const int signal = stop_signal;
  if (!error.empty()) record.stopped_by = "error: " + error;
  else if (!cluster.complete) record.stopped_by = signal_name(signal);

  pov.comment = record.command;
  const Clock::time_point write_start = Clock::now();
  // The index is gone: its memory goes back to the system before the writers take theirs.
  malloc_trim(0);
  // The writers' threads free buffers of a few hundred kB: mapped, not kept in each thread's
  // heap, where glibc's adaptive threshold would leave them (about 1 byte a particle at 10^7).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  const Formats& formats = command.formats;
  const PlyEncoding encoding = command.binary_ply ? PlyEncoding::binary : PlyEncoding::ascii;
  const Look look = [&] {
    // The distance to the mesh feeds the boundary model and the scene's switch to it.
    const std::unique_ptr<SurfaceDistance> surface =
        constraint ? std::make_unique<SurfaceDistance>(constraint->mesh()) : nullptr;
    // The tips' gaps only for the files with instancing points: the PLY and CSV alone go faster.
    return make_look(cluster, command.look, {surface.get(), nullptr, options.threads, formats.pov || formats.tips});
  }();
  // The files are independent: written at once, a thread each, the same bytes as one by one.
  std::vector<std::future<void>> writers;
  const auto write = [&](bool wanted, auto&& writer) {
    if (wanted) writers.push_back(std::async(std::launch::async, writer));
  };
  write(formats.csv, [&] { write_csv(cluster, look, output + ".csv"); });
  write(formats.ply, [&] { write_ply(cluster, look, output + ".ply", encoding); });
  write(formats.glb, [&] { write_glb(cluster, look, output + ".glb"); });
  write(formats.obj, [&] { write_obj(cluster, look, output + ".obj"); });
  write(formats.tips, [&] {
    write_instances_ply(cluster, look.attributes, command.instances, output + "_tips.ply", encoding);
  });
  write(formats.svg, [&] { write_svg(cluster, look, output + ".svg"); });
  if (formats.pov)
    write_pov(cluster, output, pov, constraint && command.scene_mesh ? &constraint->mesh() : nullptr, &look);
  for (std::future<void>& writer : writers) writer.get();
  record.write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
  if (formats.json)
    write_run_report(cluster, options, command.look, pov, record, output + ".json", constraint.get(), command.mesh_path);
  if (!cluster.complete) save(cluster);  // after the files: they matter more

  const std::string resume_hint =
      command.checkpoint_path.empty() ? "" : "; go on with: dla3d --resume " + command.checkpoint_path;
  const std::string grown = with_commas(static_cast<double>(attached(cluster)));
  if (!error.empty()) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s particles grown before it\n", error.c_str(),
                 output.c_str(), grown.c_str());
    return 1;
  }
  if (!command.quiet) {
    const double count = static_cast<double>(attached(cluster));
    std::string written;
    for (const std::string& name : file_names(command)) written += (written.empty() ? "" : " ") + name;
    const std::string render = formats.pov ? "; render: povray +W1280 +H960 +A " + output + ".pov" : "";
    std::fprintf(stderr,
                 "dla3d: grew %s particles in %.2f s (%s particles/s); bounding radius %.1f, "
                 "radius of gyration %.1f\n"
                 "dla3d: wrote %s%s\n",
                 grown.c_str(), record.grow_seconds,
                 with_commas(record.grow_seconds > 0 ? count / record.grow_seconds : 0.0).c_str(),
                 bounding_radius(cluster), radius_of_gyration(cluster), written.c_str(), render.c_str());
  }
  if (!cluster.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s of %s particles; the files hold them%s\n",
                 signal_name(signal), grown.c_str(), with_commas(static_cast<double>(options.particles)).c_str(),
                 resume_hint.c_str());
    return 128 + signal;
  }
  if (!command.checkpoint_path.empty()) std::remove(command.checkpoint_path.c_str());  // whole: nothing to resume
  return 0;
}

}  // namespace dla::cli
