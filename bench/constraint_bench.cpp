// Growth in the scanned bust (Debian's libcgal-demo; the README's bust.stl) against the same
// N unconstrained, with the same two seeds and spacing, and the unit costs of the two mesh
// calls the walk makes: the Embree branch test (once per contact) and the grid look-up for
// lost walkers (once per step); and growth over the bust in a shell (--side outside --shell 3),
// with the shell's set-up. Run:
//   build/bench/dla_constraint_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// The share of time in each call is its count per particle (a counter here) times its unit
// cost, over the time per particle (docs/performance.md).

#include "dla/mesh/constraint.h"
#include "dla/index/grid_index.h"
#include "dla/models/dla.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <memory>

namespace {

constexpr double kSpacing = 0.2;  // half dla3d's default for the bust (its longest side / 100)

const dla::MeshConstraint* bust() {
  static const std::unique_ptr<dla::MeshConstraint> constraint = [] {
    if (!std::filesystem::exists(BUST_OFF_PATH)) return std::unique_ptr<dla::MeshConstraint>();
    return std::make_unique<dla::MeshConstraint>(dla::read_mesh(BUST_OFF_PATH), dla::ConstraintOptions{}, kSpacing);
  }();
  return constraint.get();
}

dla::DlaOptions bust_options(std::size_t particles) {
  dla::DlaOptions o;
  o.particles = particles;
  o.spacing = kSpacing;
  o.spawn = dla::SpawnMode::inside;
  o.seeds = bust()->place_seeds(2, o.rng_seed);
  return o;
}

void grow(benchmark::State& state, bool constrained) {
  if (!bust()) return state.SkipWithError("the bust is missing: install libcgal-demo and run cmake again");
  dla::DlaOptions o = bust_options(static_cast<std::size_t>(state.range(0)));
  if (!constrained) o.spawn = dla::SpawnMode::sphere;
  o.rng_seed = 2;  // the same walks in every repetition (as growth_bench.cpp)
  dla::DlaStats grown;
  for (auto _ : state) {
    dla::grow_with<dla::GridIndex>(o, {}, constrained ? bust() : nullptr, nullptr, nullptr, &grown);
  }
  const dla::WalkStats& stats = grown.walk;
  const double n = static_cast<double>(o.particles);
  state.counters["particles_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["steps_per_particle"] = static_cast<double>(stats.steps) / n;
  state.counters["branch_tests_per_particle"] =
      static_cast<double>(o.particles + stats.rejected) / n;  // every accepted or refused branch
}

void grow_in_bust(benchmark::State& state) { grow(state, true); }
void grow_unconstrained(benchmark::State& state) { grow(state, false); }

// The branches of a grown structure, tested again: the mix of an actual run, where nearly every
// tested branch is accepted.
void branch_test(benchmark::State& state) {
  if (!bust()) return state.SkipWithError("the bust is missing");
  const dla::Cluster cluster = dla::grow(bust_options(20'000), *bust());
  std::size_t i = 1, hits = 0;
  for (auto _ : state) {
    const dla::Particle& p = cluster.particles[cluster.seed_count + i % (cluster.particles.size() - cluster.seed_count)];
    const dla::BranchCheck check = bust()->check_branch(cluster.particles[static_cast<std::size_t>(p.parent)].position, p.position);
    hits += !check.accepted;
    ++i;
  }
  benchmark::DoNotOptimize(hits);
}

void lost_lookup(benchmark::State& state) {
  if (!bust()) return state.SkipWithError("the bust is missing");
  dla::Rng rng(3);
  const dla::Box& box = bust()->box();
  std::vector<dla::Vec3> points(1 << 16);
  for (dla::Vec3& p : points)
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] + (box.max[a] - box.min[a]) * rng.uniform();
  std::size_t i = 0, lost = 0;
  for (auto _ : state) lost += bust()->lost(points[i++ & (points.size() - 1)]);
  benchmark::DoNotOptimize(lost);
}

// Frost: a shell of three spacings outside the bust, walkers started anywhere in it.
void grow_in_shell(benchmark::State& state) {
  if (!bust()) return state.SkipWithError("the bust is missing");
  dla::ConstraintOptions frost;
  frost.side = dla::Side::outside;
  frost.shell = 3.0;
  const auto start = std::chrono::steady_clock::now();
  const dla::MeshConstraint shell(dla::read_mesh(BUST_OFF_PATH), frost, kSpacing);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  dla::DlaOptions o;
  o.particles = static_cast<std::size_t>(state.range(0));
  o.spacing = kSpacing;
  o.spawn = dla::SpawnMode::inside;
  o.seeds = shell.place_seeds(2, o.rng_seed);
  o.rng_seed = 2;
  dla::DlaStats grown;
  for (auto _ : state) {
    dla::grow_with<dla::GridIndex>(o, {}, &shell, nullptr, nullptr, &grown);
  }
  const dla::WalkStats& stats = grown.walk;
  const double n = static_cast<double>(o.particles);
  state.counters["particles_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["steps_per_particle"] = static_cast<double>(stats.steps) / n;
  state.counters["refused_per_particle"] = static_cast<double>(stats.lost) / n;
  state.counters["setup_s"] = setup;
}

}  // namespace

BENCHMARK(grow_in_bust)->Name("bust/constrained")->Arg(100'000)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(grow_unconstrained)->Name("bust/unconstrained")->Arg(100'000)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(branch_test)->Name("bust/branch_test");
BENCHMARK(lost_lookup)->Name("bust/lost_lookup");
BENCHMARK(grow_in_shell)->Name("bust/shell")->Arg(30'000)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
