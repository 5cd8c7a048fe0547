// The breakdown model (breakdown.h) against DLA at the same count, one thread: a 3D discharge
// from a point towards the ground plane at eta 0, 2 and 3 (the plane far enough below that
// every run grows its whole count without striking it), by the walkers field, the charges
// field and the conductor field (10^4 and 10^5 particles), and DLA itself (eta 1 with no
// target and one walker a particle: dla3d's structure, byte for byte). Counters: particles a
// second, and walkers or sites weighed a particle. Run:
//   build/bench/dla_breakdown_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians and the ratio to DLA in docs/performance.md).

#include "dla/models/breakdown.h"

#include <benchmark/benchmark.h>

#include <algorithm>

namespace {

void grow_discharge(benchmark::State& state) {
  dla::DlaOptions walk;
  walk.particles = static_cast<std::size_t>(state.range(0));
  walk.rng_seed = 1;
  dla::BreakdownOptions options;
  options.eta = static_cast<double>(state.range(1)) / 10.0;
  options.target.kind = state.range(1) == 10 ? dla::TargetKind::none : dla::TargetKind::plane;
  options.target.axis = dla::Axis::y;
  options.target.at = -400.0 * std::max<double>(1.0, static_cast<double>(walk.particles) / 10000.0);
  constexpr dla::BreakdownField fields[] = {dla::BreakdownField::walkers, dla::BreakdownField::charges,
                                            dla::BreakdownField::conductor};
  options.field = fields[state.range(2)];
  dla::BreakdownStats stats;
  for (auto _ : state) {
    stats = {};
    const dla::Cluster cluster = dla::breakdown(walk, options, nullptr, {}, nullptr, &stats);
    benchmark::DoNotOptimize(cluster.particles.data());
  }
  const double n = static_cast<double>(walk.particles);
  state.counters["particles_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["walkers_per_particle"] = static_cast<double>(stats.walk.walkers) / n;
  state.counters["sites_per_particle"] = static_cast<double>(stats.sites) / n;
}

}  // namespace

// eta in tenths: 10 is DLA, the baseline; field 0: walkers, 1: charges, 2: conductor.
BENCHMARK(grow_discharge)
    ->ArgNames({"particles", "eta_tenths", "field"})
    ->Args({10000, 10, 0})
    ->Args({10000, 0, 0})
    ->Args({10000, 20, 0})
    ->Args({10000, 30, 0})
    ->Args({10000, 0, 1})
    ->Args({10000, 20, 1})
    ->Args({10000, 30, 1})
    ->Args({100000, 20, 1})
    ->Args({10000, 0, 2})
    ->Args({10000, 20, 2})
    ->Args({10000, 30, 2})
    ->Args({100000, 20, 2})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

BENCHMARK_MAIN();
