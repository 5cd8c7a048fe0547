// libFuzzer target for dla3d's command line: the input is split into words at newlines, parsed
// exactly as dla3d parses them (cli/command_line.cpp), and a growth command without a mesh is
// grown, with at most 16 particles on at most two threads, for at most a second (a stop flag,
// as Ctrl-C would), and given the look it asks for. Any words must either be refused with
// InvalidInput, or parse into options that grow a valid tree with positive radii, tubes and
// instancing points: never crash, hang, overflow or read out of bounds. A colonize command is
// grown with at most 64 nodes among at most 300 attractors, an eden command to 200 sites, a
// drop or ballistic command (without a mesh) to 64 particles.
// Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "../../cli/command_line.h"

#include "dla/models/ballistic.h"
#include "dla/models/colonization.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/models/growth.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "../tree_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words;
  std::string word;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      words.push_back(word);
      word.clear();
    } else {
      word += static_cast<char>(data[i]);
    }
  }
  if (!word.empty()) words.push_back(word);
  try {
    const dla::cli::CommandLine line = dla::cli::parse_command_line(words);
    if (line.kind == dla::cli::CommandLine::Kind::colonize) {
      // Space colonization, small: a tree of valid nodes and positive radii.
      dla::cli::ColonizeCommand c = line.colonize;
      // Meshes and point files are the readers' fuzzers' and the property test's.
      if (!c.vessel_path.empty() || !c.collide_path.empty() || !c.attractors_path.empty()) return 0;
      c.options.max_nodes = std::min<std::size_t>(c.options.max_nodes, 64);
      c.attractors.count = std::min<std::size_t>(c.attractors.count, 300);
      const std::vector<dla::Vec3> attractors =
          dla::scatter_attractors(c.attractors, c.options.rng_seed, c.options.dimensions);
      const dla::Cluster tree = dla::colonize(c.options, attractors, dla::cli::colonize_roots(c, attractors, nullptr));
      if (tree.particles.size() > c.options.max_nodes) std::abort();
      // One step a node, or as far as the noise moves it.
      const double noise = std::sqrt(3.0) * c.options.noise_amplitude;
      if (!dla::testing::tree_fault(tree, {noise > 0 ? 0.0 : 1.0, 1.0 + noise, false}).empty()) std::abort();
      const dla::Look look = dla::make_look(tree, c.look);
      for (const float radius : look.radii(tree))
        if (!(radius > 0.0f) || !std::isfinite(radius)) std::abort();
      return 0;
    }
    if (line.kind == dla::cli::CommandLine::Kind::eden) {
      // Eden growth, small: sites on the lattice, each hanging from an earlier one.
      dla::EdenOptions o = line.eden.options;
      if (!line.eden.mask_path.empty()) return 0;  // mask files are the property test's
      o.sites = std::min<std::size_t>(o.sites, 200);
      const dla::Cluster cluster = dla::eden(o);
      if (cluster.particles.size() > o.sites) std::abort();
      // A site hangs from the nearest occupied site of its mask, up to 8 sites away each way.
      if (!dla::testing::tree_fault(cluster, {1.0, 8 * std::sqrt(3.0), true}).empty()) std::abort();
      const dla::Look look = dla::make_look(cluster, line.eden.look);
      for (const float radius : look.radii(cluster))
        if (!(radius > 0.0f) || !std::isfinite(radius)) std::abort();
      return 0;
    }
    if (line.kind == dla::cli::CommandLine::Kind::drop || line.kind == dla::cli::CommandLine::Kind::ballistic) {
      // Random drops (without a mesh: meshes are the property test's) and straight lines,
      // small: each particle hangs from an earlier one.
      const bool dropping = line.kind == dla::cli::CommandLine::Kind::drop;
      if (dropping && !line.drop.mesh_path.empty()) return 0;
      dla::DropOptions drop = line.drop.options;
      dla::BallisticOptions lines = line.ballistic.options;
      drop.particles = std::min<std::size_t>(drop.particles, 64);
      lines.particles = std::min<std::size_t>(lines.particles, 64);
      // Seeds thousands of spacings apart are valid but outgrow the grid: the property test's.
      for (const dla::Vec3& seed : dropping ? drop.seeds : lines.seeds)
        if (seed.cwiseAbs().maxCoeff() > 500.0 * (dropping ? drop.spacing : lines.spacing)) return 0;
      const dla::Cluster cluster = dropping ? dla::drop(drop) : dla::ballistic(lines);
      if (!dla::testing::tree_fault(cluster).empty()) std::abort();
      const dla::Look look = dla::make_look(cluster, dropping ? line.drop.look : line.ballistic.look);
      for (const float radius : look.radii(cluster))
        if (!(radius > 0.0f) || !std::isfinite(radius)) std::abort();
      return 0;
    }
    if (line.kind != dla::cli::CommandLine::Kind::grow || !line.grow.mesh_path.empty()) return 0;
    dla::GrowthOptions options = line.grow.options;
    options.particles = std::min<std::size_t>(options.particles, 16);
    options.threads = std::min(options.threads, 2);
    // Seeds thousands of spacings apart are valid, and take a grid of a gigabyte: more than
    // the fuzzer's memory limit. They are grown by the CLI's property test.
    for (const dla::Vec3& seed : options.seeds)
      if (seed.allFinite() && seed.cwiseAbs().maxCoeff() > 500.0 * options.spacing) return 0;
    // Valid but slow setups (walkers that must find a far, small structure) are stopped as
    // Ctrl-C would stop them: what grew is checked.
    dla::StopFlag stop{false};
    std::mutex mutex;
    std::condition_variable done;
    bool finished = false;
    std::thread watchdog([&] {
      std::unique_lock<std::mutex> lock(mutex);
      if (!done.wait_for(lock, std::chrono::seconds(1), [&] { return finished; })) stop.store(true);
    });
    const auto stop_watchdog = [&] {
      {
        std::lock_guard<std::mutex> lock(mutex);
        finished = true;
      }
      done.notify_one();
      watchdog.join();
    };
    dla::Cluster cluster;
    try {
      cluster = dla::grow(options, {}, &stop);
    } catch (...) {
      stop_watchdog();
      throw;
    }
    stop_watchdog();
    if (!dla::testing::tree_fault(cluster).empty()) std::abort();
    // The look the options ask for: attributes, radii, tubes and instancing points.
    const dla::Look look = dla::make_look(cluster, line.grow.look);
    const std::vector<float> radii = look.radii(cluster);
    for (const float radius : radii)
      if (!(radius > 0.0f) || !std::isfinite(radius)) std::abort();
    std::size_t triangles = 0;
    dla::for_each_tube(cluster, look.attributes, radii, line.grow.look.tubes,
                       [&](const dla::TubePiece& piece) { triangles += piece.triangles.size(); });
    if (line.grow.instances.within == std::numeric_limits<double>::infinity())
      for (const dla::Instance& instance : dla::instancing_points(cluster, look.attributes, line.grow.instances))
        if (!(instance.scale > 0.0)) std::abort();
  } catch (const dla::InvalidInput&) {
  } catch (const dla::GrowthError&) {  // a run that cannot go on, said so
  }
  return 0;
}
