#pragma once
//! \file one_by_one.h
//! What random drops (drop.h) and ballistic lines (ballistic.h) share: a structure grown from
//! seeds one particle at a time into an index, in the shell every model grows in
//! (model_shell.h).

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/index/grid_index.h"
#include "dla/models/model_shell.h"

#include <algorithm>
#include <cstdint>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

namespace dla::detail {

//! What one try to attach a particle came to.
enum class Attempt {
  attached,  //!< a particle joined
  failed,    //!< none did; try again
  done,      //!< none can: growth ends, complete, with fewer particles
};

template <class Index>
class OneByOne {
 public:
  //! Starts from the seeds, one tree each. Without `distance_maps`, a GridIndex keeps no gap
  //! or node map (grid_index.h): for models that only ask nearest().
  OneByOne(const std::vector<Vec3>& seeds, double spacing, int dimensions, std::size_t particles, bool distance_maps)
      : cluster_(seeded(seeds, spacing, dimensions)),
        index_(make_index(cluster_.particles, spacing, dimensions, distance_maps)) {
    cluster_.particles.reserve(seeds.size() + std::min<std::size_t>(particles, 1u << 24));
    index_.reserve(seeds.size() + std::min<std::size_t>(particles, 1u << 24));
    for (std::size_t i = 0; i < seeds.size(); ++i) index_add(static_cast<std::int32_t>(i));
  }

  //! Calls `attempt()` until `particles` have attached, it says done, or `stop` is set or
  //! `progress` says stop (the cluster then comes back incomplete). Throws PartialGrowth, with
  //! what grew, if the structure outgrows the index or memory.
  template <class Try>
  Cluster run(std::size_t particles, const ProgressFn& progress, const StopFlag* stop, Try&& attempt) {
    ModelShell shell(progress, stop, 64);  // a particle can take a microsecond
    try {
      while (attached(cluster_) < particles) {
        const Attempt result = attempt();
        if (result == Attempt::done) break;
        if (attached(cluster_) < particles && !shell.go_on(cluster_)) {
          cluster_.complete = false;
          break;
        }
      }
    } catch (...) {
      ModelShell::keep_what_grew(cluster_);
    }
    shell.finish(cluster_);
    return std::move(cluster_);
  }

  const Vec3& position(std::int32_t id) const { return cluster_.particles[static_cast<std::size_t>(id)].position; }

  //! Attaches a particle to `parent`, in its tree.
  void attach(const Vec3& at, std::int32_t parent) {
    add({at, parent, cluster_.particles[static_cast<std::size_t>(parent)].seed});
  }

  const Cluster& cluster() const { return cluster_; }
  const Index& index() const { return index_; }
  double cluster_radius() const { return cluster_radius_; }  //!< farthest particle from the centre

 private:
  static Index make_index(const std::vector<Particle>& particles, double spacing, int dimensions, bool distance_maps) {
    if constexpr (std::is_same_v<Index, GridIndex>) return Index(particles, spacing, dimensions, distance_maps);
    else return Index(particles, spacing, dimensions);
  }

  void add(const Particle& p) {
    cluster_.particles.push_back(p);
    index_add(static_cast<std::int32_t>(cluster_.particles.size() - 1));
  }
  void index_add(std::int32_t id) {
    index_.insert(id);
    cluster_radius_ = std::max(cluster_radius_, (position(id) - cluster_.center).norm());
  }

  Cluster cluster_;  // before the index, which reads its particles
  Index index_;
  double cluster_radius_ = 0.0;
};

}  // namespace dla::detail
