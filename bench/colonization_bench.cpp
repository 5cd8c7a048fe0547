// Space colonization (include/dla/models/colonization.h): the kept closest nodes against a full
// rescan of every attractor at every iteration (tests/colonization_rescan.h), side by side on
// the same attractors, and the kept version at 10^6 attractors. Attractors fill a sphere of
// radius R (scattered once, not timed), one root at its bottom. Arguments: attractors, R,
// nodes at most, the influence in spacings (0: unbounded, every attractor pulls).
// Run:
//   build/bench/dla_colonization_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/models/colonization.h"
#include "colonization_rescan.h"

#include <benchmark/benchmark.h>

#include <limits>

namespace {

struct Setup {
  dla::ColonizationOptions options;
  std::vector<dla::Vec3> attractors;
  std::vector<dla::Vec3> roots;
};

Setup setup(const benchmark::State& state) {
  Setup s;
  dla::AttractorOptions a;
  a.count = static_cast<std::size_t>(state.range(0));
  a.radius = static_cast<double>(state.range(1));
  s.attractors = dla::scatter_attractors(a, 1, 3);
  s.roots = {dla::Vec3(0, 0, -a.radius)};
  s.options.max_nodes = static_cast<std::size_t>(state.range(2));
  if (state.range(3) > 0) s.options.influence = static_cast<double>(state.range(3));
  return s;
}

template <bool kRescan>
void colonize(benchmark::State& state) {
  const Setup s = setup(state);
  std::size_t nodes = 0;
  for (auto _ : state) {
    const dla::Cluster tree = kRescan ? dla::testing::colonize_by_rescan(s.options, s.attractors, s.roots)
                                      : dla::colonize(s.options, s.attractors, s.roots);
    nodes = tree.particles.size();
  }
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["nodes_per_s"] = benchmark::Counter(static_cast<double>(nodes), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(colonize<false>)->Name("kept")->Args({100000, 50, 5000, 10})->Args({100000, 50, 5000, 0})
    ->Args({1000000, 100, 100001, 10})->Args({1000000, 100, 100001, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(colonize<true>)->Name("rescan")->Args({100000, 50, 5000, 10})->Args({100000, 50, 5000, 0})
    ->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
