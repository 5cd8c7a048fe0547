// CGAL's AABB tree and triangle-triangle intersection behind intersect_surfaces(), kept to this
// one translation unit (CGAL's headers take tens of seconds to compile).

#include "dla/mesh/mesh_intersection.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <iterator>
#include <vector>

namespace dla {

namespace {

// Exact predicates find the pairs of triangles that meet, even when they only touch. What they
// share is constructed exactly: CGAL 5.5's triangle-triangle intersection in doubles finds
// nothing for many pairs that do cross (a sphere and a cylinder at an angle, say).
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 vec(const Exact::Point_3& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}; }

Triangle triangle(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  return {point(mesh.vertices[t[0]]), point(mesh.vertices[t[1]]), point(mesh.vertices[t[2]])};
}

}  // namespace

SurfaceIntersection intersect_surfaces(const TriangleMesh& first, const TriangleMesh& second) {
  SurfaceIntersection out;
  Triangles triangles;
  triangles.reserve(first.triangles.size());
  for (const auto& t : first.triangles) triangles.push_back(triangle(first, t));
  if (triangles.empty()) return out;
  AabbTree tree(triangles.begin(), triangles.end());
  std::vector<AabbTree::Primitive_id> hits;
  const CGAL::Cartesian_converter<Kernel, Exact> exact;
  for (const auto& t : second.triangles) {
    const Triangle query = triangle(second, t);
    if (query.is_degenerate()) continue;
    hits.clear();
    tree.all_intersected_primitives(query, std::back_inserter(hits));
    for (const auto& hit : hits) {
      const auto index = static_cast<std::uint32_t>(hit - triangles.begin());
      if (hit->is_degenerate()) continue;
      const auto shared = CGAL::intersection(exact(*hit), exact(query));
      if (!shared) continue;
      if (const auto* segment = boost::get<Exact::Segment_3>(&*shared)) {
        out.segments.push_back({vec(segment->source()), vec(segment->target()), index});
      } else if (const auto* overlap = boost::get<Exact::Triangle_3>(&*shared)) {
        out.patches.push_back({vec(overlap->vertex(0)), vec(overlap->vertex(1)), vec(overlap->vertex(2)), index});
      } else if (const auto* polygon = boost::get<std::vector<Exact::Point_3>>(&*shared)) {
        for (std::size_t i = 1; i + 1 < polygon->size(); ++i)
          out.patches.push_back({vec((*polygon)[0]), vec((*polygon)[i]), vec((*polygon)[i + 1]), index});
      }
      // A single point (a corner touching) has no length to seed.
    }
  }
  return out;
}

}  // namespace dla
