// Writing a structure of 10^6 and 10^7 particles: each file dla3d writes, timed alone, into
// /tmp (the page cache: the formatting's cost, not the disk's). The tree is made up (each
// particle a spacing from a random recent one), which writers cannot tell from grown DLA.
// Run:
//   build/bench/dla_writer_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// (medians in docs/performance.md).

#include "dla/io/checkpoint.h"
#include "dla/io/csv_writer.h"
#include "dla/io/html_writer.h"
#include "dla/look/look.h"
#include "dla/io/ply_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/core/random.h"
#include "dla/io/run_report.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

namespace {

const dla::Cluster& made_up_tree(std::size_t n) {
  static std::map<std::size_t, dla::Cluster> trees;
  dla::Cluster& tree = trees[n];
  if (!tree.particles.empty()) return tree;
  dla::Rng rng(1, 0);
  tree.seed_count = 1;
  tree.particles.reserve(n + 1);
  tree.particles.push_back({dla::Vec3::Zero(), -1, 0});
  for (std::size_t i = 1; i <= n; ++i) {
    const std::size_t back = 1 + static_cast<std::size_t>(rng.uniform() * std::min<double>(1000.0, static_cast<double>(i)));
    const auto parent = static_cast<std::int32_t>(i - std::min(back, i));
    const dla::Vec3 at = tree.particles[static_cast<std::size_t>(parent)].position + dla::random_direction(rng, 3);
    tree.particles.push_back({at, parent, 0});
  }
  return tree;
}

// The made-up tree's look, with the tips' gaps the scene uses: what the CLI writes with.
const dla::Look& made_up_look(std::size_t n) {
  static std::map<std::size_t, dla::Look> looks;
  const auto found = looks.find(n);
  if (found != looks.end()) return found->second;
  return looks[n] = dla::make_look(made_up_tree(n), {});
}

template <class Write>
void write_file(benchmark::State& state, Write write) {
  const dla::Cluster& tree = made_up_tree(static_cast<std::size_t>(state.range(0)));
  const std::string prefix = "/tmp/dla_writer_bench";
  for (auto _ : state) write(tree, prefix);
  state.counters["particles_per_s"] = benchmark::Counter(static_cast<double>(state.range(0)),
                                                         benchmark::Counter::kIsIterationInvariantRate);
  for (const char* ext : {".csv", ".ply", ".pov", ".inc", "_growth.inc", ".html", ".json", ".ck"})
    std::remove((prefix + ext).c_str());
}

void csv(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) { dla::write_csv(c, p + ".csv"); });
}
void csv_look(benchmark::State& state) {
  const dla::Look& look = made_up_look(static_cast<std::size_t>(state.range(0)));
  write_file(state, [&](const dla::Cluster& c, const std::string& p) { dla::write_csv(c, look, p + ".csv"); });
}
void ply_ascii(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) { dla::write_ply(c, p + ".ply", dla::PlyEncoding::ascii); });
}
void ply_binary(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) {
    dla::write_ply(c, p + ".ply", dla::PlyEncoding::binary);
  });
}
void pov(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) { dla::write_pov(c, p); });
}
void pov_look(benchmark::State& state) {
  const dla::Look& look = made_up_look(static_cast<std::size_t>(state.range(0)));
  write_file(state, [&](const dla::Cluster& c, const std::string& p) { dla::write_pov(c, p, {}, nullptr, &look); });
}
void html(benchmark::State& state) {
  const dla::Look& look = made_up_look(static_cast<std::size_t>(state.range(0)));
  write_file(state, [&](const dla::Cluster& c, const std::string& p) { dla::write_html(c, look, p + ".html"); });
}
void json(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) {
    dla::write_run_report(c, {"dla", 1}, {}, {}, {}, p + ".json");
  });
}
void checkpoint(benchmark::State& state) {
  write_file(state, [](const dla::Cluster& c, const std::string& p) { dla::write_checkpoint({{}, 0, c, {}}, p + ".ck"); });
}

}  // namespace

#define DLA_WRITER_BENCH(f) \
  BENCHMARK(f)->Name("write/" #f)->ArgName("n")->Arg(1'000'000)->Arg(10'000'000) \
      ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime()
DLA_WRITER_BENCH(csv);
DLA_WRITER_BENCH(csv_look);
DLA_WRITER_BENCH(ply_ascii);
DLA_WRITER_BENCH(ply_binary);
DLA_WRITER_BENCH(pov);
DLA_WRITER_BENCH(pov_look);
DLA_WRITER_BENCH(html);
DLA_WRITER_BENCH(json);
DLA_WRITER_BENCH(checkpoint);

BENCHMARK_MAIN();
