// Aggregates of clusters (include/dla/models/aggregate.h) on one core: the marks are
// DLCA of 10^4 monomers at a volume fraction of 0.01 in at most 10 s, and a tuned aggregate of
// 10^3 in at most 0.2 s. Arguments: monomers, and for the box's modes the volume fraction in
// thousandths (0: no box, as rlca's reaction-limited limit and tuned have none). Run:
//   build/bench/dla_aggregate_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md and docs/aggregate.md).

#include "dla/models/aggregate.h"

#include <benchmark/benchmark.h>

namespace {

void aggregate(benchmark::State& state, dla::AggregateMode mode) {
  dla::AggregateOptions o;
  o.mode = mode;
  o.monomers = static_cast<std::size_t>(state.range(0));
  if (state.range(1) > 0) o.volume_fraction = static_cast<double>(state.range(1)) / 1000.0;
  dla::AggregateStats stats;
  for (auto _ : state) {
    stats = {};
    benchmark::DoNotOptimize(dla::aggregate(o, {}, nullptr, &stats).particles.data());
  }
  state.counters["monomers_per_s"] =
      benchmark::Counter(static_cast<double>(o.monomers), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["moves"] = static_cast<double>(stats.moves);
  const dla::FractalLaw fit = dla::fit_joins(stats);
  state.counters["df"] = fit.dimension;
  state.counters["kf"] = fit.prefactor;
}

void dlca(benchmark::State& state) { aggregate(state, dla::AggregateMode::dlca); }
void rlca(benchmark::State& state) { aggregate(state, dla::AggregateMode::rlca); }
void ballistic(benchmark::State& state) { aggregate(state, dla::AggregateMode::ballistic); }
void tuned(benchmark::State& state) { aggregate(state, dla::AggregateMode::tuned); }

}  // namespace

BENCHMARK(dlca)->Args({10000, 10})->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(rlca)->Args({10000, 0})->Args({100000, 0})->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(ballistic)->Args({10000, 10})->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(tuned)->Args({1000, 0})->Args({10000, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
