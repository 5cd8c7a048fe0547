// Embree's point queries behind SurfaceDistance. Embree's hierarchy, in floats, only says which
// triangles may be near; each is measured in double precision, and the query's radius is
// padded by more than the floats' rounding, so no triangle nearer than the best is passed over.

#include "dla/mesh/surface_distance.h"

#include "embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dla {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: the closest point by Voronoi regions.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct SurfaceDistance::Tree : detail::EmbreeScene {
  Tree(const TriangleMesh& mesh, double scale) : EmbreeScene(mesh), mesh(mesh), scale(scale) {
    planes.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
      const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
      const Vec3 normal = (b - a).cross(c - a).normalized();  // not finite if degenerate
      planes.emplace_back(normal.x(), normal.y(), normal.z(), -normal.dot(a));
    }
  }
  TriangleMesh mesh;
  std::vector<Eigen::Vector4d> planes;  // each triangle's, as (unit normal, offset)
  double scale;  // the largest coordinate of the mesh: the floats' rounding is relative to it
};

namespace {

//! What a point query has found so far.
struct Nearest {
  const TriangleMesh* mesh;
  const std::vector<Eigen::Vector4d>* planes;
  Vec3 p;
  double pad;  // added to the radius: more than the floats' rounding
  double squared = std::numeric_limits<double>::infinity();
  unsigned triangle = std::numeric_limits<unsigned>::max();
  Vec3 point = Vec3::Zero();

  //! Measures triangle t and keeps it if it is the nearest (on a tie, the first listed).
  bool offer(unsigned t) {
    // A triangle is no nearer than its plane: most that Embree offers are passed over at that.
    const Eigen::Vector4d& plane = (*planes)[t];
    const double off_plane = std::abs(plane.head<3>().dot(p) + plane[3]);
    if (off_plane > pad && (off_plane - pad) * (off_plane - pad) > squared) return false;
    const auto& tri = mesh->triangles[t];
    const Vec3 q = closest_point_on_triangle(p, mesh->vertices[tri[0]], mesh->vertices[tri[1]], mesh->vertices[tri[2]]);
    const double d = (q - p).squaredNorm();
    if (d > squared || (d == squared && t > triangle)) return false;
    squared = d;
    triangle = t;
    point = q;
    return true;
  }
};

bool visit(RTCPointQueryFunctionArguments* args) {
  auto* nearest = static_cast<Nearest*>(args->userPtr);
  if (!nearest->offer(args->primID)) return false;
  const float radius = static_cast<float>(std::sqrt(nearest->squared) + nearest->pad);
  if (!(radius < args->query->radius)) return false;
  args->query->radius = std::nextafter(radius, std::numeric_limits<float>::infinity());
  return true;
}

}  // namespace

SurfaceDistance::SurfaceDistance(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw InvalidInput("the mesh has no triangle to measure distances to");
  const Box box = bounding_box(mesh);
  const double scale = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  tree_ = std::make_unique<Tree>(mesh, scale);
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

SurfaceDistance::Closest SurfaceDistance::on_triangle(const Vec3& p, std::uint32_t t) const {
  const TriangleMesh& mesh = tree_->mesh;
  const auto& tri = mesh.triangles.at(t);
  return {closest_point_on_triangle(p, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]), t};
}

SurfaceDistance::Closest SurfaceDistance::closest(const Vec3& p, std::uint32_t hint) const {
  const TriangleMesh& mesh = tree_->mesh;
  const double scale = std::max(tree_->scale, p.cwiseAbs().maxCoeff());
  Nearest nearest{&mesh, &tree_->planes, p, 1e-6 * scale};
  constexpr double float_range = 1e30;
  if (!(scale < float_range)) {  // beyond floats (or not finite): every triangle
    for (unsigned t = 0; t < mesh.triangles.size(); ++t) nearest.offer(t);
    return {nearest.point, nearest.triangle};
  }
  // The hint's distance bounds the search from the start; the hint itself is measured again in
  // turn, so that a tie still goes to the triangle listed first.
  double within = std::numeric_limits<double>::infinity();
  if (hint < mesh.triangles.size()) {
    const auto& tri = mesh.triangles[hint];
    within = (closest_point_on_triangle(p, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]) - p).norm();
  }
  detail::FlushDenormals flush;
  alignas(16) RTCPointQuery query;
  query.x = static_cast<float>(p.x());
  query.y = static_cast<float>(p.y());
  query.z = static_cast<float>(p.z());
  query.time = 0.0f;
  query.radius = std::nextafter(static_cast<float>(within + nearest.pad), std::numeric_limits<float>::infinity());
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(tree_->scene(), &query, &context, visit, &nearest);
  return {nearest.point, nearest.triangle};
}

}  // namespace dla
