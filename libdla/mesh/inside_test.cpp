// Winding numbers by signed crossings of a vertical ray. The 2D edge tests are computed so that
// the two triangles sharing an edge get exactly opposite values, and a tie rule gives a point
// on the edge to exactly one of them: a ray through an edge or a vertex is counted once, never
// twice or not at all. This file is built with -ffp-contract=off so no fused multiply-add
// breaks that symmetry.

#include "dla/mesh/inside_test.h"

#include <algorithm>
#include <array>
#include <limits>

namespace dla {

namespace {

constexpr double kMaxBuckets = 1024.0 * 1024.0;
constexpr double kMaxClearBuckets = 256.0;  // for clear_of_surface()

//! Whether every edge is used as often one way as the other: a closed surface (or several),
//! around which the winding number is the same along every line.
bool is_closed(const TriangleMesh& mesh) {
  std::vector<std::pair<std::uint64_t, int>> edges;  // (the two ends, lower first; +1 or -1)
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = t[k], b = t[(k + 1) % 3];
      edges.emplace_back(a < b ? a << 32 | b : b << 32 | a, a < b ? 1 : -1);
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    int sum = 0;
    std::size_t j = i;
    for (; j < edges.size() && edges[j].first == edges[i].first; ++j) sum += edges[j].second;
    if (sum != 0) return false;
    i = j;
  }
  return true;
}

//! Twice the signed area of (u, v, q) in the xy plane; exactly -orient(v, u, q).
inline double orient(const Vec3& u, const Vec3& v, double qx, double qy) {
  return (u.x() - qx) * (v.y() - qy) - (u.y() - qy) * (v.x() - qx);
}

//! Which of the two directions of an edge owns the points on it (exactly one of them does).
inline bool owns(const Vec3& u, const Vec3& v) {
  return v.y() < u.y() || (v.y() == u.y() && v.x() > u.x());
}

//! +1 or -1 if the vertical line through (qx, qy) crosses triangle (a, b, c) (the sign of the
//! triangle's normal along z), with the crossing's height in z; 0 if it misses.
inline int vertical_crossing(const Vec3& a, Vec3 b, Vec3 c, double qx, double qy, double& z) {
  const double area = orient(a, b, c.x(), c.y());
  if (area == 0.0) return 0;  // seen edge-on: its neighbours count the crossing
  int sign = 1;
  if (area < 0.0) {
    std::swap(b, c);
    sign = -1;
  }
  const double w0 = orient(b, c, qx, qy), w1 = orient(c, a, qx, qy), w2 = orient(a, b, qx, qy);
  const auto in = [](double w, const Vec3& u, const Vec3& v) { return w > 0.0 || (w == 0.0 && owns(u, v)); };
  if (!in(w0, b, c) || !in(w1, c, a) || !in(w2, a, b)) return 0;
  const double sum = w0 + w1 + w2;
  z = (w0 * a.z() + w1 * b.z() + w2 * c.z()) / sum;
  return sign;
}

}  // namespace

InsideTest::InsideTest(const TriangleMesh& mesh, double band, double cell) {
  const Box box = bounding_box(mesh);
  corners_.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (std::uint32_t id : t) corners_.push_back(mesh.vertices[id]);
  const std::size_t triangles = mesh.triangles.size();

  // The voxel grid: the box, a band and a cell wider on every side.
  grid_ = VoxelGrid(box, band + cell, cell);
  const double side = grid_.cell;  // of a cell
  const Vec3& origin = grid_.origin;
  const std::size_t nx = grid_.dims[0], ny = grid_.dims[1];
  const double dims[3] = {static_cast<double>(grid_.dims[0]), static_cast<double>(grid_.dims[1]),
                          static_cast<double>(grid_.dims[2])};

  // Buckets in xy of a cell, or larger so that there are at most about a million: a vertical
  // line then meets few triangles besides those it crosses. Each bucket lists its triangles
  // twice, by falling top and by rising bottom, so that a winding number reads only those that
  // reach above its point, or on a closed mesh those that reach below, whichever are fewer.
  const double columns = dims[0] * dims[1];
  bucket_ = side * std::max(1.0, std::ceil(std::sqrt(columns / kMaxBuckets)));
  bucket_origin_ = origin;
  bucket_dims_[0] = static_cast<int>(std::ceil(dims[0] * side / bucket_));
  bucket_dims_[1] = static_cast<int>(std::ceil(dims[1] * side / bucket_));
  const auto bucket_range = [&](std::size_t t, int axis) {
    const double a = corners_[3 * t][axis], b = corners_[3 * t + 1][axis], c = corners_[3 * t + 2][axis];
    const double lo_f = (std::min({a, b, c}) - bucket_origin_[axis]) / bucket_;
    const double hi_f = (std::max({a, b, c}) - bucket_origin_[axis]) / bucket_;
    return std::pair<int, int>{std::clamp(static_cast<int>(std::floor(lo_f)), 0, bucket_dims_[axis] - 1),
                               std::clamp(static_cast<int>(std::floor(hi_f)), 0, bucket_dims_[axis] - 1)};
  };
  // A crossing's height is a weighted mean of the corners' heights: it can pass the highest or
  // lowest corner by rounding, never by a billionth of the heights.
  std::vector<double> top(triangles), bottom(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const double a = corners_[3 * t].z(), b = corners_[3 * t + 1].z(), c = corners_[3 * t + 2].z();
    const double margin = 1e-9 * std::max({std::abs(a), std::abs(b), std::abs(c)});
    top[t] = std::max({a, b, c}) + margin;
    bottom[t] = std::min({a, b, c}) - margin;
  }
  // The buckets a triangle's xy shadow touches, row by row: a long slanted triangle (a fan of a
  // CAD model's cap) would claim many more by its bounding box. Each row's span is the shadow's
  // within the row's strip, from where the edges enter and leave it, widened by far more than
  // rounding so that no bucket a vertical line crosses the triangle in is missed.
  const auto for_each_bucket = [&](std::uint32_t t, auto&& visit) {
    const Vec3* corner = &corners_[3 * t];
    const auto [x0, x1] = bucket_range(t, 0);
    const auto [y0, y1] = bucket_range(t, 1);
    const double widen = 1e-9 * (bucket_ + corner[0].cwiseAbs().maxCoeff() + corner[1].cwiseAbs().maxCoeff() +
                                 corner[2].cwiseAbs().maxCoeff() + bucket_origin_.cwiseAbs().maxCoeff());
    for (int y = y0; y <= y1; ++y) {
      const double strip_lo = bucket_origin_.y() + y * bucket_ - widen, strip_hi = strip_lo + bucket_ + 2 * widen;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int e = 0; e < 3; ++e) {
        const Vec3 &u = corner[e], &v = corner[(e + 1) % 3];
        const double e_lo = std::max(strip_lo, std::min(u.y(), v.y())), e_hi = std::min(strip_hi, std::max(u.y(), v.y()));
        if (e_lo > e_hi) continue;  // the edge misses the strip
        for (const double at : {e_lo, e_hi}) {
          const double s = u.y() == v.y() ? 0.0 : std::clamp((at - u.y()) / (v.y() - u.y()), 0.0, 1.0);
          const double x = u.y() == v.y() ? std::min(u.x(), v.x()) : u.x() + s * (v.x() - u.x());
          lo = std::min(lo, x);
          hi = std::max(hi, u.y() == v.y() ? std::max(u.x(), v.x()) : x);
        }
      }
      if (!(lo <= hi)) continue;
      const int from = std::max(x0, static_cast<int>(std::floor((lo - widen - bucket_origin_.x()) / bucket_)));
      const int to = std::min(x1, static_cast<int>(std::floor((hi + widen - bucket_origin_.x()) / bucket_)));
      for (int x = from; x <= to; ++x) visit(static_cast<std::size_t>(y) * bucket_dims_[0] + x);
    }
  };
  bucket_start_.assign(static_cast<std::size_t>(bucket_dims_[0]) * bucket_dims_[1] + 1, 0);
  for (std::uint32_t t = 0; t < triangles; ++t) for_each_bucket(t, [&](std::size_t b) { ++bucket_start_[b + 1]; });
  for (std::size_t b = 1; b < bucket_start_.size(); ++b) bucket_start_[b] += bucket_start_[b - 1];
  for (const bool falling : {true, false}) {
    std::vector<std::uint32_t> order(triangles);
    for (std::uint32_t t = 0; t < triangles; ++t) order[t] = t;
    const std::vector<double>& height = falling ? top : bottom;
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t s, std::uint32_t t) { return falling ? height[s] > height[t] : height[s] < height[t]; });
    ByHeight& list = falling ? from_top_ : from_bottom_;
    list.triangles.resize(bucket_start_.back());
    list.heights.resize(bucket_start_.back());
    std::vector<std::uint32_t> fill(bucket_start_.begin(), bucket_start_.end() - 1);
    for (const std::uint32_t t : order)
      for_each_bucket(t, [&](std::size_t b) {
        list.triangles[fill[b]] = t;
        list.heights[fill[b]++] = height[t];
      });
  }
  closed_ = is_closed(mesh);

  const std::vector<bool> inside = inside_centres(grid_);
  cells_.resize(inside.size());
  for (std::size_t v = 0; v < cells_.size(); ++v) cells_[v] = inside[v] ? Region::inside : Region::outside;

  // The band: every cell that may hold a point within `band` of a triangle. The plane test
  // keeps large slanted triangles from claiming their whole bounding box.
  const double reach = band + 0.5 * std::sqrt(3.0) * side;
  for (std::size_t t = 0; t < triangles; ++t) {
    const Vec3 &a = corners_[3 * t], &b = corners_[3 * t + 1], &c = corners_[3 * t + 2];
    const Vec3 normal = (b - a).cross(c - a).normalized();
    std::array<std::size_t, 3> from{}, to{};
    for (int axis = 0; axis < 3; ++axis) {
      const double l = (std::min({a[axis], b[axis], c[axis]}) - band - origin[axis]) / side;
      const double h = (std::max({a[axis], b[axis], c[axis]}) + band - origin[axis]) / side;
      from[axis] = static_cast<std::size_t>(std::clamp(std::floor(l), 0.0, dims[axis] - 1));
      to[axis] = static_cast<std::size_t>(std::clamp(std::floor(h), 0.0, dims[axis] - 1));
    }
    for (std::size_t k = from[2]; k <= to[2]; ++k)
      for (std::size_t j = from[1]; j <= to[1]; ++j)
        for (std::size_t i = from[0]; i <= to[0]; ++i) {
          const Vec3 center = grid_.center(i, j, k);
          if (normal.allFinite() && std::abs(normal.dot(center - a)) > reach) continue;
          cells_[(k * ny + j) * nx + i] = Region::surface;
        }
  }
}

VoxelGrid::VoxelGrid(const Box& box, double margin, double min_cell) {
  const Vec3 lo = box.min.array() - margin, hi = box.max.array() + margin;
  const Vec3 extent = hi - lo;
  constexpr double max_cells = 16.0 * 1024 * 1024;
  cell = std::max(min_cell, std::cbrt(extent.prod() / max_cells));
  origin = lo;
  for (int a = 0; a < 3; ++a) {
    limits_[a] = std::max(1.0, std::ceil(extent[a] / cell));
    dims[a] = static_cast<std::size_t>(limits_[a]);
  }
}

std::vector<bool> InsideTest::inside_centres(const VoxelGrid& grid) const {
  // Every cell centre's winding number, a column at a time: the crossings of the column's
  // vertical line, from the top down.
  const Vec3& origin = grid.origin;
  const double cell = grid.cell;
  const std::size_t nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  std::vector<bool> inside(nx * ny * nz, false);
  struct Crossing {
    std::size_t column;
    double z;
    int sign;
  };
  std::vector<Crossing> crossings;
  for (std::size_t t = 0; 3 * t < corners_.size(); ++t) {
    const Vec3 &a = corners_[3 * t], &b = corners_[3 * t + 1], &c = corners_[3 * t + 2];
    const double x_lo = std::min({a.x(), b.x(), c.x()}), x_hi = std::max({a.x(), b.x(), c.x()});
    const double y_lo = std::min({a.y(), b.y(), c.y()}), y_hi = std::max({a.y(), b.y(), c.y()});
    const std::size_t i0 = static_cast<std::size_t>(std::max(0.0, std::ceil((x_lo - origin.x()) / cell - 0.5)));
    const std::size_t j0 = static_cast<std::size_t>(std::max(0.0, std::ceil((y_lo - origin.y()) / cell - 0.5)));
    for (std::size_t j = j0; j < ny; ++j) {
      const double y = origin.y() + (static_cast<double>(j) + 0.5) * cell;
      if (y > y_hi) break;
      for (std::size_t i = i0; i < nx; ++i) {
        const double x = origin.x() + (static_cast<double>(i) + 0.5) * cell;
        if (x > x_hi) break;
        double z;
        if (const int sign = vertical_crossing(a, b, c, x, y, z)) crossings.push_back({j * nx + i, z, sign});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end(), [](const Crossing& p, const Crossing& q) {
    return p.column != q.column ? p.column < q.column : p.z > q.z;
  });
  for (std::size_t first = 0; first < crossings.size();) {
    std::size_t last = first;
    while (last < crossings.size() && crossings[last].column == crossings[first].column) ++last;
    const std::size_t column = crossings[first].column;
    int winding = 0;
    std::size_t next = first;
    for (std::size_t k = nz; k-- > 0;) {
      const double z = origin.z() + (static_cast<double>(k) + 0.5) * cell;
      while (next < last && crossings[next].z > z) winding += crossings[next++].sign;
      inside[k * nx * ny + column] = winding > 0;
    }
    first = last;
  }
  return inside;
}

namespace {

//! Whether the corners q lie more than `margin` to one side of the plane through p with unit
//! normal n.
bool plane_separates(const Vec3& p, const Vec3& n, const Vec3* q, double margin) {
  const double d0 = n.dot(q[0] - p), d1 = n.dot(q[1] - p), d2 = n.dot(q[2] - p);
  return (d0 > margin && d1 > margin && d2 > margin) || (d0 < -margin && d1 < -margin && d2 < -margin);
}

}  // namespace

bool InsideTest::clear_of_surface(const Vec3& a, const Vec3& b, const Vec3& c, double margin) const {
  const Vec3 normal = (b - a).cross(c - a).normalized();
  if (!normal.allFinite() || !(margin >= 0.0)) return false;
  const Vec3 corners[3] = {a, b, c};
  const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - margin, hi = a.cwiseMax(b).cwiseMax(c).array() + margin;
  // A triangle that comes within the margin has its shadow under the box's, in the buckets
  // there, and its top above the box's bottom.
  const auto bucket = [&](double v, int axis) {
    const double f = std::floor((v - bucket_origin_[axis]) / bucket_);
    return static_cast<int>(std::clamp(f, 0.0, static_cast<double>(bucket_dims_[axis] - 1)));
  };
  const int x0 = bucket(lo.x(), 0), x1 = bucket(hi.x(), 0), y0 = bucket(lo.y(), 1), y1 = bucket(hi.y(), 1);
  // A triangle over many buckets (a CAD model's long cap, at a fine spacing) would cost more
  // scans than the inside tests it saves.
  if (static_cast<double>(x1 - x0 + 1) * (y1 - y0 + 1) > kMaxClearBuckets) return false;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t b_index = static_cast<std::size_t>(y) * bucket_dims_[0] + x;
      for (std::uint32_t k = bucket_start_[b_index]; k < bucket_start_[b_index + 1]; ++k) {
        if (from_top_.heights[k] < lo.z()) break;  // by falling top: this and the rest are below
        const Vec3* q = &corners_[3 * from_top_.triangles[k]];
        const Vec3 q_lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]), q_hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
        if ((q_lo.array() > hi.array()).any() || (q_hi.array() < lo.array()).any()) continue;
        if (plane_separates(a, normal, q, margin)) continue;
        const Vec3 q_normal = (q[1] - q[0]).cross(q[2] - q[0]).normalized();
        if (q_normal.allFinite() && plane_separates(q[0], q_normal, corners, margin)) continue;
        return false;
      }
    }
  return true;
}

int InsideTest::winding_number(const Vec3& p) const {
  const double fx = (p.x() - bucket_origin_.x()) / bucket_, fy = (p.y() - bucket_origin_.y()) / bucket_;
  if (!(fx >= 0.0 && fy >= 0.0 && fx < bucket_dims_[0] && fy < bucket_dims_[1])) return 0;
  const std::size_t b = static_cast<std::size_t>(fy) * bucket_dims_[0] + static_cast<std::size_t>(fx);
  const std::uint32_t first = bucket_start_[b], last = bucket_start_[b + 1];
  const double* tops = from_top_.heights.data();
  const double* bottoms = from_bottom_.heights.data();
  const std::uint32_t above = static_cast<std::uint32_t>(
      std::partition_point(tops + first, tops + last, [&](double h) { return h > p.z(); }) - tops);
  int winding = 0;
  if (closed_) {
    // On a closed mesh every vertical line crosses as much one way as the other, so the
    // crossings at and below p, counted the other way, give the same number.
    const std::uint32_t below = static_cast<std::uint32_t>(
        std::partition_point(bottoms + first, bottoms + last, [&](double h) { return h <= p.z(); }) - bottoms);
    if (below - first < above - first) {
      for (std::uint32_t k = first; k < below; ++k) {
        const std::size_t t = from_bottom_.triangles[k];
        double z;
        const int sign = vertical_crossing(corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2], p.x(), p.y(), z);
        if (sign && z <= p.z()) winding -= sign;
      }
      return winding;
    }
  }
  for (std::uint32_t k = first; k < above; ++k) {
    const std::size_t t = from_top_.triangles[k];
    double z;
    const int sign = vertical_crossing(corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2], p.x(), p.y(), z);
    if (sign && z > p.z()) winding += sign;
  }
  return winding;
}

}  // namespace dla
