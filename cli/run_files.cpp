#include "run_files.h"

#include "model_run.h"

#include "dla/io/csv_writer.h"
#include "dla/io/mesh_writers.h"
#include "dla/io/ply_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/mesh/surface_distance.h"
#include "dla/io/png_writer.h"
#include "dla/io/svg_writer.h"
#include "dla/io/html_writer.h"

#include <malloc.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <future>
#include <memory>

namespace dla::cli {

std::string with_commas(double value) { return detail::format_count(static_cast<std::uint64_t>(value + 0.5)); }

void check_writable(const std::string& path) {
  const std::string probe = path + ".tmp";
  {
    std::ofstream out(probe);
    if (!out) throw InvalidInput("cannot write '" + path + "': " + std::strerror(errno));
  }
  std::remove(probe.c_str());
}

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

std::vector<std::string> file_names(const FileOptions& files) {
  const Formats& f = files.formats;
  const std::string& o = files.output;
  std::vector<std::string> names;
  if (f.pov) names.insert(names.end(), {o + ".pov", o + ".inc", o + "_growth.inc"});
  if (f.csv) names.push_back(o + ".csv");
  if (f.ply) names.push_back(o + ".ply");
  if (f.glb) names.push_back(o + ".glb");
  if (f.obj) names.push_back(o + ".obj");
  if (f.tips) names.push_back(o + "_tips.ply");
  if (f.svg) names.push_back(o + ".svg");
  if (f.png) names.push_back(o + ".png");
  if (f.html) names.push_back(o + ".html");
  if (f.json) names.push_back(o + ".json");
  return names;
}

// A spacing of about a hundredth of the mesh box's longest side, rounded to two digits.
double default_spacing(const Box& box) {
  const double raw = (box.max - box.min).maxCoeff() / 100.0;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)) - 1.0);
  return std::round(raw / unit) * unit;
}

// The axis of the mesh box's longest side, y on a tie: standing figures and vessels come out
// upright.
Axis longest_axis(const Box& box) {
  const Vec3 size = box.max - box.min;
  if (size.z() > size.y() && size.z() > size.x()) return Axis::z;
  if (size.x() > size.y()) return Axis::x;
  return Axis::y;
}

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

void write_files(const Cluster& cluster, const FileOptions& files, const PovOptions& pov, int threads,
                 const MeshConstraint* constraint, const TriangleMesh* scene_mesh) {
  // What growth freed (the index) goes back to the system before the writers take theirs.
  malloc_trim(0);
  // The writers' threads free buffers of a few hundred kB: mapped, not kept in each thread's
  // heap, where glibc's adaptive threshold would leave them (about 1 byte a particle at 10^7).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  const Formats& formats = files.formats;
  const std::string& output = files.output;
  const PlyEncoding encoding = files.ply_encoding;
  const Look look = [&] {
    // The distance to the mesh feeds the boundary model and the scene's switch to it.
    const std::unique_ptr<SurfaceDistance> surface =
        constraint ? std::make_unique<SurfaceDistance>(constraint->mesh()) : nullptr;
    // The tips' gaps only for the files with instancing points: PREFIX_tips.ply and .inc.
    return make_look(cluster, files.look, {surface.get(), nullptr, threads, formats.tips});
  }();
  std::vector<std::future<void>> writers;
  const auto write = [&](bool wanted, auto&& writer) {
    if (wanted) writers.push_back(std::async(std::launch::async, writer));
  };
  write(formats.csv, [&] { write_csv(cluster, look, output + ".csv"); });
  write(formats.ply, [&] { write_ply(cluster, look, output + ".ply", encoding); });
  write(formats.glb, [&] { write_glb(cluster, look, output + ".glb"); });
  write(formats.obj, [&] { write_obj(cluster, look, output + ".obj"); });
  write(formats.tips, [&] {
    write_instances_ply(cluster, look.attributes, files.instances, output + "_tips.ply", encoding);
  });
  write(formats.svg, [&] { write_svg(cluster, look, output + ".svg"); });
  write(formats.png, [&] { write_png(cluster, output + ".png", files.png); });
  write(formats.html, [&] {
    HtmlOptions html;
    html.up = pov.up;
    const std::size_t slash = output.find_last_of('/');
    html.title = "dla3d: " + (slash == std::string::npos ? output : output.substr(slash + 1));
    write_html(cluster, look, output + ".html", html, scene_mesh);
  });
  if (formats.pov) write_pov(cluster, output, pov, scene_mesh, &look);
  for (std::future<void>& writer : writers) writer.get();
}

Cluster grow_recorded(ModelRun& run, const ProgressFn& progress, const StopFlag& stop,
                      const volatile std::sig_atomic_t& stop_signal, const std::vector<std::string>& args,
                      RunRecord& record, std::string& error) {
  const Clock::time_point start = Clock::now();
  Cluster cluster;
  try {
    cluster = run.grow(progress, &stop);
  } catch (const PartialGrowth& e) {
    cluster = e.partial();
    error = e.what();
  }
  record.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  record.command = command_line(args);
  if (!error.empty()) record.stopped_by = "error: " + error;
  else if (!cluster.complete) record.stopped_by = signal_name(stop_signal);
  return cluster;
}

void print_summary(const ModelRun& run, const Cluster& cluster, const FileOptions& files, const RunRecord& record) {
  std::string written;
  for (const std::string& name : file_names(files)) written += (written.empty() ? "" : " ") + name;
  const std::string render = files.formats.pov ? "; render: povray +W1280 +H960 +A " + files.output + ".pov" : "";
  std::fprintf(stderr, "dla3d: %s\ndla3d: wrote %s%s\n", run.summary(cluster, record).c_str(), written.c_str(),
               render.c_str());
}

}  // namespace dla::cli
