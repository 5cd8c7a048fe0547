// Loops (docs/loops.md): what --links adds to DLA's growth at 10^6 particles, against the
// growth itself in the same sitting, and closed venation against open at 10^5 attractors on
// the same attractors and influence.
// Run:
//   build/bench/dla_links_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/models/colonization.h"
#include "dla/models/links.h"
#include "dla_tree.h"

#include <benchmark/benchmark.h>

namespace {

// DLA's growth on one thread: the baseline the links are a share of. Argument: particles.
void grow(benchmark::State& state) {
  dla::DlaOptions o;
  o.particles = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(dla::grow(o).particles.size());
}

// The links of a grown tree. Arguments: particles, D in tenths of a spacing, K, threads.
void links(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  dla::LinkOptions o;
  o.distance = static_cast<double>(state.range(1)) / 10.0;
  o.most = static_cast<std::size_t>(state.range(2));
  std::size_t made = 0;
  for (auto _ : state) made = dla::neighbour_links(tree, o, static_cast<int>(state.range(3))).size();
  state.counters["links"] = static_cast<double>(made);
}

// Space colonization among attractors in a sphere of radius 50, one root at its bottom.
// Arguments: attractors, closed (1) or open (0), the influence in spacings (0: unbounded).
void venation(benchmark::State& state) {
  dla::AttractorOptions a;
  a.count = static_cast<std::size_t>(state.range(0));
  a.radius = 50;
  const std::vector<dla::Vec3> attractors = dla::scatter_attractors(a, 1, 3);
  dla::ColonizationOptions o;
  if (state.range(2) > 0) o.influence = static_cast<double>(state.range(2));
  o.max_nodes = 1'000'000;
  o.venation = state.range(1) ? dla::Venation::closed : dla::Venation::open;
  std::size_t nodes = 0, links = 0;
  for (auto _ : state) {
    const dla::Cluster tree = dla::colonize(o, attractors, {dla::Vec3(0, 0, -50)});
    nodes = tree.particles.size();
    links = tree.links.size();
  }
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["links"] = static_cast<double>(links);
}

}  // namespace

BENCHMARK(grow)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(links)->Args({1'000'000, 20, 1, 1})->Args({1'000'000, 30, 3, 1})->Args({1'000'000, 30, 3, 2})
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(venation)->Args({100'000, 0, 0})->Args({100'000, 0, 10})->Args({100'000, 1, 10})->Args({100'000, 0, 5})
    ->Args({100'000, 1, 5})->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
