#pragma once
//! \file grid_index.h
//! The default nearest-particle look-up: a grid of cells two spacings wide, stored in blocks
//! allocated where particles are, under a pyramid of coarser occupancy bits.
//!
//! Far from the structure a probe reads one bit per pyramid level and returns a lower bound
//! on the distance (the walk only needs a ball free of particles); within a few spacings it
//! scans the 27 cells around the point and returns the exact nearest particle. See
//! docs/index.md for the layout and the measurements that made it the default.

#include "dla/errors.h"
#include "dla/spatial_index.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dla {

class GridIndex {
 public:
  GridIndex(const std::vector<Particle>& particles, double spacing, int dimensions)
      : particles_(particles), cell_(2.0 * spacing), planar_(dimensions == 2) {}

  void insert(std::int32_t id) {
    const Vec3& p = particles_[static_cast<std::size_t>(id)].position;
    if (cells_ == 0) start(p, 0.0);
    while (!inside(p, 0.0)) grow();
    next_.push_back(-1);
    ++inserted_;
    place(id);
  }

  void cover(const Vec3& center, double radius) {
    if (cells_ == 0) start(center, radius);
    while (!inside(center, radius)) grow();
  }

  Probe probe(const Vec3& x) const {
    if (cells_ == 0) return {};
    std::array<double, 3> f;  // position in fine cells from the domain's corner
    std::array<int, 3> c;
    for (int a = 0; a < axes(); ++a) {
      f[a] = (x[a] - origin_[a]) / cell_;
      if (!(f[a] >= 0.0 && f[a] < dims_[a])) return {-1, distance_to_domain(x)};
      c[a] = static_cast<int>(f[a]);
    }
    if (planar_) c[2] = 0;

    // The coarsest clear level around x bounds the distance by its cell size plus the
    // distance from x to its own cell's faces.
    int clear = -1;
    for (int l = 0; l < static_cast<int>(levels_.size()); ++l) {
      if (levels_[l].test(c, planar_)) break;
      clear = l;
    }
    if (clear >= 0) {
      const int shift = levels_[clear].shift;
      return {-1, ((1 << shift) + face_margin(f, c, shift)) * cell_};
    }

    std::int32_t best = -1;
    double best2 = std::numeric_limits<double>::infinity();
    for_each_cell(c[0] - 1, c[0] + 1, c[1] - 1, c[1] + 1, planar_ ? 0 : c[2] - 1,
                  planar_ ? 0 : c[2] + 1, [&](std::int32_t id) {
                    const double d2 = (particles_[static_cast<std::size_t>(id)].position - x)
                                          .squaredNorm();
                    if (d2 < best2) {
                      best2 = d2;
                      best = id;
                    }
                  });
    const double bound = (1.0 + face_margin(f, c, 0)) * cell_;
    if (best >= 0 && best2 <= bound * bound) return {best, std::sqrt(best2)};
    return {-1, bound};
  }

  template <class Visit>
  void for_each_within(const Vec3& x, double radius, Visit&& visit) const {
    if (cells_ == 0) return;
    std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int a = 0; a < axes(); ++a) {
      const double from = std::floor((x[a] - radius - origin_[a]) / cell_);
      const double to = std::floor((x[a] + radius - origin_[a]) / cell_);
      if (to < 0.0 || from >= dims_[a]) return;
      lo[a] = static_cast<int>(std::max(from, 0.0));
      hi[a] = static_cast<int>(std::min(to, dims_[a] - 1.0));
    }
    const double r2 = radius * radius;
    for_each_cell(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], [&](std::int32_t id) {
      const double d2 = (particles_[static_cast<std::size_t>(id)].position - x).squaredNorm();
      if (d2 <= r2) visit(id, d2);
    });
  }

  //! Bytes held by the grid (cells, blocks and pyramid), for bench/.
  std::size_t memory_bytes() const {
    std::size_t bytes = (block_of_.capacity() + heads_.capacity() + next_.capacity()) * 4;
    for (const Level& level : levels_) bytes += level.bits.capacity() * 8;
    return bytes;
  }

 private:
  static constexpr int kBlockShift = 3;                   // blocks of 8 cells a side
  static constexpr int kMaxCells = 2048;                  // cells a side at most
  static constexpr std::size_t kMaxLevelWords = 1 << 22;  // 32 MiB; finer levels are skipped

  //! One pyramid level: cells of 2^shift fine cells a side; a bit is set when a particle lies
  //! in the cell or one of its 26 neighbours, so one bit answers "is the 3x3x3 block empty".
  struct Level {
    int shift;
    std::array<int, 3> dims;
    std::vector<std::uint64_t> bits;

    std::size_t bit(const std::array<int, 3>& c) const {
      return (static_cast<std::size_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
    }
    bool test(const std::array<int, 3>& fine, bool planar) const {
      const std::array<int, 3> c{fine[0] >> shift, fine[1] >> shift, planar ? 0 : fine[2] >> shift};
      const std::size_t b = bit(c);
      return (bits[b >> 6] >> (b & 63)) & 1u;
    }
    void mark(const std::array<int, 3>& fine, bool planar) {
      const std::array<int, 3> c{fine[0] >> shift, fine[1] >> shift, planar ? 0 : fine[2] >> shift};
      const int dz = planar ? 0 : 1;
      for (int z = std::max(c[2] - dz, 0); z <= std::min(c[2] + dz, dims[2] - 1); ++z)
        for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
          for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, dims[0] - 1); ++x) {
            const std::size_t b = bit({x, y, z});
            bits[b >> 6] |= std::uint64_t{1} << (b & 63);
          }
    }
  };

  int axes() const { return planar_ ? 2 : 3; }

  //! Distance from fractional cell position f to the faces of its cell at level `shift`, in
  //! fine cells.
  double face_margin(const std::array<double, 3>& f, const std::array<int, 3>& c, int shift) const {
    double margin = std::numeric_limits<double>::infinity();
    for (int a = 0; a < axes(); ++a) {
      const double lo = static_cast<double>((c[a] >> shift) << shift);
      margin = std::min({margin, f[a] - lo, lo + (1 << shift) - f[a]});
    }
    return std::max(margin, 0.0);
  }

  double distance_to_domain(const Vec3& x) const {
    double d2 = 0.0;
    for (int a = 0; a < axes(); ++a) {
      const double lo = origin_[a], hi = origin_[a] + dims_[a] * cell_;
      const double out = std::max({lo - x[a], x[a] - hi, 0.0});
      d2 += out * out;
    }
    return std::sqrt(d2);
  }

  bool inside(const Vec3& center, double radius) const {
    for (int a = 0; a < axes(); ++a)
      if (!(center[a] - radius >= origin_[a] && center[a] + radius < origin_[a] + dims_[a] * cell_))
        return false;
    return true;
  }

  void start(const Vec3& center, double radius) {
    center_ = center;
    cells_ = 64;
    while (cells_ < kMaxCells && cells_ * cell_ < 2.0 * radius + 4.0 * cell_) cells_ *= 2;
    rebuild();
  }

  //! Doubles the domain about its centre and files every particle again.
  void grow() {
    if (cells_ >= kMaxCells)
      throw GrowthError("the structure reaches beyond " + std::to_string(cells_ / 2) +
                        " grid cells from the seeds' centre, more than the grid index holds;"
                        " use the kdtree index");
    cells_ *= 2;
    rebuild();
  }

  void rebuild() {
    const int depth = planar_ ? 1 : cells_;
    dims_ = {cells_, cells_, depth};
    origin_ = center_ - Vec3::Constant(0.5 * cells_ * cell_);
    if (planar_) origin_.z() = center_.z() - 0.5 * cell_;
    block_dims_ = {cells_ >> kBlockShift, cells_ >> kBlockShift,
                   planar_ ? 1 : cells_ >> kBlockShift};
    block_of_.assign(static_cast<std::size_t>(block_dims_[0]) * block_dims_[1] * block_dims_[2], -1);
    heads_.clear();
    levels_.clear();
    for (int shift = 1; (cells_ >> shift) >= 4; ++shift) {
      Level level{shift, {cells_ >> shift, cells_ >> shift, planar_ ? 1 : cells_ >> shift}, {}};
      const std::size_t words =
          (static_cast<std::size_t>(level.dims[0]) * level.dims[1] * level.dims[2] + 63) / 64;
      if (words > kMaxLevelWords) continue;
      level.bits.assign(words, 0);
      levels_.push_back(std::move(level));
    }
    for (std::int32_t id = 0; id < inserted_; ++id) place(id);
  }

  std::array<int, 3> cell_of(const Vec3& p) const {
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < axes(); ++a)
      c[a] = std::min(static_cast<int>((p[a] - origin_[a]) / cell_), dims_[a] - 1);
    return c;
  }

  int block_cells() const { return planar_ ? 64 : 512; }

  std::size_t slot_of(const std::array<int, 3>& c) const {
    const std::size_t block =
        (static_cast<std::size_t>(c[2] >> kBlockShift) * block_dims_[1] + (c[1] >> kBlockShift)) *
            block_dims_[0] +
        (c[0] >> kBlockShift);
    const std::int32_t b = block_of_[block];
    if (b < 0) return std::numeric_limits<std::size_t>::max();
    const int m = (1 << kBlockShift) - 1;
    return static_cast<std::size_t>(b) * block_cells() +
           (((c[2] & m) << kBlockShift | (c[1] & m)) << kBlockShift | (c[0] & m));
  }

  void place(std::int32_t id) {
    const std::array<int, 3> c = cell_of(particles_[static_cast<std::size_t>(id)].position);
    std::size_t slot = slot_of(c);
    if (slot == std::numeric_limits<std::size_t>::max()) {
      const std::size_t block =
          (static_cast<std::size_t>(c[2] >> kBlockShift) * block_dims_[1] + (c[1] >> kBlockShift)) *
              block_dims_[0] +
          (c[0] >> kBlockShift);
      block_of_[block] = static_cast<std::int32_t>(heads_.size() / block_cells());
      heads_.resize(heads_.size() + block_cells(), -1);
      slot = slot_of(c);
    }
    next_[static_cast<std::size_t>(id)] = heads_[slot];
    heads_[slot] = id;
    for (Level& level : levels_) level.mark(c, planar_);
  }

  template <class Visit>
  void for_each_cell(int x0, int x1, int y0, int y1, int z0, int z1, Visit&& visit) const {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), z0 = std::max(z0, 0);
    x1 = std::min(x1, dims_[0] - 1), y1 = std::min(y1, dims_[1] - 1), z1 = std::min(z1, dims_[2] - 1);
    for (int z = z0; z <= z1; ++z)
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const std::size_t slot = slot_of({x, y, z});
          if (slot == std::numeric_limits<std::size_t>::max()) continue;
          for (std::int32_t id = heads_[slot]; id >= 0; id = next_[static_cast<std::size_t>(id)])
            visit(id);
        }
  }

  const std::vector<Particle>& particles_;
  double cell_;  // fine cell edge: two spacings, so 27 cells hold every particle within 2 spacings
  bool planar_;
  Vec3 center_ = Vec3::Zero();
  Vec3 origin_ = Vec3::Zero();
  int cells_ = 0;  // fine cells a side (z is one cell when planar); 0 until the first use
  std::array<int, 3> dims_{0, 0, 0};
  std::array<int, 3> block_dims_{0, 0, 0};
  std::vector<std::int32_t> block_of_;  // block table: block number, or -1 while empty
  std::vector<std::int32_t> heads_;     // per cell of every block: first particle, or -1
  std::vector<std::int32_t> next_;      // per particle: next particle in its cell, or -1
  std::vector<Level> levels_;           // finest first
  std::int32_t inserted_ = 0;
};

}  // namespace dla
