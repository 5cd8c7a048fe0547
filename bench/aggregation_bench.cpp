// Random-drop ballistic aggregation (include/dla/models/drop.h) and ballistic aggregation
// (ballistic.h): particles a second on one core, and the drops a particle took.
// Arguments: particles, dimensions, and for drop the zone radius in spacings (0: growing).
// Run:
//   build/bench/dla_aggregation_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/models/ballistic.h"
#include "dla/models/drop.h"

#include <benchmark/benchmark.h>

namespace {

void drop(benchmark::State& state) {
  dla::DropOptions o;
  o.particles = static_cast<std::size_t>(state.range(0));
  o.dimensions = static_cast<int>(state.range(1));
  o.zone_radius = static_cast<double>(state.range(2));
  dla::DropStats stats;
  for (auto _ : state) {
    stats = {};
    benchmark::DoNotOptimize(dla::drop(o, nullptr, {}, nullptr, &stats).particles.data());
  }
  state.counters["particles_per_s"] =
      benchmark::Counter(static_cast<double>(o.particles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["drops_per_particle"] = static_cast<double>(stats.drops) / static_cast<double>(o.particles);
}

void ballistic(benchmark::State& state) {
  dla::BallisticOptions o;
  o.particles = static_cast<std::size_t>(state.range(0));
  o.dimensions = static_cast<int>(state.range(1));
  dla::BallisticStats stats;
  for (auto _ : state) {
    stats = {};
    benchmark::DoNotOptimize(dla::ballistic(o, {}, nullptr, &stats).particles.data());
  }
  state.counters["particles_per_s"] =
      benchmark::Counter(static_cast<double>(o.particles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["lines_per_particle"] = static_cast<double>(stats.launched) / static_cast<double>(o.particles);
  state.counters["steps_per_line"] =
      static_cast<double>(stats.far_steps + stats.near_steps) / static_cast<double>(stats.launched);
}

}  // namespace

BENCHMARK(drop)->Args({1000000, 3, 0})->Args({1000000, 2, 0})->Args({100000, 2, 400})->Unit(benchmark::kMillisecond);
BENCHMARK(ballistic)->Args({1000000, 3})->Args({1000000, 2})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
