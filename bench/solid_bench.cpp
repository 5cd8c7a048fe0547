// The solid of a grown 3D DLA tree (grown once on two threads, not timed), with the pipe
// radius: built and written as binary STL into /tmp (the page cache), as `dla3d --formats stl`
// does. Arguments: particles, the voxel in thousandths of a spacing (0: the default, a third of
// the thinnest branch) and the adaptivity in tenths. Counters give triangles and STL bytes a
// particle. The peak memory is the process's: measure it with /usr/bin/time -v on the CLI
// (docs/solid.md).
// Run:
//   build/bench/dla_solid_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/solid.md).

#include "dla/io/mesh_writers.h"
#include "dla/io/solid_writers.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla_tree.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>

namespace {

void solid_stl(benchmark::State& state) {
  const dla::Cluster& tree = dla_tree(static_cast<std::size_t>(state.range(0)));
  dla::LookOptions look;
  look.radius.model = dla::RadiusModel::pipe;
  const std::vector<float> radii = dla::make_look(tree, look).radii;
  dla::SolidOptions options;
  options.voxel = static_cast<double>(state.range(1)) / 1000.0;
  options.adaptivity = static_cast<double>(state.range(2)) / 10.0;
  std::size_t triangles = 0;
  for (auto _ : state) {
    const dla::Solid solid = dla::build_solid(tree, radii, options);
    dla::write_stl(solid, "/tmp/dla_solid_bench.stl");
    triangles = solid.mesh.triangles.size();
  }
  std::remove("/tmp/dla_solid_bench.stl");
  const double n = static_cast<double>(tree.particles.size());
  state.counters["triangles_per_particle"] = static_cast<double>(triangles) / n;
  state.counters["stl_bytes_per_particle"] = static_cast<double>(84 + 50 * triangles) / n;
}

}  // namespace

// The targets: 10^5 at the default voxel in 10 s, 10^6 at a voxel of a spacing in 60 s.
BENCHMARK(solid_stl)
    ->Args({100'000, 0, 0})
    ->Args({100'000, 0, 3})
    ->Args({1'000'000, 1000, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_MAIN();
