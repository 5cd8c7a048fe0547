#pragma once
//! \file particle_feed.h
//! Particles handed, as they attach, from the thread that grows them to one that works on them
//! meanwhile (run.h: the distances to a mesh, measured on a spare core as DLA grows).

#include "dla/core/cluster.h"

#include <atomic>
#include <cstddef>
#include <limits>
#include <vector>

namespace dla {

//! A queue of particles of fixed room between one thread that puts and one that takes. Putting
//! never waits: once the taker falls a whole room behind, the feed closes and takes no more, so
//! the taker has every particle from the first up to where it closed, and growth never slows.
class ParticleFeed {
 public:
  //! Room for at least `room` particles: the next power of two, so that a count finds its
  //! place with a mask.
  explicit ParticleFeed(std::size_t room = std::size_t{1} << 16) : ring_(power_of_two_from(room)) {}

  //! On the growing thread: the next particle; dropped once the feed is closed.
  void put(const Particle& particle) {
    const std::size_t put = put_.load(std::memory_order_relaxed);
    if (closed_.load(std::memory_order_relaxed)) return;
    // The taker's count is looked at only when the room seems full: its cache line stays with
    // the taker.
    if (put - taken_before_ == ring_.size()) {
      taken_before_ = taken_.load(std::memory_order_acquire);
      if (put - taken_before_ == ring_.size()) {
        closed_.store(true, std::memory_order_release);
        return;
      }
    }
    ring_[put & (ring_.size() - 1)] = particle;
    put_.store(put + 1, std::memory_order_release);
  }

  //! On the taking thread: how many particles have been put (the first is 0).
  std::size_t put_count() const { return put_.load(std::memory_order_acquire); }
  //! On the taking thread: particle k, put but not yet taken.
  const Particle& at(std::size_t k) const { return ring_[k & (ring_.size() - 1)]; }
  //! On the taking thread: every particle before k is done with; their room is free. Once a
  //! batch, not a particle: the putter looks at it when its room seems full.
  void taken(std::size_t k) { taken_.store(k, std::memory_order_release); }
  //! Whether the taker fell a room behind and the feed took no more from then on.
  bool closed() const { return closed_.load(std::memory_order_acquire); }

 private:
  //! The least power of two not below `room`; past the largest, the largest (which no vector
  //! can hold: its constructor throws std::length_error).
  static std::size_t power_of_two_from(std::size_t room) {
    std::size_t size = 1;
    while (size < room && size <= std::numeric_limits<std::size_t>::max() / 2) size *= 2;
    return size;
  }

  std::vector<Particle> ring_;
  alignas(64) std::atomic<std::size_t> put_{0};
  std::atomic<bool> closed_{false};
  std::size_t taken_before_ = 0;  // the taker's count when the putter last looked
  alignas(64) std::atomic<std::size_t> taken_{0};
};

}  // namespace dla
