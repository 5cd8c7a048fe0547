// The Eden model (include/dla/models/eden.h): sites a second on each lattice, one core, and
// under a wide mask. Arguments: sites, the lattice (its index in dla::Lattice).
// Run:
//   build/bench/dla_eden_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/models/eden.h"

#include <benchmark/benchmark.h>

namespace {

void eden(benchmark::State& state) {
  dla::EdenOptions o;
  o.sites = static_cast<std::size_t>(state.range(0));
  o.lattice = static_cast<dla::Lattice>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(dla::eden(o).particles.data());
  state.SetLabel(std::string(dla::to_string(o.lattice)));
  state.counters["sites_per_s"] =
      benchmark::Counter(static_cast<double>(o.sites), benchmark::Counter::kIsIterationInvariantRate);
}

// Drops under mask D (24 sites), 6 of them occupied to stick, from a disk of radius 3.
void eden_drop(benchmark::State& state) {
  dla::EdenOptions o;
  o.sites = static_cast<std::size_t>(state.range(0));
  o.mode = dla::EdenMode::drop;
  o.mask = dla::EdenMask::D;
  o.mask_threshold = 6;
  o.seed_radius = 3;
  for (auto _ : state) benchmark::DoNotOptimize(dla::eden(o).particles.data());
  state.counters["sites_per_s"] =
      benchmark::Counter(static_cast<double>(o.sites), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(eden_drop)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(eden)
    ->Args({10000000, static_cast<long>(dla::Lattice::square4)})
    ->Args({10000000, static_cast<long>(dla::Lattice::square8)})
    ->Args({10000000, static_cast<long>(dla::Lattice::hex)})
    ->Args({1000000, static_cast<long>(dla::Lattice::cubic6)})
    ->Args({1000000, static_cast<long>(dla::Lattice::cubic26)})
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
