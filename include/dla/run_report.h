#pragma once
//! \file run_report.h
//! The JSON sidecar of a run: version, effective options and RNG seed (enough to grow the same
//! structure again), counts, walk statistics, measures and timings.

#include "dla/cluster.h"
#include "dla/options.h"
#include "dla/pov_writer.h"

#include <string>

namespace dla {

struct RunTimings {
  double grow_seconds = 0.0;
  double write_seconds = 0.0;
};

//! Throws IOError if the file cannot be written. Everything but `timings` is the same for the
//! same options and seed.
void write_run_report(const Cluster& cluster, const GrowthOptions& options,
                      const PovOptions& pov, const RunTimings& timings, const std::string& path);

}  // namespace dla
