// The targets of growth in a mesh, through the run layer as the CLI makes a run (prepare_run,
// grow_recorded, write_run): the main job (`dla3d --stl bust.stl --seeds 2`) against free
// growth of the same count, a fine spacing in the bust (`--spacing 0.1 -n 300000`), and what
// writing a mesh run's files costs beside its growth (the look and the measures ask the
// surface's distance of every particle): the JSON record alone, and the main job's default
// files. Each iteration writes over the files of the one before, as a user running again does.
// Run:
//   build/bench/dla_mesh_run_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// Each iteration grows the same structure: the spread is the machine's.

#include "dla/run/run.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

namespace {

std::filesystem::path scratch() { return std::filesystem::temp_directory_path() / "dla_mesh_run_bench"; }

dla::DlaRunOptions options(bool mesh, std::size_t particles, double spacing, const char* formats = "json") {
  dla::DlaRunOptions o;
  if (mesh) {
    o.stl = BUST_OFF_PATH;
    o.seeds.count = 2;
  }
  if (particles) o.particles = particles;
  if (spacing > 0.0) o.spacing = spacing;
  std::filesystem::create_directories(scratch());
  o.files.output = (scratch() / "run").string();
  o.files.formats = dla::parse_formats(formats);
  return o;
}

//! Grows (timed), then writes the files (timed apart: all of write_run, the JSON record too).
void run(benchmark::State& state, const dla::DlaRunOptions& o) {
  if (!o.stl.empty() && !std::filesystem::exists(o.stl))
    return state.SkipWithError("the bust is missing: install libcgal-demo and run cmake again");
  double grow_seconds = 0.0, write_seconds = 0.0;
  std::size_t particles = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const std::unique_ptr<dla::Run> prepared = dla::prepare_run(o);
    dla::RunRecord record;
    state.ResumeTiming();
    const dla::Cluster grown = dla::grow_recorded(*prepared, {}, nullptr, record);
    state.PauseTiming();
    const auto start = std::chrono::steady_clock::now();
    dla::write_run(*prepared, grown, record);
    write_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    grow_seconds += record.grow_seconds;
    particles = grown.particles.size();
    state.ResumeTiming();
  }
  const double n = static_cast<double>(particles);
  state.counters["particles_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["write_share"] = write_seconds / grow_seconds;  // the files' time over growth's
}

void main_job(benchmark::State& state) { run(state, options(true, 0, 0.0)); }
void main_job_default_files(benchmark::State& state) { run(state, options(true, 0, 0.0, "pov,csv,ply,json")); }
void free_same_count(benchmark::State& state) { run(state, options(false, 30'000, 0.0)); }
void fine_spacing(benchmark::State& state) { run(state, options(true, 300'000, 0.1)); }

}  // namespace

BENCHMARK(main_job)->Name("bust/main_job")->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();
BENCHMARK(main_job_default_files)->Name("bust/main_job_default_files")->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();
BENCHMARK(free_same_count)->Name("free/30000")->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();
BENCHMARK(fine_spacing)->Name("bust/spacing_0.1_300000")->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
