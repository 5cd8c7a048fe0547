#pragma once
//! \file one_by_one.h
//! What random drops (drop.h) and ballistic lines (ballistic.h) share: a structure grown from
//! seeds one particle at a time into an index, with the progress calls, the stop flag and the
//! partial result on failure that DLA has (dla.h).

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/index/grid_index.h"

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
      : index_(make_index(cluster_.particles, spacing, dimensions, distance_maps)) {
    cluster_.spacing = spacing;
    cluster_.dimensions = dimensions;
    cluster_.seed_count = seeds.size();
    cluster_.particles.reserve(seeds.size() + std::min<std::size_t>(particles, 1u << 24));
    index_.reserve(seeds.size() + std::min<std::size_t>(particles, 1u << 24));
    for (const Vec3& s : seeds) cluster_.center += s;
    cluster_.center /= static_cast<double>(seeds.size());
    for (std::size_t i = 0; i < seeds.size(); ++i) add({seeds[i], -1, static_cast<std::int32_t>(i)});
  }

  //! Calls `attempt()` until `particles` have attached, it says done, or `stop` is set (the
  //! cluster then comes back incomplete); `progress` every 256 particles and at the end.
  //! Throws PartialGrowth, with what grew, if the structure outgrows the index or memory.
  template <class Try>
  Cluster run(std::size_t particles, const ProgressFn& progress, const StopFlag* stop, Try&& attempt) {
    try {
      while (attached(cluster_) < particles) {
        if (stop && stop->load(std::memory_order_relaxed)) {
          cluster_.complete = false;
          break;
        }
        const Attempt result = attempt();
        if (result == Attempt::done) {
          if (progress) progress(cluster_);
          break;
        }
        const std::size_t n = attached(cluster_);
        if (result == Attempt::attached && progress && (n % 256 == 0 || n == particles) && !progress(cluster_)) {
          cluster_.complete = n == particles;
          break;
        }
      }
    } catch (const GrowthError& e) {
      cluster_.complete = false;
      throw PartialGrowth(e.what(), std::move(cluster_));
    } catch (const std::bad_alloc&) {
      cluster_.complete = false;
      throw PartialGrowth("out of memory after " + std::to_string(attached(cluster_)) + " particles", std::move(cluster_));
    }
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
    index_.insert(static_cast<std::int32_t>(cluster_.particles.size() - 1));
    cluster_radius_ = std::max(cluster_radius_, (p.position - cluster_.center).norm());
  }

  Cluster cluster_;  // before the index, which reads its particles
  Index index_;
  double cluster_radius_ = 0.0;
};

}  // namespace dla::detail
