#pragma once
// A growth run set up from its command line, ready to grow: its meshes read, the defaults they
// give taken, its seeds, roots or attractors placed, every option checked. dla3d's subcommands
// grow it and write its files; the Python module (python/) grows the same run and hands the
// structure to Python, so that a run from either grows the same structure for the same seed.

#include "command_line.h"

#include "dla/core/cluster.h"
#include "dla/io/checkpoint.h"
#include "dla/io/run_report.h"
#include "dla/mesh/constraint.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace dla::cli {

//! Reads the mesh a path names, with the hash of its file when `hash` is not null: read_mesh(),
//! or meshes handed over in memory under a name (the Python module's arrays).
using MeshReader = std::function<TriangleMesh(const std::string& path, std::uint64_t* hash)>;

class ModelRun {
 public:
  virtual ~ModelRun() = default;

  //! Grows the structure (once: a run's seeds and stats are its own). Throws PartialGrowth as
  //! the models do.
  virtual Cluster grow(const ProgressFn& progress, const StopFlag* stop) = 0;
  //! The first line of the summary dla3d prints, for the structure grown.
  virtual std::string summary(const Cluster& cluster, const RunRecord& record) const = 0;
  //! How much of `total` a structure growing has: its particles (DLA: without the seeds).
  virtual std::size_t done(const Cluster& so_far) const { return so_far.particles.size(); }
  //! Writes the JSON record of the run to `path`.
  virtual void write_report(const Cluster& cluster, const LookOptions& look, const PovOptions& pov,
                            const RunRecord& record, const std::string& path) const = 0;

  //! The command's files, with the up axis the mesh gives when none was asked for.
  FileOptions files;
  std::size_t total = 0;          //!< particles at most, for the progress bar
  const char* unit = "particles"; //!< what they are called in the stop line
  int threads = 1;                //!< for the look's measurements and the writers
  //! "NAME: 1,234 triangles; REPAIRS; spacing S", for a run with a constraint mesh, else empty.
  std::string mesh_line;
  //! The mesh the look measures distances to (the boundary radius model), or null.
  const MeshConstraint* constraint = nullptr;
  //! The mesh the POV-Ray scene and the web viewer show, or null.
  const TriangleMesh* scene_mesh = nullptr;
  //! DLA growing to fill a mesh: the fraction of its volume asked for (the progress bar shows
  //! it), else 0.
  double fill = 0.0;
  //! DLA: the hash of the mesh's file (or text), which a checkpoint keeps to know it again.
  std::uint64_t input_hash = 0;
};

//! Sets up the run of a growth command (`line.kind` is grow, colonize, eden, drop or
//! ballistic); `resumed` is the checkpoint a DLA run goes on from. Throws InvalidInput, with
//! one line, for options that cannot work with the meshes or this machine.
std::unique_ptr<ModelRun> prepare_run(const CommandLine& line, const Checkpoint* resumed = nullptr,
                                      const MeshReader& read = {});

//! Writes the files `files` asks for (the JSON record too) of what `run` grew, and records the
//! time taken in `record`.
void write_run(const ModelRun& run, const Cluster& cluster, const FileOptions& files, RunRecord& record);

}  // namespace dla::cli
