// self_intersects() (solid_check.h) by CGAL, which the library's solids do not use.
#include "solid_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

namespace dla {

bool self_intersects(const SolidMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Surface_mesh<Kernel::Point_3> surface;
  std::vector<CGAL::Surface_mesh<Kernel::Point_3>::Vertex_index> vertices;
  for (const Eigen::Vector3f& v : mesh.vertices) vertices.push_back(surface.add_vertex({v.x(), v.y(), v.z()}));
  for (const auto& t : mesh.triangles) surface.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  return CGAL::Polygon_mesh_processing::does_self_intersect(surface);
}

}  // namespace dla
