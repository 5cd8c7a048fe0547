#pragma once
//! \file links.h
//! Branches that join: links between neighbours beside the tree (`--links D[,K]`). When a
//! particle attaches, it is also linked to up to K earlier particles within D spacings, nearest
//! first, leaving out those within kLoopSteps - 1 tree steps of it: a link joins two different
//! branches into a loop of at least kLoopSteps + 1 branches, instead of closing a small
//! triangle. The thesis "DLA inside 3D models" (section 4.2.2, figure 22) links each stopped
//! point to its neighbours so. See docs/loops.md.
//!
//! A link depends only on the particles before its later one, so the links of a finished
//! structure are those growth would have made as it went: they are made after growth, on the
//! index's range query, on several threads, and are the same for any thread count.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/options.h"
#include "dla/core/stop.h"
#include "dla/index/grid_index.h"
#include "dla/index/kdtree_index.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <vector>

namespace dla {

//! The fewest tree steps between two particles that a link may join: a link closes a loop of
//! at least this many branches and itself.
inline constexpr int kLoopSteps = 8;

//! The most links one particle may make when it attaches.
inline constexpr std::size_t kMaxLinksEach = 64;

//! Links between neighbours (`links`). Not set (distance 0): a tree.
struct LinkOptions {
  double distance = 0.0;  //!< spacings between the centres at most, in (0, 100]; 0: no links
  std::size_t most = 1;   //!< links a particle makes when it attaches, at most, 1-64
  //! Eden only: every pair of lattice neighbours (the lattice graph); distance and most are the
  //! lattice's.
  bool lattice = false;
  bool any() const { return lattice || distance > 0.0; }
};

inline void validate(const LinkOptions& o) {
  if (o.lattice || o.distance == 0.0) return;
  detail::require_in("`links` distance", o.distance, 1e-3, 100.0);
  if (o.most < 1 || o.most > kMaxLinksEach)
    throw InvalidInput("`links` " + std::to_string(o.most) + " links a particle is not in 1-64");
}

//! "D", "D,K" or "lattice", as the CLI and Python write `links`.
inline LinkOptions parse_links(std::string_view word) {
  LinkOptions o;
  if (word == "lattice") {
    o.lattice = true;
    return o;
  }
  const std::size_t comma = word.find(',');
  const std::string distance(word.substr(0, comma));
  char* end = nullptr;
  o.distance = std::strtod(distance.c_str(), &end);
  bool good = !distance.empty() && end == distance.c_str() + distance.size();
  if (good && comma != std::string_view::npos) {
    const std::string_view most = word.substr(comma + 1);
    const auto [at, error] = std::from_chars(most.data(), most.data() + most.size(), o.most);
    good = !most.empty() && error == std::errc() && at == most.data() + most.size();
  }
  if (!good)
    throw InvalidInput("`links` '" + std::string(word) +
                       "' is not D (spacings), D,K (K links a particle at most) or lattice (Eden)");
  if (o.distance <= 0.0) throw InvalidInput("`links` distance " + distance + " is not above 0");
  validate(o);
  return o;
}

//! How the options were written: "2", "2,3" or "lattice".
inline std::string to_string(const LinkOptions& o) {
  if (o.lattice) return "lattice";
  return detail::format_number(o.distance) + (o.most == 1 ? "" : "," + std::to_string(o.most));
}

//! `links` described once: "D[,K]", with `lattice` (Eden's) "D[,K]|lattice".
inline const OptionTable<LinkOptions>& links_option_table(bool lattice = false) {
  const auto table = [](bool lattice) {
    return OptionTable<LinkOptions>{parsed<LinkOptions>(
        "links", OptionKind::text, lattice ? "D[,K]|lattice" : "D[,K]", "Growth",
        lattice ? "also link each particle, as it attaches, to up to K (default 1) earlier ones within D spacings and "
                  "at least 8 tree steps away: loops (docs/loops.md); lattice: every pair of neighbouring sites"
                : "also link each particle, as it attaches, to up to K (default 1) earlier ones within D spacings and "
                  "at least 8 tree steps away: loops (docs/loops.md)",
        [](LinkOptions& o, const std::string& words) { o = words.empty() ? LinkOptions{} : parse_links(words); },
        [](const LinkOptions& o) { return o.any() ? to_string(o) : std::string(); })};
  };
  static const OptionTable<LinkOptions> plain = table(false), with_lattice = table(true);
  return lattice ? with_lattice : plain;
}

//! Whether a link may join two particles at these centres (a constraint mesh's test that the
//! segment stays on its growing side); none: any.
using LinkFilter = std::function<bool(const Vec3& earlier, const Vec3& later)>;

namespace detail {

//! Whether particles a and b are fewer than `steps` (at most 32) tree steps apart.
inline bool tree_near(const std::vector<Particle>& ps, std::int32_t a, std::int32_t b, int steps) {
  // a's ancestors up to steps - 1 above it, then b's, each against them.
  std::int32_t up[32];
  steps = std::min(steps, 32);
  int count = 0;
  for (std::int32_t v = a; v >= 0 && count < steps; v = ps[static_cast<std::size_t>(v)].parent) up[count++] = v;
  std::int32_t v = b;
  for (int m = 0; v >= 0 && m < steps; ++m, v = ps[static_cast<std::size_t>(v)].parent)
    for (int k = 0; k < count && k + m < steps; ++k)
      if (up[k] == v) return true;
  return false;
}

//! The links particles [begin, end) make, in order, on `index` holding every particle; none
//! more once `stop` is set.
template <class Index>
void links_of(const Cluster& cluster, const Index& index, double radius, std::size_t most, int steps,
              const LinkFilter& keep, std::size_t begin, std::size_t end, const StopFlag* stop, std::vector<Link>& links) {
  const auto& ps = cluster.particles;
  std::vector<std::pair<double, std::int32_t>> near;
  // A particle among 10^4 neighbours takes a millisecond: the flag is read before each.
  for (std::size_t i = begin; i < end && !stopped(stop); ++i) {
    const auto later = static_cast<std::int32_t>(i);
    near.clear();
    index.for_each_within(ps[i].position, radius, [&](std::int32_t j, double d2) {
      if (j < later) near.emplace_back(d2, j);
    });
    std::sort(near.begin(), near.end());
    std::size_t made = 0;
    for (const auto& [d2, j] : near) {
      if (made == most) break;
      if (tree_near(ps, later, j, steps)) continue;
      if (keep && !keep(ps[static_cast<std::size_t>(j)].position, ps[i].position)) continue;
      links.push_back({j, later});
      ++made;
    }
  }
}

template <class Index>
std::vector<Link> link_with(const Cluster& cluster, double radius, std::size_t most, int steps, const LinkFilter& keep,
                            int threads, const StageWatch& watch) {
  const auto& ps = cluster.particles;
  // The grid without its distance maps: only range queries are asked.
  Index index = [&] {
    if constexpr (std::is_same_v<Index, GridIndex>) return GridIndex(ps, cluster.spacing, cluster.dimensions, false);
    else return Index(ps, cluster.spacing, cluster.dimensions);
  }();
  index.reserve(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) index.insert(static_cast<std::int32_t>(i));
  // Ranges of particles on `threads` threads, joined in order: small ones, so the progress
  // heard after each of the calling thread's is smooth.
  const std::size_t chunks = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(threads) * 256, ps.size() / 256 + 1));
  std::vector<std::vector<Link>> parts(chunks);
  std::vector<std::thread> workers;
  std::atomic<std::size_t> next{0}, finished{0};
  std::exception_ptr failure;
  std::mutex failed;
  const auto work = [&](bool caller) {
    try {
      for (std::size_t c; (c = next++) < chunks;) {
        links_of(cluster, index, radius, most, steps, keep, ps.size() * c / chunks, ps.size() * (c + 1) / chunks,
                 watch.stop, parts[c]);
        const double done = static_cast<double>(++finished) / static_cast<double>(chunks);
        if (caller && watch.progress) watch.progress(done, "links");
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failed);
      failure = std::current_exception();
    }
  };
  for (int t = 1; t < threads && static_cast<std::size_t>(t) < chunks; ++t) workers.emplace_back(work, false);
  work(true);
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  if (stopped(watch.stop)) throw Interrupted("the links were stopped before every particle's were made");
  std::vector<Link> links;
  for (const std::vector<Link>& part : parts) links.insert(links.end(), part.begin(), part.end());
  return links;
}

}  // namespace detail

//! The links `options` ask for on `cluster`'s tree, those `keep` allows, made on `threads`
//! threads; the same for any count. Particles fewer than `steps` tree steps apart are not
//! linked. `lattice` needs lattice_links() (eden.h). Throws Interrupted, with no links made,
//! once `watch.stop` is set.
inline std::vector<Link> neighbour_links(const Cluster& cluster, const LinkOptions& options, int threads = 1,
                                         const LinkFilter& keep = {}, int steps = kLoopSteps,
                                         const StageWatch& watch = {}) {
  validate(options);
  if (options.lattice) throw InvalidInput("`links` lattice links the sites of an Eden cluster; give D[,K] spacings");
  if (!options.any()) return {};
  const double radius = options.distance * cluster.spacing;
  threads = std::clamp(threads, 1, 256);
  try {
    return detail::link_with<GridIndex>(cluster, radius, options.most, steps, keep, threads, watch);
  } catch (const GrowthError&) {  // beyond the grid's reach: the k-d tree holds any extent
    return detail::link_with<KdTreeIndex>(cluster, radius, options.most, steps, keep, threads, watch);
  }
}

}  // namespace dla
