// write_run(): every file of a run, each by a writer behind one signature, on threads of their
// own (run.h).

#include "dla/run/run.h"

#include "dla/io/csv_writer.h"
#include "dla/io/html_writer.h"
#include "dla/io/mesh_writers.h"
#include "dla/io/ply_writer.h"
#include "dla/io/png_writer.h"
#include "dla/io/solid_writers.h"
#include "dla/io/pov_writer.h"
#include "dla/io/scattering_writers.h"
#include "dla/io/svg_writer.h"
#include "dla/mesh/surface_distance.h"
#include "io/output_file.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <thread>

namespace dla {

namespace {

//! What every writer is handed: the structure, its look, the run's files and the path (or, for
//! the POV-Ray scene, the prefix) to write.
struct WriteJob {
  const Cluster& cluster;
  const Look& look;
  const OutputOptions& files;
  const PovOptions& pov;
  const TriangleMesh* scene_mesh;
  const Leaf* leaf;  //!< for the glb, or null
  GlbWritten& glb;  //!< the glb's writer counts its levels' triangles and its leaves here
};

using Writer = void (*)(const WriteJob& job, const std::string& path);

//! One writer a format, by the flag that asks for it and the suffix of its file.
struct WriterEntry {
  bool Formats::*wanted;
  const char* suffix;
  Writer write;
};

const WriterEntry kWriters[] = {
    {&Formats::csv, ".csv", [](const WriteJob& j, const std::string& path) { write_csv(j.cluster, j.look, path); }},
    {&Formats::spheres, "_spheres.csv",
     [](const WriteJob& j, const std::string& path) { write_spheres_csv(j.cluster, j.look, path); }},
    {&Formats::mstm, "_mstm.pos",
     [](const WriteJob& j, const std::string& path) { write_mstm_positions(j.cluster, j.look, path); }},
    {&Formats::ddscat, "_ddscat.dat",
     [](const WriteJob& j, const std::string& path) {
       write_ddscat_shape(j.cluster, j.look, j.files.ddscat_resolution, path);
     }},
    {&Formats::ply, ".ply",
     [](const WriteJob& j, const std::string& path) { write_ply(j.cluster, j.look, path, j.files.ply_encoding); }},
    {&Formats::glb, ".glb",
     [](const WriteJob& j, const std::string& path) {
       j.glb = write_glb(j.cluster, j.look, path, {j.files.lods, j.leaf, j.files.instances});
     }},
    {&Formats::obj, ".obj", [](const WriteJob& j, const std::string& path) { write_obj(j.cluster, j.look, path); }},
    {&Formats::tips, "_tips.ply",
     [](const WriteJob& j, const std::string& path) {
       write_instances_ply(j.cluster, j.look.attributes, j.files.instances, path, j.files.ply_encoding);
     }},
    {&Formats::svg, ".svg", [](const WriteJob& j, const std::string& path) { write_svg(j.cluster, j.look, path); }},
    {&Formats::png, ".png", [](const WriteJob& j, const std::string& path) { write_png(j.cluster, path, j.files.png); }},
    {&Formats::html, ".html",
     [](const WriteJob& j, const std::string& path) {
       HtmlOptions html;
       html.up = j.pov.up;
       const std::string& output = j.files.output;
       const std::size_t slash = output.find_last_of('/');
       html.title = "dla3d: " + (slash == std::string::npos ? output : output.substr(slash + 1));
       write_html(j.cluster, j.look, path, html, j.scene_mesh);
     }},
    // The scene writes PREFIX.pov, .inc and _growth.inc (and _mesh.inc, _tips.inc) itself.
    {&Formats::pov, "",
     [](const WriteJob& j, const std::string& prefix) { write_pov(j.cluster, prefix, j.pov, j.scene_mesh, &j.look); }},
};

//! One writer of the solid's files, by the flag that asks for it and the suffix of its file.
struct SolidWriterEntry {
  bool Formats::*wanted;
  const char* suffix;
  void (*write)(const Solid& solid, const WriteJob& job, const std::string& path);
};

const SolidWriterEntry kSolidWriters[] = {
    {&Formats::stl, ".stl", [](const Solid& s, const WriteJob&, const std::string& path) { write_stl(s, path); }},
    {&Formats::threemf, ".3mf", [](const Solid& s, const WriteJob&, const std::string& path) { write_3mf(s, path); }},
    {&Formats::vdb, ".vdb",
     [](const Solid& s, const WriteJob& j, const std::string& path) { write_vdb(s, j.cluster, j.look, path); }},
    {&Formats::solid_glb, "_solid.glb",
     [](const Solid& s, const WriteJob& j, const std::string& path) { write_solid_glb(s, j.cluster, j.look, path); }},
    {&Formats::solid_obj, "_solid.obj",
     [](const Solid& s, const WriteJob& j, const std::string& path) { write_solid_obj(s, j.cluster, j.look, path); }},
};

//! Builds the planned solid once, on every core, and writes each of its files on a thread of
//! its own.
SolidMeasures write_solid(const SolidPlan& plan, const WriteJob& job, const WriteContext& context) {
  const Solid solid = build_solid(plan, context.stop, context.solid_progress);
  std::vector<std::future<void>> writers;
  for (const SolidWriterEntry& writer : kSolidWriters) {
    if (!(job.files.formats.*(writer.wanted))) continue;
    const std::string path = job.files.output + writer.suffix;
    writers.push_back(std::async(std::launch::async, [&solid, &job, &writer, &context, path] {
      const detail::StopScope watched(context.stop);
      writer.write(solid, job, path);
    }));
  }
  detail::finish_all(writers);
  return solid.measures;
}

}  // namespace

FilesWritten write_files(const Cluster& cluster, const OutputOptions& files, const WriteContext& context) {
  const detail::StopScope watched(context.stop);  // the look's measures and the scene, on this thread
  PovOptions pov = files.pov;
  pov.comment = context.comment;
  pov.tips = files.formats.tips;    // the scene reads its tips from PREFIX_tips.inc
  pov.instances = files.instances;  // at the same points as PREFIX_tips.ply
  // What growth freed (the index) goes back to the system before the writers take theirs.
  malloc_trim(0);
  // The writers' threads free buffers of a few hundred kB: mapped, not kept in each thread's
  // heap, where glibc's adaptive threshold would leave them (about 1 byte a particle at 10^7).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  // The distance to the mesh feeds the boundary model and the scene's switch to it; measured
  // on every core, as the files do not depend on how many. The tips' gaps only for the files
  // with instancing points (PREFIX_tips.ply and .inc, the leaves), where they pick every tip.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const Look look = make_look(cluster, files.look,
                              {context.constraint ? &context.constraint->surface() : nullptr, nullptr,
                               std::max(context.threads, cores),
                               (files.formats.tips || !files.leaf.empty()) && picks_every_tip(files.instances),
                               files.instances.exclude_paint ? &*files.instances.exclude_paint : nullptr,
                               context.constraint ? &context.constraint->mesh() : nullptr, context.measured});
  // The solid's plan first: a solid that would not fit is refused before any file is written.
  const SolidPlan plan = files.formats.solid() ? plan_solid(cluster, look.radii, files.solid) : SolidPlan{};
  if (files.formats.ddscat)  // and DDSCAT's dipoles
    refuse_dipoles(dipole_lattice(cluster, look, files.ddscat_resolution), files.ddscat_resolution,
                   files.output + "_ddscat.dat");
  FilesWritten written;
  std::optional<Leaf> leaf_read_here;
  const Leaf* leaf = context.leaf;
  if (!leaf && !files.leaf.empty() && files.formats.glb) leaf = &leaf_read_here.emplace(read_leaf(files.leaf));
  const WriteJob job{cluster, look, files, pov, context.scene_mesh, leaf, written.glb};
  std::vector<std::future<void>> writers;
  const WriterEntry* scene = nullptr;
  for (const WriterEntry& writer : kWriters) {
    if (!(files.formats.*(writer.wanted))) continue;
    if (writer.wanted == &Formats::pov) {
      scene = &writer;  // on this thread, as the others write
      continue;
    }
    const std::string path = files.output + writer.suffix;
    writers.push_back(std::async(std::launch::async, [&job, &writer, &context, path] {
      const detail::StopScope watched(context.stop);
      writer.write(job, path);
    }));
  }
  if (files.formats.solid())
    writers.push_back(std::async(std::launch::async, [&] { written.solid = write_solid(plan, job, context); }));
  std::exception_ptr scene_failure;
  try {
    if (scene) scene->write(job, files.output);
  } catch (...) {
    scene_failure = std::current_exception();
  }
  detail::finish_all(writers, scene_failure);
  return written;
}

void write_run(const Run& run, const Cluster& cluster, const OutputOptions& files, RunRecord& record,
               const StopFlag* stop, const StageProgress& solid_progress) {
  const auto start = std::chrono::steady_clock::now();
  record.printed = files.solid.print_size > 0.0;
  // The record is written even when a file fails (Ctrl-C while the solid builds), but not for
  // a solid refused before any file was written.
  std::exception_ptr failure;
  try {
    FilesWritten written = write_files(
        cluster, files,
        {run.threads, run.constraint, run.scene_mesh, record.command, stop, solid_progress, run.measured_while_growing.get(),
         run.leaf.get()});
    record.solid = written.solid;
    record.lod_triangles = std::move(written.glb.lod_triangles);
    if (!files.leaf.empty() && files.formats.glb) record.leaves = written.glb.leaves;
  } catch (const InvalidInput&) {
    throw;
  } catch (const Interrupted&) {
    record.stopped_in = "files";
    failure = std::current_exception();
  } catch (...) {
    failure = std::current_exception();
  }
  record.write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (files.formats.json) write_run_report(cluster, run.record(), files.look, files.pov, record, files.output + ".json");
  if (failure) std::rethrow_exception(failure);
}

}  // namespace dla
