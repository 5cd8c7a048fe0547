#pragma once
//! \file run_report.h
//! The JSON sidecar of a run: version, effective options and RNG seed (enough to grow the same
//! structure again), counts, walk statistics, measures and timings.

#include "dla/core/cluster.h"
#include "dla/models/ballistic.h"
#include "dla/models/colonization.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/mesh/constraint.h"
#include "dla/look/look.h"
#include "dla/core/options.h"
#include "dla/io/pov_writer.h"

#include <string>

namespace dla {

//! What the sidecar records of the run itself, beyond the structure and the options.
struct RunRecord {
  double grow_seconds = 0.0;
  double write_seconds = 0.0;
  std::string command;     //!< the command line that made the run, if any
  std::string stopped_by;  //!< why growth ended before the count (a signal, an error), if it did
};

//! Throws IOError if the file cannot be written. Everything but the timings is the same for the
//! same options and seed. With a `constraint`, records it and the file it came from.
void write_run_report(const Cluster& cluster, const DlaOptions& options, const LookOptions& look,
                      const PovOptions& pov, const RunRecord& record, const std::string& path,
                      const MeshConstraint* constraint = nullptr, const std::string& mesh_file = "");

//! The files a space colonization run read, for its record.
struct ColonizationInputs {
  std::string attractors_file;  //!< the attractors' file; empty: they were scattered
  std::size_t attractor_count = 0;  //!< how many grew the tree
  std::string vessel_file;      //!< the vessel's mesh; empty: none
  std::string collide_file;     //!< the collision mesh; empty: none
  CollisionMode collision = CollisionMode::push;
};

//! The sidecar of a space colonization run (colonization.h): "model": "colonization", its
//! options and attractors, the roots, and the vessel's and collision mesh's files if any; no
//! walk statistics. Throws IOError.
void write_colonization_report(const Cluster& cluster, const ColonizationOptions& options,
                               const AttractorOptions& attractors, const LookOptions& look, const PovOptions& pov,
                               const RunRecord& record, const std::string& path, const ColonizationInputs& inputs);

//! The sidecar of an Eden run (eden.h): "model": "eden", its options (the mask as its sites,
//! and the file it came from if any); no walk statistics. Throws IOError.
void write_eden_report(const Cluster& cluster, const EdenOptions& options, const std::string& mask_file,
                       const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                       const std::string& path);

//! The sidecar of a random-drop run (drop.h): "model": "drop", its options, the constraint
//! mesh's file and settings if any, and what became of the drops. Throws IOError.
void write_drop_report(const Cluster& cluster, const DropOptions& options, const DropStats& stats,
                       const MeshConstraint* constraint, const std::string& mesh_file, const LookOptions& look,
                       const PovOptions& pov, const RunRecord& record, const std::string& path);

//! The sidecar of a ballistic run (ballistic.h): "model": "ballistic", its options and the
//! lines' counts. Throws IOError.
void write_ballistic_report(const Cluster& cluster, const BallisticOptions& options, const BallisticStats& stats,
                            const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                            const std::string& path);

}  // namespace dla
