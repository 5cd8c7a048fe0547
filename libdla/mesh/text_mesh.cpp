// FreeType's glyph outlines and CGAL's constrained Delaunay triangulation behind text_mesh(),
// kept to this one translation unit (CGAL's headers take tens of seconds to compile).

#include "dla/mesh/text.h"

#include "dla/core/options.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <list>
#include <memory>

namespace dla {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

//! How deep in the outlines a face lies: odd levels are inside a glyph, even ones in a counter
//! (the hole of an O) or outside.
struct FaceInfo {
  int nesting = -1;
  bool filled() const { return nesting % 2 == 1; }
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<
    Kernel, CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>>;
// Exact_predicates_tag: outlines that cross (some fonts overlap their strokes) are split where
// they cross, at a computed point.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>, CGAL::Exact_predicates_tag>;

using Contour = std::vector<Point>;

//! A glyph's outline as closed polygons, its curves flattened, in font units moved by `origin`.
struct Outline {
  std::vector<Contour> contours;
  Point origin;
  Point last;

  void add(const Point& p) {
    if (contours.back().empty() || contours.back().back() != p) contours.back().push_back(p);
    last = p;
  }
  Point at(const FT_Vector* v) const { return {origin.x() + double(v->x), origin.y() + double(v->y)}; }
};

// Curves become 8 chords: a thousandth of the em or less away from the curve in the bold fonts.
constexpr int kChords = 8;

int move_to(const FT_Vector* to, void* user) {
  auto& outline = *static_cast<Outline*>(user);
  outline.contours.emplace_back();
  outline.add(outline.at(to));
  return 0;
}

int line_to(const FT_Vector* to, void* user) {
  auto& outline = *static_cast<Outline*>(user);
  outline.add(outline.at(to));
  return 0;
}

int conic_to(const FT_Vector* control, const FT_Vector* to, void* user) {
  auto& outline = *static_cast<Outline*>(user);
  const Point a = outline.last, b = outline.at(control), c = outline.at(to);
  for (int i = 1; i <= kChords; ++i) {
    const double t = double(i) / kChords, s = 1 - t;
    outline.add({s * s * a.x() + 2 * s * t * b.x() + t * t * c.x(), s * s * a.y() + 2 * s * t * b.y() + t * t * c.y()});
  }
  return 0;
}

int cubic_to(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
  auto& outline = *static_cast<Outline*>(user);
  const Point a = outline.last, b = outline.at(c1), c = outline.at(c2), d = outline.at(to);
  for (int i = 1; i <= kChords; ++i) {
    const double t = double(i) / kChords, s = 1 - t;
    const double wa = s * s * s, wb = 3 * s * s * t, wc = 3 * s * t * t, wd = t * t * t;
    outline.add({wa * a.x() + wb * b.x() + wc * c.x() + wd * d.x(), wa * a.y() + wb * b.y() + wc * c.y() + wd * d.y()});
  }
  return 0;
}

//! Marks each face's nesting: 0 outside, then one more across each outline (CGAL's example).
void mark_nesting(Cdt& cdt) {
  std::list<Cdt::Edge> border;
  const auto flood = [&](Cdt::Face_handle start, int level) {
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle face = queue.front();
      queue.pop_front();
      if (face->info().nesting != -1) continue;
      face->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle next = face->neighbor(i);
        if (next->info().nesting != -1) continue;
        if (cdt.is_constrained({face, i})) border.push_back({face, i});
        else queue.push_back(next);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge edge = border.front();
    border.pop_front();
    const Cdt::Face_handle next = edge.first->neighbor(edge.second);
    if (next->info().nesting == -1) flood(next, edge.first->info().nesting + 1);
  }
}

double distance_to_segment(const Point& p, const Point& a, const Point& b) {
  const double dx = b.x() - a.x(), dy = b.y() - a.y(), length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? ((p.x() - a.x()) * dx + (p.y() - a.y()) * dy) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x() - a.x() - t * dx, p.y() - a.y() - t * dy);
}

//! Fills the outline, extrudes it from z = 0 to `depth` (scaled by `scale`) into `out`, and
//! returns the point of the glyph farthest from its outline, near enough.
Vec3 extrude(const Outline& outline, double scale, double depth, TriangleMesh& out) {
  Cdt cdt;
  for (const Contour& contour : outline.contours) {
    Contour ring = contour;
    while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
    if (ring.size() >= 3) cdt.insert_constraint(ring.begin(), ring.end(), true);
  }
  mark_nesting(cdt);
  const auto base = static_cast<std::uint32_t>(out.vertices.size());
  std::uint32_t count = 0;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) v->info() = count++;
  for (const double z : {0.0, depth})
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
      out.vertices.emplace_back(scale * v->point().x(), scale * v->point().y(), z);
  const auto bottom = [&](Cdt::Vertex_handle v) { return base + v->info(); };
  const auto top = [&](Cdt::Vertex_handle v) { return base + count + v->info(); };

  std::vector<std::pair<Point, Point>> edges;  // the outline, to measure depth by
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->info().filled()) continue;
    const auto a = f->vertex(0), b = f->vertex(1), c = f->vertex(2);  // counter-clockwise
    out.triangles.push_back({top(a), top(b), top(c)});
    out.triangles.push_back({bottom(a), bottom(c), bottom(b)});
    for (int i = 0; i < 3; ++i) {
      if (!cdt.is_constrained({f, i}) || f->neighbor(i)->info().filled()) continue;
      // The glyph is on the left of p -> q: the wall faces right, out of it.
      const auto p = f->vertex(Cdt::ccw(i)), q = f->vertex(Cdt::cw(i));
      out.triangles.push_back({bottom(p), bottom(q), top(q)});
      out.triangles.push_back({bottom(p), top(q), top(p)});
      edges.emplace_back(p->point(), q->point());
    }
  }
  // Candidates: each filled triangle's centroid and the midpoints of its edges (across a stroke,
  // the long triangles' edges span it, so their midpoints lie in the middle).
  double deepest = -1.0;
  Point seed(0, 0);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->info().filled()) continue;
    const Point &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
    for (const Point& candidate : {CGAL::centroid(a, b, c), CGAL::midpoint(a, b), CGAL::midpoint(b, c), CGAL::midpoint(c, a)}) {
      double depth_here = std::numeric_limits<double>::infinity();
      for (const auto& [p, q] : edges) depth_here = std::min(depth_here, distance_to_segment(candidate, p, q));
      if (depth_here > deepest) {
        deepest = depth_here;
        seed = candidate;
      }
    }
  }
  return {scale * seed.x(), scale * seed.y(), 0.5 * depth};
}

//! The next code point of UTF-8 `text` at `at`, moving `at` past it.
char32_t next_code_point(const std::string& text, std::size_t& at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  const int length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xe ? 3 : (lead >> 3) == 0x1e ? 4 : 0;
  if (length == 0 || at + length > text.size()) throw InvalidInput("`text` is not valid UTF-8");
  char32_t code = length == 1 ? lead : lead & (0x7f >> length);
  for (int i = 1; i < length; ++i) {
    if ((byte(at + i) >> 6) != 0x2) throw InvalidInput("`text` is not valid UTF-8");
    code = code << 6 | (byte(at + i) & 0x3f);
  }
  at += length;
  return code;
}

}  // namespace

TextMesh text_mesh(const TextOptions& options) {
  if (!(options.size > 0.0 && std::isfinite(options.size)))
    throw InvalidInput("the text size " + detail::format_number(options.size) + " is not a positive length");
  if (!(options.depth > 0.0 && std::isfinite(options.depth)))
    throw InvalidInput("the text depth " + detail::format_number(options.depth) + " is not a positive length");
  FT_Library library = nullptr;
  if (FT_Init_FreeType(&library)) throw IOError("FreeType did not start");
  const std::unique_ptr<FT_LibraryRec_, FT_Error (*)(FT_Library)> library_owner(library, FT_Done_FreeType);
  FT_Face face = nullptr;
  if (FT_New_Face(library, options.font.c_str(), 0, &face))
    throw IOError("cannot read the font '" + options.font + "': not found, or not a font FreeType reads");
  const std::unique_ptr<FT_FaceRec_, FT_Error (*)(FT_Face)> face_owner(face, FT_Done_Face);
  if (!FT_IS_SCALABLE(face)) throw InvalidInput(options.font + " is a bitmap font: text needs outlines");

  const double scale = options.size / face->units_per_EM;
  const FT_Outline_Funcs funcs{move_to, line_to, conic_to, cubic_to, 0, 0};
  TextMesh result;
  double pen_x = 0.0, pen_y = 0.0;
  FT_UInt previous = 0;
  constexpr std::size_t max_characters = 10'000;  // a page: more is no longer a sculpture
  std::size_t characters = 0;
  for (std::size_t at = 0; at < options.text.size();) {
    const char32_t code = next_code_point(options.text, at);
    if (++characters > max_characters) throw InvalidInput("the text has more than 10,000 characters");
    if (code == U'\n') {
      pen_x = 0.0;
      pen_y -= face->height;
      previous = 0;
      continue;
    }
    const FT_UInt glyph = FT_Get_Char_Index(face, code);
    if (glyph == 0) {
      char name[16];
      std::snprintf(name, sizeof name, "U+%04X", static_cast<unsigned>(code));
      throw InvalidInput(options.font + " has no glyph for " + name + " of the text");
    }
    if (previous && FT_HAS_KERNING(face)) {
      FT_Vector kern;
      if (!FT_Get_Kerning(face, previous, glyph, FT_KERNING_UNSCALED, &kern)) pen_x += kern.x;
    }
    if (FT_Load_Glyph(face, glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_BITMAP) ||
        face->glyph->format != FT_GLYPH_FORMAT_OUTLINE)
      throw InvalidInput(options.font + " gives no outline for a character of the text");
    Outline outline;
    outline.origin = Point(pen_x, pen_y);
    if (FT_Outline_Decompose(&face->glyph->outline, &funcs, &outline))
      throw InvalidInput(options.font + " has a malformed outline");
    if (!outline.contours.empty()) {
      const std::size_t before = result.mesh.triangles.size();
      const Vec3 seed = extrude(outline, scale, options.depth, result.mesh);
      if (result.mesh.triangles.size() > before) result.glyph_seeds.push_back(seed);
    }
    pen_x += face->glyph->advance.x;
    previous = glyph;
  }
  if (result.mesh.triangles.empty()) throw InvalidInput("the text has nothing to draw: give it letters, not only spaces");
  return result;
}

}  // namespace dla
