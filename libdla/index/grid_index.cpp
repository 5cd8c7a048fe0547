// The grid index's inserts, its growth and nearest(): what runs once a particle or once a far
// query, out of the header; the probes a walker makes every step stay inline there.

#include "dla/index/grid_index.h"

#include "index/gap_rows.h"

namespace dla {

void GridIndex::start(const Vec3& center, double radius) {
  center_ = center;
  cells_ = 32;
  while (cells_ < max_cells_ && cells_ * cell_ < 2.0 * (radius + (kGapReach + 1) * cell_)) cells_ *= 2;
  lay_out();
}

void GridIndex::grow() {
  if (cells_ >= max_cells_)
    throw GrowthError("the structure reaches beyond " + std::to_string(cells_ / 2) + " grid cells (" +
                      std::to_string(4 * (cells_ / 2)) + " spacings) from the seeds' centre, more than the "
                      "grid index holds; use the kdtree index");
  const HugePageVector<std::int32_t*> old_heads = std::move(heads_of_);
  const HugePageVector<std::uint8_t*> old_gaps = std::move(gaps_of_);
  const Cell old_dims = block_dims_;
  const int shift = (cells_ / 2) >> kBlockShift;  // blocks the corner moves by, per axis
  cells_ *= 2;
  lay_out();
  for (int z = 0; z < old_dims[2]; ++z)
    for (int y = 0; y < old_dims[1]; ++y)
      for (int x = 0; x < old_dims[0]; ++x) {
        const std::size_t old_index = (static_cast<std::size_t>(z) * old_dims[1] + y) * old_dims[0] + x;
        const Cell first{(x + shift) << kBlockShift, (y + shift) << kBlockShift,
                         planar_ ? 0 : (z + shift) << kBlockShift};
        gaps_of_[block_of(first)] = old_gaps[old_index];
        heads_of_[block_of(first)] = old_heads[old_index];
        if (!old_heads[old_index]) continue;
        mark_occupied(first, old_heads[old_index]);
        if (distance_maps_) lower_far(first);
      }
}

void GridIndex::lay_out() {
  dims_ = {cells_, cells_, planar_ ? 1 : cells_};
  origin_ = center_ - Vec3::Constant(0.5 * cells_ * cell_);
  if (planar_) origin_.z() = center_.z() - 0.5 * cell_;
  block_dims_ = {cells_ >> kBlockShift, cells_ >> kBlockShift, planar_ ? 1 : cells_ >> kBlockShift};
  heads_of_.assign(static_cast<std::size_t>(block_dims_[0]) * block_dims_[1] * block_dims_[2], nullptr);
  gaps_of_.assign(heads_of_.size(), nullptr);
  occupied_.reset(dims_);
  const int nodes = (cells_ >> kNodeShift) + 1;  // corners of the cells at both ends
  node_dims_ = {nodes, nodes, planar_ ? 1 : nodes};
  nodes_.assign(static_cast<std::size_t>(nodes) * nodes * node_dims_[2], static_cast<std::uint8_t>(node_cap_));
  far_.assign(heads_of_.size(), static_cast<std::uint8_t>(kFarCap));
  levels_.clear();
  for (int shift = 1; (cells_ >> shift) >= 4; ++shift) {
    const Cell dims{cells_ >> shift, cells_ >> shift, planar_ ? 1 : cells_ >> shift};
    if (static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] / 64 > kMaxLevelWords) continue;
    Level level{shift, {}, {}};
    level.near.reset(dims);
    level.held.reset(dims);
    levels_.push_back(std::move(level));
  }
}

void GridIndex::mark_occupied(const Cell& first, const std::int32_t* heads) {
  const int side = 1 << kBlockShift;
  for (int z = 0; z < (planar_ ? 1 : side); ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const Cell c{first[0] + x, first[1] + y, first[2] + z};
        if (heads[cell_in_block(c)] < 0) continue;
        occupied_.set(c);
        for (Level& level : levels_) level.mark(c, planar_);
        if (distance_maps_) lower_nodes(c);
      }
}

bool GridIndex::place(std::int32_t id) {
  const Vec3& p = position(id);
  const Cell c = cell_of(p);
  const bool opens_block = heads_of_[block_of(c)] == nullptr;  // only place() allocates a block
  std::int32_t& head = heads_at(c)[cell_in_block(c)];
  const bool opens = head < 0;
  store(next_[static_cast<std::size_t>(id)], head);
  store_release(head, id);
  if (distance_maps_) lower_gaps(p, c);
  if (!opens) return false;  // the bits, the pyramid, the nodes and the far map know the cell
  occupied_.set(c);
  for (Level& level : levels_) level.mark(c, planar_);
  if (distance_maps_) lower_nodes(c);
  if (distance_maps_ && opens_block) lower_far(c);
  return true;
}

void GridIndex::lower_gaps(const Vec3& p, const Cell& home) {
  static_assert(kBlockShift == 3, "detail::may_lower_gaps reads a block's row of 8 cells");
  constexpr int span = 2 * kGapReach + 1;
  constexpr int m = (1 << kBlockShift) - 1;
  std::array<std::array<double, span>, 3> axis_gap2{};  // [axis][offset + reach], in units²
  // Along x, the same in floats for every cell of the block rows the update meets, from
  // home - kGapReach - m on; infinite beyond the reach, where no cell is lowered.
  std::array<float, 2 * (kGapReach + m) + 2> axis_x;
  axis_x.fill(std::numeric_limits<float>::infinity());
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < axes(); ++a) {
    lo[a] = std::max(home[a] - kGapReach, 0);
    hi[a] = std::min(home[a] + kGapReach, dims_[a] - 1);
    for (int n = lo[a]; n <= hi[a]; ++n) {
      const double from = origin_[a] + n * cell_;
      const double gap = std::max({from - p[a], p[a] - from - cell_, 0.0}) * (kGapUnits / cell_);
      axis_gap2[a][n - home[a] + kGapReach] = gap * gap;
      if (a == 0) axis_x[n - home[0] + kGapReach + m] = static_cast<float>(gap * gap);
    }
  }
  constexpr double far2 = static_cast<double>(kFarGap) * kFarGap;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y) {
      const double yz2 = axis_gap2[1][y - home[1] + kGapReach] + axis_gap2[2][z - home[2] + kGapReach];
      if (yz2 >= far2) continue;
      // A block's row at a time: the cells that may be lowered, from floats, then the exact test.
      for (int x = lo[0] & ~m; x <= hi[0]; x += m + 1) {
        std::uint8_t* row = gaps_at({x, y, z}) + cell_in_block({x, y, z});
        const float* along = &axis_x[static_cast<std::size_t>(x - home[0] + kGapReach + m)];
        for (unsigned cells = detail::may_lower_gaps(row, static_cast<float>(yz2), along); cells; cells &= cells - 1) {
          const int i = __builtin_ctz(cells);
          const double d2 = yz2 + axis_gap2[0][x + i - home[0] + kGapReach];
          std::uint8_t& gap = row[i];
          // Rounded down (and a hair below, against sqrt's last bit): a bound, never above.
          if (d2 < static_cast<double>(gap) * gap) store(gap, static_cast<std::uint8_t>(std::sqrt(d2) * (1.0 - 1e-12)));
        }
      }
    }
}

void GridIndex::lower_far(const Cell& c) {
  Cell low{0, 0, 0}, high{0, 0, 0}, home{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    home[a] = c[a] >> kBlockShift;
    low[a] = std::max(home[a] - kFarReach, 0);
    high[a] = std::min(home[a] + kFarReach, block_dims_[a] - 1);
  }
  const auto gap2 = [](int from, int to) {
    const int gap = std::max(std::abs(to - from) - 1, 0);
    return gap * gap;
  };
  for (int z = low[2]; z <= high[2]; ++z)
    for (int y = low[1]; y <= high[1]; ++y) {
      const int yz2 = gap2(home[1], y) + gap2(home[2], z);
      if (yz2 >= kFarCap) continue;
      std::uint8_t* row = &far_[(static_cast<std::size_t>(z) * block_dims_[1] + y) * block_dims_[0]];
      for (int x = low[0]; x <= high[0]; ++x) {
        const int value = yz2 + gap2(home[0], x);
        if (value < row[x]) store(row[x], static_cast<std::uint8_t>(value));
      }
    }
}

void GridIndex::lower_nodes(const Cell& c) {
  constexpr int most = 3 * (kMostNodeReach + 1) * (kMostNodeReach + 1);  // squared distances, in cells²
  static const std::array<std::uint8_t, most> units = [] {
    std::array<std::uint8_t, most> table{};
    for (int d2 = 0; d2 < most; ++d2)
      table[d2] = static_cast<std::uint8_t>(std::min(255.0, std::floor(std::sqrt(d2) * kNodeUnits)));
    return table;
  }();
  Cell low{0, 0, 0}, high{0, 0, 0};
  for (int a = 0; a < axes(); ++a) {
    low[a] = std::max((c[a] - node_reach_ + (1 << kNodeShift) - 1) >> kNodeShift, 0);
    high[a] = std::min((c[a] + 1 + node_reach_) >> kNodeShift, node_dims_[a] - 1);
  }
  // Whole cells along each axis between a node and the cell's box.
  const auto gap = [](int cell, int node) { return std::max({cell - node, node - cell - 1, 0}); };
  for (int z = low[2]; z <= high[2]; ++z) {
    const int gz = planar_ ? 0 : gap(c[2], z << kNodeShift);
    for (int y = low[1]; y <= high[1]; ++y) {
      const int gy = gap(c[1], y << kNodeShift), gyz2 = gy * gy + gz * gz;
      if (gyz2 >= node_reach_ * node_reach_) continue;
      std::uint8_t* row = &nodes_[node_index({0, y, z})];
      for (int x = low[0]; x <= high[0]; ++x) {
        const int gx = gap(c[0], x << kNodeShift);
        const std::uint8_t value = std::min(units[static_cast<std::size_t>(gyz2 + gx * gx)], node_cap_);
        if (value < row[x]) store(row[x], value);
      }
    }
  }
}

Probe GridIndex::nearest(const Vec3& x) const {
  if (cells_ == 0) return {};
  double best2 = std::numeric_limits<double>::infinity();
  std::int32_t best = -1;
  const auto visit = [&](const Cell& cell) {
    for_each_in_cell(cell, [&](std::int32_t id) {
      const double d2 = (position(id) - x).squaredNorm();
      if (d2 < best2 || (d2 == best2 && id < best)) best2 = d2, best = id;
    });
  };
  const auto found = [&] { return Probe{best, std::sqrt(best2)}; };
  std::array<double, 3> f{0.0, 0.0, 0.0};
  Cell c{0, 0, 0};
  bool inside_domain = true;
  for (int a = 0; a < axes(); ++a) {
    f[a] = (x[a] - origin_[a]) / cell_;
    inside_domain = inside_domain && f[a] >= 0.0 && f[a] < dims_[a];
    c[a] = static_cast<int>(f[a]);
  }
  if (inside_domain) {
    // Shell k: the cells k cells from x's along some axis and at most k along the others.
    const double margin = face_margin(f, c, 0);
    const int depth = planar_ ? 0 : 1;
    // Squared gap along each axis from x to the cells at offsets -k..k: [axis][offset + k].
    std::array<std::array<double, 2 * kMostShells + 1>, 3> gap2{};
    for (int a = 0; a < axes(); ++a)
      for (int o = -kMostShells; o <= kMostShells; ++o) {
        const double gap = std::max({static_cast<double>(c[a] + o) - f[a], f[a] - static_cast<double>(c[a] + o + 1), 0.0}) * cell_;
        gap2[a][o + kMostShells] = gap * gap;
      }
    thread_local std::vector<Candidate> shell;
    for (int k = 0; k <= kMostShells && (k <= kNearShells || best >= 0); ++k) {
      shell.clear();
      for (int dz = -k * depth; dz <= k * depth; ++dz) {
        const int z = c[2] + dz;
        if (z < 0 || z >= dims_[2]) continue;
        for (int dy = -k; dy <= k; ++dy) {
          const int y = c[1] + dy;
          const double yz2 = gap2[1][dy + kMostShells] + gap2[2][dz + kMostShells];
          if (y < 0 || y >= dims_[1] || yz2 > best2) continue;
          const bool whole_row = std::abs(dy) == k || std::abs(dz) == k;
          const int x0 = std::max(c[0] - k, 0), x1 = std::min(c[0] + k, dims_[0] - 1);
          for (std::uint64_t row = occupied_.row({x0, y, z}, x1 - x0 + 1); row; row &= row - 1) {
            const int cx = x0 + __builtin_ctzll(row);
            // Cells inside the shell were visited; a cell farther than the best holds none nearer.
            const double cell2 = yz2 + gap2[0][cx - c[0] + kMostShells];
            if ((whole_row || std::abs(cx - c[0]) == k) && cell2 <= best2) shell.push_back({cell2, {cx, y, z}});
          }
        }
      }
      // Nearest cells first: the best found soon rules out the rest.
      std::sort(shell.begin(), shell.end(), [](const Candidate& a, const Candidate& b) { return a.gap2 < b.gap2; });
      for (const Candidate& cell : shell) {
        if (cell.gap2 > best2) break;
        visit(cell.cell);
      }
      const double reach = (k + margin) * cell_;  // every cell beyond shell k is this far
      if (best2 < reach * reach) return found();
    }
  }
  struct Entry {
    double gap2;  // squared distance from x to the cell's box
    int level;    // index in levels_, or -1 for a base cell
    Cell cell;
    bool operator<(const Entry& other) const { return gap2 > other.gap2; }  // a min-heap
  };
  thread_local std::vector<Entry> heap;
  heap.clear();
  const auto push = [&](int level, const Cell& cell) {
    const int shift = level < 0 ? 0 : levels_[static_cast<std::size_t>(level)].shift;
    double gap2 = 0.0;
    for (int a = 0; a < axes(); ++a) {
      const double lo = origin_[a] + static_cast<double>(cell[a] << shift) * cell_;
      const double gap = std::max({lo - x[a], x[a] - lo - static_cast<double>(1 << shift) * cell_, 0.0});
      gap2 += gap * gap;
    }
    if (gap2 > best2) return;
    heap.push_back({gap2, level, cell});
    std::push_heap(heap.begin(), heap.end());
  };
  // The cells of `level` within the cell `parent` of the level above (with no parent, all of
  // them) that may hold a particle.
  const auto push_within = [&](int level, const Entry* parent) {
    const BitGrid& bits = level < 0 ? occupied_ : levels_[static_cast<std::size_t>(level)].held;
    const int shift = level < 0 ? 0 : levels_[static_cast<std::size_t>(level)].shift;
    const int ratio = parent ? levels_[static_cast<std::size_t>(parent->level)].shift - shift : 0;
    Cell lo{0, 0, 0}, hi = {bits.dims[0] - 1, bits.dims[1] - 1, bits.dims[2] - 1};
    for (int a = 0; parent && a < 3; ++a) {
      lo[a] = std::min(parent->cell[a] << ratio, hi[a]);
      hi[a] = std::min(((parent->cell[a] + 1) << ratio) - 1, hi[a]);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int xx = lo[0]; xx <= hi[0]; ++xx)
          if (bits.test({xx, y, z})) push(level, {xx, y, z});
  };
  push_within(static_cast<int>(levels_.size()) - 1, nullptr);
  while (!heap.empty() && heap.front().gap2 <= best2) {
    std::pop_heap(heap.begin(), heap.end());
    const Entry e = heap.back();
    heap.pop_back();
    if (e.level >= 0) push_within(e.level - 1, &e);
    else visit(e.cell);
  }
  return best >= 0 ? found() : Probe{};
}

}  // namespace dla
