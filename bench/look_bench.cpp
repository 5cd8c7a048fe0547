// The look of a grown structure of 10^6 particles (3D DLA, grown once on two threads, not
// timed): the attributes, the radii, the tube mesh for 6, 8 and 12 sides, and the .glb and
// .obj written into /tmp (the page cache); and three levels of detail of 10^5 particles.
// Counters give triangles and .glb bytes a particle;
// tube_mesh's arguments are particles, sides, the tolerance in tenths of a spacing and the
// smallest branch kept.
// Run:
//   build/bench/dla_look_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla_tree.h"
#include "dla/look/look.h"
#include "dla/io/mesh_writers.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>

namespace {

void attributes(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(dla::compute_attributes(tree));
  state.counters["particles_per_s"] = benchmark::Counter(static_cast<double>(tree.particles.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate);
}

void look(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  dla::LookOptions options;
  options.radius.model = dla::RadiusModel::pipe;
  for (auto _ : state) {
    const dla::Look look = dla::make_look(tree, options);
    benchmark::DoNotOptimize(look.radii);  // the radii are computed when asked
  }
}

//! Attributes, radii and every tube's geometry: what the tube writers compute.
void tube_mesh(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  dla::LookOptions options;
  options.tubes.sides = static_cast<int>(state.range(1));
  options.tubes.tolerance = static_cast<double>(state.range(2)) / 10.0;  // tenths of a spacing
  options.tubes.min_branch = static_cast<int>(state.range(3));
  std::size_t vertices = 0, triangles = 0;
  for (auto _ : state) {
    const dla::Look look = dla::make_look(tree, options);
    vertices = triangles = 0;
    dla::for_each_tube(tree, look.attributes, look.radii, options.tubes, [&](const dla::TubePiece& piece) {
      vertices += piece.positions.size();
      triangles += piece.triangles.size();
    });
  }
  const double n = static_cast<double>(tree.particles.size());
  state.counters["triangles_per_particle"] = static_cast<double>(triangles) / n;
  // .glb without colour: 72 bytes a vertex (with its tangent and texture coordinates), 12 a triangle.
  state.counters["glb_bytes_per_particle"] =
      (72.0 * static_cast<double>(vertices) + 12.0 * static_cast<double>(triangles)) / n;
}

void glb(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  const dla::Look look = dla::make_look(tree, {});
  for (auto _ : state) dla::write_glb(tree, look, "/tmp/dla_look_bench.glb");
  std::remove("/tmp/dla_look_bench.glb");
}

//! A tree's glb and `levels` levels of detail beside it (--lod): twigs dropped, tubes
//! simplified. The levels' own time is this less `glb`'s.
void glb_lods(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  const dla::Look look = dla::make_look(tree, {});
  std::size_t last = 0;
  const int levels = static_cast<int>(state.range(1));
  const dla::GlbOptions options{levels, nullptr, {}};
  for (auto _ : state) last = dla::write_glb(tree, look, "/tmp/dla_look_bench.glb", options).lod_triangles.back();
  std::remove("/tmp/dla_look_bench.glb");
  for (int level = 1; level <= levels; ++level)
    std::remove(("/tmp/dla_look_bench_lod" + std::to_string(level) + ".glb").c_str());
  state.counters["last_level_triangles"] = static_cast<double>(last);
}

void obj(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  const dla::Look look = dla::make_look(tree, {});
  for (auto _ : state) dla::write_obj(tree, look, "/tmp/dla_look_bench.obj");
  std::remove("/tmp/dla_look_bench.obj");
}

}  // namespace

BENCHMARK(attributes)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(look)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(tube_mesh)
    ->Args({1'000'000, 6, 0, 1})
    ->Args({1'000'000, 8, 0, 1})
    ->Args({1'000'000, 12, 0, 1})
    ->Args({1'000'000, 8, 3, 1})
    ->Args({1'000'000, 6, 10, 4})
    ->Args({1'000'000, 4, 10, 16})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(glb)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(glb_lods)->Args({100'000, 3})->Unit(benchmark::kMillisecond);
BENCHMARK(obj)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
