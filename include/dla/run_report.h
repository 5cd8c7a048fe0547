#pragma once
//! \file run_report.h
//! The JSON sidecar of a run: version, effective options and RNG seed (enough to grow the same
//! structure again), counts, walk statistics, measures and timings.

#include "dla/cluster.h"
#include "dla/constraint.h"
#include "dla/options.h"
#include "dla/pov_writer.h"

#include <string>

namespace dla {

struct RunTimings {
  double grow_seconds = 0.0;
  double write_seconds = 0.0;
};

//! Throws IOError if the file cannot be written. Everything but `timings` is the same for the
//! same options and seed. With a `constraint`, records it and the file it came from.
void write_run_report(const Cluster& cluster, const GrowthOptions& options,
                      const PovOptions& pov, const RunTimings& timings, const std::string& path,
                      const MeshConstraint* constraint = nullptr, const std::string& mesh_file = "");

}  // namespace dla
