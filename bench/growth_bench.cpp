// Unconstrained 3D growth (spacing = contact distance = 1, stickiness 1) for 10^4, 10^5 and
// 10^6 particles with each index, on one thread and (grid) on two: particles per second and
// peak bytes per particle (peak heap in use during growth). Run:
//   build/bench/dla_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/core/huge_pages.h"
#include "dla/index/grid_index.h"
#include "dla/models/dla.h"
#include "dla/index/kdtree_index.h"
#include "dla/index/spatial_index.h"

#include <benchmark/benchmark.h>

#include <malloc.h>

#include <algorithm>

namespace {

// Bytes the heap has handed out and not taken back (glibc), mmapped blocks included, and the
// index's arrays in huge pages, which have mappings of their own.
double heap_in_use() {
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd + dla::huge_page_bytes());
}

template <class Index>
void grow_cluster(benchmark::State& state) {
  dla::DlaOptions options;
  options.particles = static_cast<std::size_t>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  // Every repetition grows the same cluster (Google Benchmark calls this function afresh for
  // each), so alternating runs of two builds compare the same walks. Seeds differ by ±10% in
  // steps a particle: for that spread, run the CLI with several --rng-seed values.
  options.rng_seed = 2;
  double peak_bytes = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    const double before = heap_in_use();
    double peak = before;
    state.ResumeTiming();
    // The progress call every 256 particles samples the heap: the cost is a few microseconds
    // per 256 particles, and the peak is exact to within 256 particles' growth.
    const dla::Cluster cluster = dla::grow_with<Index>(options, [&](const dla::Cluster&) {
      peak = std::max(peak, heap_in_use());
      return true;
    });
    benchmark::DoNotOptimize(cluster.particles.data());
    peak_bytes = peak - before;
  }
  const double n = static_cast<double>(options.particles);
  state.counters["particles_per_s"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_particle"] = peak_bytes / n;
}

}  // namespace

BENCHMARK(grow_cluster<dla::GridIndex>)
    ->Name("grow/grid")->ArgNames({"n", "threads"})->ArgsProduct({{10'000, 100'000, 1'000'000}, {1, 2}})
    ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(grow_cluster<dla::KdTreeIndex>)
    ->Name("grow/kdtree")->ArgNames({"n", "threads"})->Args({10'000, 1})->Args({100'000, 1})
    ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(grow_cluster<dla::BruteForceIndex>)
    ->Name("grow/brute")->ArgNames({"n", "threads"})->Args({10'000, 1})
    ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
