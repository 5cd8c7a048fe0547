// The CGAL side of mesh repair, kept to this one translation unit: CGAL's headers take tens of
// seconds and over a gigabyte to compile.

#include "dla/mesh/mesh_repair.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <map>
#include <set>

namespace dla {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

//! "1 hole", "64,687 duplicate vertices".
std::string count(std::size_t n, const char* one, const char* many) {
  return detail::format_count(n) + " " + (n == 1 ? one : many);
}

//! Whether triangle `t` of `mesh` runs the other way round from the same corners `original`.
bool reversed(const std::array<Vec3, 3>& original, const std::array<Vec3, 3>& t) {
  for (int shift = 0; shift < 3; ++shift)
    if (t[0] == original[shift] && t[1] == original[(shift + 1) % 3] && t[2] == original[(shift + 2) % 3])
      return false;
  return true;
}

}  // namespace

std::string RepairReport::summary() const {
  std::vector<std::string> parts;
  if (merged_vertices) parts.push_back("merged " + count(merged_vertices, "duplicate vertex", "duplicate vertices"));
  if (dropped_triangles)
    parts.push_back("dropped " + count(dropped_triangles, "degenerate or repeated triangle", "degenerate or repeated triangles"));
  if (reoriented_triangles) parts.push_back("turned " + count(reoriented_triangles, "triangle", "triangles") + " round");
  if (holes_closed)
    parts.push_back("closed " + count(holes_closed, "hole", "holes") + " with " + count(hole_triangles, "triangle", "triangles"));
  if (holes_left) parts.push_back(count(holes_left, "hole", "holes") + " could not be closed");
  if (parts.empty()) return "nothing to repair";
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : ", ") + part;
  return text;
}

TriangleMesh repair_mesh(const TriangleMesh& input, const RepairOptions& options, RepairReport* report) {
  RepairReport r;
  r.input_triangles = input.triangles.size();

  // Merge vertices at exactly the same place (STL stores every corner of every triangle).
  std::vector<Point> points;
  std::vector<std::uint32_t> merged(input.vertices.size());
  std::map<std::array<double, 3>, std::uint32_t> first;
  std::vector<std::uint32_t> read_as;  // for each merged vertex, the first vertex read there
  for (std::size_t i = 0; i < input.vertices.size(); ++i) {
    const Vec3& v = input.vertices[i];
    const auto [it, added] = first.emplace(std::array<double, 3>{v.x(), v.y(), v.z()},
                                           static_cast<std::uint32_t>(points.size()));
    if (added) {
      points.emplace_back(v.x(), v.y(), v.z());
      read_as.push_back(static_cast<std::uint32_t>(i));
    }
    merged[i] = it->second;
  }
  std::size_t used_vertices = 0;
  {
    std::vector<bool> used(input.vertices.size(), false);
    for (const auto& t : input.triangles)
      for (std::uint32_t id : t) used[id] = true;
    for (bool u : used) used_vertices += u;
  }

  // Drop triangles with repeated or collinear corners, and second copies of a triangle.
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<std::array<Vec3, 3>> kept;  // corners as read, to count the triangles turned round
  std::set<std::array<std::uint32_t, 3>> seen;
  for (const auto& t : input.triangles) {
    const std::uint32_t a = merged[t[0]], b = merged[t[1]], c = merged[t[2]];
    if (a == b || b == c || a == c || CGAL::collinear(points[a], points[b], points[c])) {
      ++r.dropped_triangles;
      continue;
    }
    std::array<std::uint32_t, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) {
      ++r.dropped_triangles;
      continue;
    }
    polygons.push_back({a, b, c});
    kept.push_back({input.vertices[t[0]], input.vertices[t[1]], input.vertices[t[2]]});
  }
  if (polygons.empty()) throw InvalidInput("the mesh has no triangle with an area: all " + std::to_string(r.input_triangles) + " are degenerate");
  {
    std::vector<bool> used(points.size(), false);
    for (const auto& p : polygons)
      for (std::size_t id : p) used[id] = true;
    std::size_t after = 0;
    for (bool u : used) after += u;
    r.merged_vertices = used_vertices > after ? used_vertices - after : 0;
  }

  // Consistent orientation; vertices where the surface is not a manifold are split.
  PMP::orient_polygon_soup(points, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);

  if (options.close_holes) {
    std::vector<Mesh::Halfedge_index> holes;
    std::set<Mesh::Halfedge_index> visited;
    for (Mesh::Halfedge_index h : mesh.halfedges()) {
      if (!mesh.is_border(h) || visited.count(h)) continue;
      holes.push_back(h);
      for (Mesh::Halfedge_index g : CGAL::halfedges_around_face(h, mesh)) visited.insert(g);
    }
    for (Mesh::Halfedge_index h : holes) {
      std::size_t edges = 0;
      for ([[maybe_unused]] Mesh::Halfedge_index g : CGAL::halfedges_around_face(h, mesh)) ++edges;
      std::vector<Mesh::Face_index> patch;
      // The cubic fallback is fine for the holes of scans and far too slow for huge ones.
      PMP::triangulate_hole(mesh, h, std::back_inserter(patch),
                            CGAL::parameters::do_not_use_cubic_algorithm(edges > 500));
      if (patch.empty()) {
        ++r.holes_left;
      } else {
        ++r.holes_closed;
        r.hole_triangles += patch.size();
      }
    }
    r.closed = CGAL::is_closed(mesh);
    if (r.closed) PMP::orient_to_bound_a_volume(mesh);
  } else {
    r.closed = CGAL::is_closed(mesh);
  }

  TriangleMesh out;
  out.vertices.reserve(mesh.number_of_vertices());
  std::vector<std::uint32_t> id(mesh.num_vertices(), 0);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    id[v.idx()] = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.emplace_back(p.x(), p.y(), p.z());
    // Vertices keep their places (split ones are copies, holes add none): the colour is the
    // first one read there.
    if (!input.colors.empty()) out.colors.push_back(input.colors[read_as[first.at({p.x(), p.y(), p.z()})]]);
  }
  out.triangles.reserve(mesh.number_of_faces());
  for (Mesh::Face_index f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    std::array<Vec3, 3> corners;
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) {
        t[k] = id[v.idx()];
        corners[k] = out.vertices[t[k]];
      }
      ++k;
    }
    if (k != 3) continue;
    // Faces keep their order through polygon_soup_to_polygon_mesh; the hole patches come last.
    if (f.idx() < kept.size() && reversed(kept[f.idx()], corners)) ++r.reoriented_triangles;
    out.triangles.push_back(t);
  }
  if (report) *report = r;
  return out;
}

}  // namespace dla
