// libFuzzer target for dla3d's command line: the input is split into words at newlines and
// parsed exactly as dla3d parses them (cli/command_line.cpp). A growth run of any model that
// reads no file (meshes, text, attractors, masks: the readers' fuzzers' and the property
// test's) is prepared by the library's run layer, as dla3d prepares it, grown small (DLA to 16
// particles on at most two threads, colonize to 64 nodes among 300 attractors, Eden to 200
// sites, drop and ballistic to 64 particles, an aggregate to 64 monomers) for at most a second (a stop flag, as Ctrl-C
// would), and given the look it asks for, and its solid (in 200 MB at most). Any words must
// either be refused with InvalidInput, or grow a valid tree (tree_check.h) with positive radii,
// tubes, instancing points and a solid of positive volume: never crash, hang, overflow or read
// out of bounds.
// Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "../../cli/command_line.h"
#include "../tree_check.h"

#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla/run/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

//! Seeds thousands of spacings apart are valid, and take a grid of a gigabyte: more than the
//! fuzzer's memory limit. The CLI's property test grows them.
bool far_apart(const std::vector<dla::Vec3>& seeds, double spacing) {
  for (const dla::Vec3& seed : seeds)
    if (seed.allFinite() && seed.cwiseAbs().maxCoeff() > 500.0 * spacing) return true;
  return false;
}

//! The run, small, or false for one that reads a file or would outgrow the fuzzer's memory.
bool make_small(dla::RunOptions& run) {
  if (auto* o = run.get_if<dla::DlaRunOptions>()) {
    if (o->has_mesh()) return false;
    o->particles = std::min<std::size_t>(o->particles.value_or(o->growth.particles), 16);
    o->growth.threads = std::min(o->growth.threads, 2);
    return !far_apart(o->seed_at.value_or(o->growth.seeds), o->spacing.value_or(o->growth.spacing));
  }
  if (auto* o = run.get_if<dla::BreakdownRunOptions>()) {
    if (o->has_mesh() || !o->target_mesh.empty()) return false;
    o->particles = std::min<std::size_t>(o->particles.value_or(o->growth.particles), 16);
    o->growth.threads = std::min(o->growth.threads, 2);
    const double spacing = o->spacing.value_or(o->growth.spacing);
    const dla::Target& target = o->breakdown.target;
    // A target far away is valid, and walkers take long to cross to it: the property test grows it.
    if (target.kind != dla::TargetKind::none &&
        (target.point.cwiseAbs().maxCoeff() > 100.0 * spacing || std::abs(target.at) > 100.0 * spacing))
      return false;
    return !far_apart(o->seed_at.value_or(o->growth.seeds), spacing);
  }
  if (auto* o = run.get_if<dla::ColonizeRunOptions>()) {
    if (!o->stl.empty() || !o->collide.empty() || !o->attractors_from.empty()) return false;
    o->colonization.max_nodes = std::min<std::size_t>(o->colonization.max_nodes, 64);
    o->attractors.count = std::min<std::size_t>(o->attractors.count, 300);
    return true;
  }
  if (auto* o = run.get_if<dla::EdenRunOptions>()) {
    o->eden.sites = std::min<std::size_t>(o->eden.sites, 200);
    return o->mask_file.empty();
  }
  if (auto* o = run.get_if<dla::DropRunOptions>()) {
    o->drop.particles = std::min<std::size_t>(o->drop.particles, 64);
    return o->stl.empty() && !far_apart(o->seed_at.value_or(o->drop.seeds), o->spacing.value_or(o->drop.spacing));
  }
  if (auto* o = run.get_if<dla::BallisticRunOptions>()) {
    o->ballistic.particles = std::min<std::size_t>(o->ballistic.particles, 64);
    return !far_apart(o->ballistic.seeds, o->ballistic.spacing);
  }
  if (auto* o = run.get_if<dla::AggregateRunOptions>()) {
    o->aggregate.monomers = std::min<std::size_t>(o->aggregate.monomers, 64);
    return true;
  }
  // A model registered since: it must join, or the fuzzer would not grow it.
  throw std::logic_error("the CLI fuzzer cannot make a " + std::string(dla::model_of(run).name) + " run small");
}

//! What a tree of this model may hold beyond the rules of every tree.
dla::testing::TreeRules rules_of(const dla::RunOptions& run) {
  if (const auto* o = run.get_if<dla::ColonizeRunOptions>()) {
    const double noise = std::sqrt(3.0) * o->colonization.noise_amplitude;  // one step, or as far as the noise moves it
    return {noise > 0 ? 0.0 : 1.0, 1.0 + noise, false};
  }
  // A monomer touches its parent at (1 - overlap)(r_i + r_j), in spacings of 2a: up to the
  // largest radius the spread draws, in a.
  if (const auto* o = run.get_if<dla::AggregateRunOptions>()) {
    const dla::AggregateOptions& a = o->aggregate;
    const double widest = a.sizes == dla::MonomerSizes::lognormal ? std::pow(a.spread, 4.0)
                          : a.sizes == dla::MonomerSizes::normal  ? 2.0 + 4.0 * a.spread
                                                                  : 1.0;
    return {0.0, widest * (1.0 + 1e-9), false};
  }
  // An Eden site hangs from the nearest occupied site of its mask, up to 8 sites away each way.
  if (run.get_if<dla::EdenRunOptions>()) return {1.0, 8 * std::sqrt(3.0), true};
  return {};
}

//! Grows `run` with a watchdog that stops it after a second, as Ctrl-C would.
dla::Cluster grow_briefly(dla::Run& run) {
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
  try {
    dla::Cluster cluster = run.grow({}, &stop);
    stop_watchdog();
    return cluster;
  } catch (...) {
    stop_watchdog();
    throw;
  }
}

}  // namespace

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
    dla::cli::CommandLine line = dla::cli::parse_command_line(words);
    if (line.kind != dla::cli::CommandLine::Kind::run || !make_small(line.run)) return 0;
    const std::unique_ptr<dla::Run> run = dla::prepare_run(line.run);
    dla::Cluster cluster = grow_briefly(*run);
    if (!dla::testing::tree_fault(cluster, rules_of(line.run)).empty()) std::abort();
    // Its links: two particles each, earlier first, none a tree edge, in order of the later.
    if (run->links.any()) cluster.links = run->make_links(cluster, {});
    for (std::size_t k = 0; k < cluster.links.size(); ++k) {
      const dla::Link& link = cluster.links[k];
      if (!(0 <= link.earlier && link.earlier < link.later &&
            static_cast<std::size_t>(link.later) < cluster.particles.size()) ||
          cluster.particles[static_cast<std::size_t>(link.later)].parent == link.earlier ||
          (k > 0 && link.later < cluster.links[k - 1].later))
        std::abort();
    }
    // The look the options ask for: attributes, radii, tubes and instancing points.
    const dla::OutputOptions& files = run->files;
    const dla::Look look = dla::make_look(cluster, files.look);
    const std::vector<float> radii = look.radii;
    for (const float radius : radii)
      if (!(radius > 0.0f) || !std::isfinite(radius)) std::abort();
    std::size_t triangles = 0;
    dla::for_each_tube(cluster, look.attributes, radii, files.look.tubes,
                       [&](const dla::TubePiece& piece) { triangles += piece.triangles.size(); });
    // Without the mesh, no distance to it nor its paint: those selections are checked elsewhere.
    if (files.instances.within == std::numeric_limits<double>::infinity() && !files.instances.exclude_paint)
      for (const dla::Instance& instance : dla::instancing_points(cluster, look.attributes, files.instances))
        if (!(instance.scale > 0.0)) std::abort();
    // The solid it asks for, in at most the fuzzer's share of memory: closed, of positive volume.
    if (files.formats.solid()) {
      dla::SolidOptions solid = files.solid;
      solid.memory = solid.memory > 0.0 ? std::min(solid.memory, 200.0) : 200.0;
      solid.threads = 2;
      const dla::Solid built = dla::build_solid(cluster, radii, solid);
      if (built.measures.shells < 1 || !(built.measures.volume > 0.0)) std::abort();
    }
  } catch (const dla::InvalidInput&) {
  } catch (const dla::GrowthError&) {  // a run that cannot go on, said so
  }
  return 0;
}
