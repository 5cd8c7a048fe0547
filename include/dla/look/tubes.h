#pragma once
//! \file tubes.h
//! The structure as a triangle mesh: one closed tube per strand (strands.h), swept along the
//! strand with rotation-minimising frames so it does not twist, capped at both ends. A strand
//! that leaves a branch point starts inside its parent's tube, so branches join without a gap.
//! Then a tube per link (links.h), rounded at both ends inside the tubes it joins.
//! Every vertex has texture coordinates and a tangent, for tiling textures and normal maps.
//! The glTF and OBJ writers stream these pieces. See docs/look.md.

#include "dla/look/attributes.h"
#include "dla/look/strands.h"
#include "dla/core/option_description.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace dla {

struct TubeOptions {
  int sides = 8;           //!< vertices around a tube, in [3, 64]
  double tolerance = 0.0;  //!< spacings, in [0, 10]: a strand's point is left out where the tube
                           //!< without it stays within this of its centre and radius; 0 keeps all
  int min_branch = 1;      //!< a branch (a strand and all that grows from it) of fewer
                           //!< particles gets no tube: twigs go first, in [1, 1000]; 1 keeps all
  double uv_scale = 0.0;   //!< scene units of strand per unit of the texture's v: 0, or in
                           //!< [1e-9, 1e9]; 0 takes the base circumference (2π times the thickest
                           //!< tube's radius), so a square texture keeps its aspect on the trunk
};

//! The tube meshes' resolution, described once (option_description.h).
inline const OptionTable<TubeOptions>& tube_option_table() {
  using O = TubeOptions;
  static const OptionTable<O> table{
      integer("tube_sides", &O::sides, closed(3, 64), "", "Look", "glb, obj: vertices around a tube"),
      real("tube_tolerance", &O::tolerance, closed(0, 10), "spacings", "Look",
           "glb, obj: leave out strand points the tube passes within this of"),
      integer("tube_min_branch", &O::min_branch, closed(1, 1000), "particles", "Look",
              "glb, obj: leave out branches of fewer particles (counting all that grow from them)"),
      real("uv_scale", &O::uv_scale, closed(1e-9, 1e9), "scene units", "Look",
           "glb, obj: strand length per unit of the texture's v", SpecialValue{0, "the base circumference"}),
  };
  return table;
}

inline void validate(const TubeOptions& options) { require_in_ranges(tube_option_table(), options); }

//! One strand's tube: vertices with normals, texture coordinates and tangents, each tied to
//! the particle whose attributes it carries, and outward-facing triangles of local vertex
//! indices. A ring's last vertex repeats its first at u = 1 (the seam), so the tube is closed
//! by position; by index it is open along the seam.
struct TubePiece {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;  //!< unit length
  //! u runs once around the tube, 0 to 1 counter-clockwise seen from ahead; v runs along the
  //! strand from its seed in `uv_scale`s, and a branch's v goes on from its parent's at the joint.
  std::vector<Eigen::Vector2f> uvs;
  //! glTF's: xyz the unit direction of rising u, orthogonal to the normal; w = 1, so the
  //! normal × tangent runs the way v rises.
  std::vector<Eigen::Vector4f> tangents;
  std::vector<std::int32_t> particles;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  void clear() {
    positions.clear();
    normals.clear();
    uvs.clear();
    tangents.clear();
    particles.clear();
    triangles.clear();
  }
};

//! A tube with `rings` rings of `sides` + 1 vertices (the seam's twice), a centre vertex closing
//! its start and a rounded tip (one more ring and an apex).
inline std::size_t tube_vertices(std::size_t rings, int sides) {
  return (rings + 1) * (static_cast<std::size_t>(sides) + 1) + 2;
}
inline std::size_t tube_triangles(std::size_t rings, int sides) { return 2 * (rings + 1) * static_cast<std::size_t>(sides); }

namespace detail {

//! The strand's points that the tube keeps (positions in `strand`): the ends always; an inner
//! point only where leaving it out would move the tube's axis or radius by more than `tolerance`.
inline void kept_points(const Cluster& cluster, const std::vector<float>& radii, const Strand& strand,
                        double tolerance, std::vector<std::size_t>& kept) {
  kept.clear();
  kept.push_back(0);
  const std::size_t last = strand.size() - 1;
  if (tolerance <= 0.0) {
    for (std::size_t k = 1; k <= last; ++k) kept.push_back(k);
    return;
  }
  constexpr std::size_t kWindow = 64;  // the most points one segment may stand for
  const auto at = [&](std::size_t k) -> const Vec3& { return cluster.particles[static_cast<std::size_t>(strand[k])].position; };
  const auto radius = [&](std::size_t k) { return radii[static_cast<std::size_t>(strand[k])] * cluster.spacing; };
  std::size_t anchor = 0;
  while (anchor < last) {
    std::size_t reach = anchor + 1;
    for (std::size_t j = anchor + 2; j <= last && j - anchor <= kWindow; ++j) {
      const Vec3 axis = at(j) - at(anchor);
      const double length2 = axis.squaredNorm();
      bool close = true;
      for (std::size_t k = anchor + 1; k < j && close; ++k) {
        const double t = length2 > 0 ? std::clamp((at(k) - at(anchor)).dot(axis) / length2, 0.0, 1.0) : 0.0;
        const double off = (at(anchor) + t * axis - at(k)).norm();
        const double r = radius(anchor) + t * (radius(j) - radius(anchor));
        close = off <= tolerance && std::abs(r - radius(k)) <= tolerance;
      }
      if (!close) break;
      reach = j;
    }
    kept.push_back(reach);
    anchor = reach;
  }
}

}  // namespace detail

//! The texture's v along the strands, worked out once for any number of walks of the tubes.
struct TubeTexture {
  double scale = 1.0;     //!< scene units of strand per unit of v
  std::vector<double> v;  //!< v at each particle: the length of its path from its seed, over `scale`
};

//! The texture of the tubes with branch radii `radii` (spacings) and TubeOptions::uv_scale
//! `uv_scale`: for 0, `scale` is the base circumference (2π times the thickest radius).
inline TubeTexture tube_texture(const Cluster& cluster, const std::vector<float>& radii, double uv_scale) {
  TubeTexture texture;
  if (uv_scale > 0.0) {
    texture.scale = uv_scale;
  } else {
    float thickest = 0.0f;
    for (const float r : radii) thickest = std::max(thickest, r);
    const double circumference = 2.0 * 3.14159265358979323846 * static_cast<double>(thickest) * cluster.spacing;
    texture.scale = circumference > 0.0 ? circumference : cluster.spacing;
  }
  const std::vector<Particle>& ps = cluster.particles;
  texture.v.assign(ps.size(), 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i)  // a parent attaches before its children
    if (ps[i].parent >= 0) {
      const auto parent = static_cast<std::size_t>(ps[i].parent);
      texture.v[i] = texture.v[parent] + (ps[i].position - ps[parent].position).norm() / texture.scale;
    }
  return texture;
}

//! A link's tube: a ring about each end and a rounded cap beyond it.
inline std::size_t link_tube_vertices(int sides) { return 4 * (static_cast<std::size_t>(sides) + 1) + 2; }
inline std::size_t link_tube_triangles(int sides) { return 8 * static_cast<std::size_t>(sides); }

//! Calls visit(const TubePiece&) for the tube of each strand of two or more particles, in
//! strand order (strands.h, from the attributes' links), then for each link's tube; `radii` are
//! the branch radii (Look::radii) in spacings, `texture` the tube_texture of them (whose
//! scale overrides `options.uv_scale`). A seed with no child has no tube, and a link to a
//! branch `min_branch` prunes has none.
template <class Visit>
void for_each_tube(const Cluster& cluster, const Attributes& attributes, const std::vector<float>& radii,
                   const TubeTexture& texture, const TubeOptions& options, Visit&& visit) {
  validate(options);
  const int sides = options.sides;
  const double tolerance = options.tolerance * cluster.spacing;
  std::vector<double> cosines(static_cast<std::size_t>(sides)), sines(static_cast<std::size_t>(sides));
  for (int s = 0; s < sides; ++s) {
    const double angle = 2.0 * 3.14159265358979323846 * s / sides;
    cosines[static_cast<std::size_t>(s)] = std::cos(angle);
    sines[static_cast<std::size_t>(s)] = std::sin(angle);
  }
  const double v_per_length = 1.0 / texture.scale;
  const std::vector<double>& lengths = texture.v;
  TubePiece piece;
  std::vector<std::size_t> kept;
  std::vector<Vec3> points, tangents;
  std::vector<double> ring_radii, ring_v;
  std::vector<std::int32_t> owners;
  // A ring of sides + 1 vertices about `center`, in the plane of n and b = t × n, the last at
  // the first's place with u = 1; its normals lean along t by `lean` (a cap's slope).
  const auto ring = [&](const Vec3& center, const Vec3& t, const Vec3& n, double radius, double lean, double v,
                        std::int32_t owner) {
    const Vec3 b = t.cross(n);
    for (int s = 0; s <= sides; ++s) {
      const auto at = static_cast<std::size_t>(s % sides);
      const Vec3 out = cosines[at] * n + sines[at] * b;
      piece.positions.push_back((center + radius * out).cast<float>());
      piece.normals.push_back((out + lean * t).normalized().cast<float>());
      piece.uvs.emplace_back(static_cast<float>(s) / static_cast<float>(sides), static_cast<float>(v));
      const Vec3 around = cosines[at] * b - sines[at] * n;  // d out / d angle: ⟂ out and t
      piece.tangents.emplace_back(static_cast<float>(around.x()), static_cast<float>(around.y()),
                                  static_cast<float>(around.z()), 1.0f);
      piece.particles.push_back(owner);
    }
  };
  // A cap's centre: its normal along ±t, its tangent the frame's b (u = 0's direction).
  const auto pole = [&](const Vec3& at, const Vec3& normal, const Vec3& b, double v, std::int32_t owner) {
    piece.positions.push_back(at.cast<float>());
    piece.normals.push_back(normal.cast<float>());
    piece.uvs.emplace_back(0.5f, static_cast<float>(v));
    piece.tangents.emplace_back(static_cast<float>(b.x()), static_cast<float>(b.y()), static_cast<float>(b.z()), 1.0f);
    piece.particles.push_back(owner);
  };
  const auto k = static_cast<std::uint32_t>(sides), row = k + 1;
  const auto continues = [&](std::size_t i) { return attributes.continues_strand(i); };
  for_each_strand(cluster, continues, [&](const Strand& strand) {
    detail::throw_if_stopped("making the tubes");
    if (strand.size() < 2) return;
    detail::kept_points(cluster, radii, strand, tolerance, kept);
    const std::size_t rings = kept.size();
    points.resize(rings);
    ring_radii.resize(rings);
    ring_v.resize(rings);
    owners.resize(rings);
    for (std::size_t j = 0; j < rings; ++j) {
      const auto id = static_cast<std::size_t>(strand[kept[j]]);
      points[j] = cluster.particles[id].position;
      ring_radii[j] = radii[id] * cluster.spacing;
      ring_v[j] = lengths[id];
      owners[j] = strand[kept[j]];
    }
    // A strand leaving a branch point starts there, no thicker than its parent's tube nor its
    // own next point: it begins inside the parent. Its colour is its own. A seed's own
    // strand starts at the seed.
    const bool own_start = starts_at_own_seed(strand, continues);
    // A branch's particles: its first own particle's subtree; a pruned branch's branches are
    // smaller still, so nothing is left floating.
    if (options.min_branch > 1 &&
        attributes.descendants[static_cast<std::size_t>(strand[own_start ? 0 : 1])] + 1 < options.min_branch)
      return;
    if (!own_start) {
      ring_radii[0] = std::min(ring_radii[0], ring_radii[1]);
      owners[0] = owners[1];
    }
    tangents.resize(rings);
    for (std::size_t j = 0; j < rings; ++j) {
      const Vec3 d = points[std::min(j + 1, rings - 1)] - points[j == 0 ? 0 : j - 1];
      tangents[j] = d.normalized();
    }
    piece.clear();
    // The first frame: the normal across the tangent's smallest component, then carried
    // along by double reflection (Wang et al. 2008), which does not twist.
    Vec3 normal;
    {
      const Vec3& t = tangents[0];
      Eigen::Index axis = 0;
      t.cwiseAbs().minCoeff(&axis);
      normal = t.cross(Vec3::Unit(axis)).normalized();
    }
    const Vec3 first_b = tangents[0].cross(normal);
    for (std::size_t j = 0; j < rings; ++j) {
      if (j > 0) {
        const Vec3 v1 = points[j] - points[j - 1];
        const double c1 = v1.squaredNorm();
        Vec3 n = normal, t = tangents[j - 1];
        if (c1 > 0) {
          n -= (2.0 / c1) * v1.dot(n) * v1;
          t -= (2.0 / c1) * v1.dot(t) * v1;
        }
        const Vec3 v2 = tangents[j] - t;
        const double c2 = v2.squaredNorm();
        if (c2 > 1e-24) n -= (2.0 / c2) * v2.dot(n) * v2;
        normal = (n - n.dot(tangents[j]) * tangents[j]).normalized();
      }
      ring(points[j], tangents[j], normal, ring_radii[j], 0.0, ring_v[j], owners[j]);
    }
    // The rounded tip: a ring part way round, then the apex; v goes on by the distance along.
    const Vec3& end = points[rings - 1];
    const Vec3& t_end = tangents[rings - 1];
    const double r_end = ring_radii[rings - 1], v_end = ring_v[rings - 1];
    ring(end + 0.7 * r_end * t_end, t_end, normal, 0.7 * r_end, 1.0, v_end + 0.7 * r_end * v_per_length,
         owners[rings - 1]);
    const auto apex = static_cast<std::uint32_t>(piece.positions.size());
    pole(end + r_end * t_end, t_end, t_end.cross(normal), v_end + r_end * v_per_length, owners[rings - 1]);
    const auto start = static_cast<std::uint32_t>(piece.positions.size());
    pole(points[0], -tangents[0], first_b, ring_v[0], owners[0]);
    // Walls between consecutive rings (the tip's ring included), outward by the frame's
    // handedness: b = t × n turns counter-clockwise seen from ahead.
    for (std::uint32_t j = 0; j < rings; ++j)
      for (std::uint32_t s = 0; s < k; ++s) {
        const std::uint32_t a = j * row + s, b = a + 1;
        const std::uint32_t c = b + row, d = a + row;
        piece.triangles.push_back({a, b, c});
        piece.triangles.push_back({a, c, d});
      }
    const auto tip = static_cast<std::uint32_t>(rings) * row;
    for (std::uint32_t s = 0; s < k; ++s) {
      piece.triangles.push_back({tip + s, tip + s + 1, apex});
      piece.triangles.push_back({start, s + 1, s});
    }
    visit(static_cast<const TubePiece&>(piece));
  });
  // Whether particle i's branch keeps its tube: its strand's first own particle's subtree.
  const auto branch_kept = [&](std::size_t i) {
    while (continues(i)) i = static_cast<std::size_t>(cluster.particles[i].parent);
    return attributes.descendants[i] + 1 >= options.min_branch;
  };
  for (const Link& link : cluster.links) {
    const auto a = static_cast<std::size_t>(link.earlier), b = static_cast<std::size_t>(link.later);
    if (options.min_branch > 1 && !(branch_kept(a) && branch_kept(b))) continue;
    const Vec3& from = cluster.particles[a].position;
    const Vec3& to = cluster.particles[b].position;
    if (from == to) continue;
    const Vec3 t = (to - from).normalized();
    Eigen::Index axis = 0;
    t.cwiseAbs().minCoeff(&axis);
    const Vec3 n = t.cross(Vec3::Unit(axis)).normalized(), side = t.cross(n);
    const double ra = radii[a] * cluster.spacing, rb = radii[b] * cluster.spacing;
    piece.clear();
    // Rings: the cap behind `from`, `from`, `to`, the cap beyond `to`; each leaning as its cap.
    // v goes on from the earlier end's along the link, from the back cap's centre.
    const std::array<Vec3, 4> centers = {from - 0.7 * ra * t, from, to, to + 0.7 * rb * t};
    const std::array<double, 4> ring_radii = {0.7 * ra, ra, rb, 0.7 * rb}, leans = {-1.0, 0.0, 0.0, 1.0};
    const double v_back = lengths[a], length = (to - from).norm();
    const std::array<double, 4> ring_v = {v_back + 0.3 * ra * v_per_length, v_back + ra * v_per_length,
                                          v_back + (ra + length) * v_per_length,
                                          v_back + (ra + length + 0.7 * rb) * v_per_length};
    for (std::size_t j = 0; j < 4; ++j)
      ring(centers[j], t, n, ring_radii[j], leans[j], ring_v[j], j < 2 ? link.earlier : link.later);
    const auto back = static_cast<std::uint32_t>(piece.positions.size());
    pole(from - ra * t, -t, side, v_back, link.earlier);
    const auto front = static_cast<std::uint32_t>(piece.positions.size());
    pole(to + rb * t, t, side, v_back + (ra + length + rb) * v_per_length, link.later);
    for (std::uint32_t j = 0; j < 3; ++j)
      for (std::uint32_t s = 0; s < k; ++s) {
        const std::uint32_t p = j * row + s, q = p + 1;
        piece.triangles.push_back({p, q, q + row});
        piece.triangles.push_back({p, q + row, p + row});
      }
    for (std::uint32_t s = 0; s < k; ++s) {
      piece.triangles.push_back({back, s + 1, s});
      piece.triangles.push_back({3 * row + s, 3 * row + s + 1, front});
    }
    visit(static_cast<const TubePiece&>(piece));
  }
}

//! for_each_tube with the texture of `options.uv_scale`.
template <class Visit>
void for_each_tube(const Cluster& cluster, const Attributes& attributes, const std::vector<float>& radii,
                   const TubeOptions& options, Visit&& visit) {
  validate(options);
  for_each_tube(cluster, attributes, radii, tube_texture(cluster, radii, options.uv_scale), options,
                std::forward<Visit>(visit));
}

}  // namespace dla
