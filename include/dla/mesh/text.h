#pragma once
//! \file text.h
//! Text as a closed triangle mesh: the glyphs' outlines from a font file (FreeType), filled
//! (CGAL's constrained Delaunay triangulation) and extruded, to grow inside as any mesh
//! (`--text "DLA"`, the thesis' vines on text). See docs/constraints.md#3d-text.

#include "dla/mesh/mesh.h"

#include <string>
#include <vector>

namespace dla {

//! A Debian font (fonts-dejavu-core): bold strokes leave room to grow in.
inline constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

struct TextOptions {
  std::string text;                //!< UTF-8; a line break starts a new line below
  std::string font = kDefaultFont; //!< any font FreeType reads (TrueType, OpenType, Type 1)
  double size = 100.0;             //!< the em, in mesh units: capitals stand about 0.73 of it
  double depth = 25.0;             //!< the extrusion along z, in mesh units, from z = 0
};

//! The extruded text, in the plane z = 0 to `depth`, reading along +x with +y up, and a point
//! deep inside each glyph that has an outline (a seed for each letter).
struct TextMesh {
  TriangleMesh mesh;              //!< closed, triangles facing out
  std::vector<Vec3> glyph_seeds;  //!< the point of each glyph farthest from its outline, at depth / 2
};

//! Throws IOError if the font cannot be read, and InvalidInput for text with nothing to draw
//! (empty, or only spaces) or more than 10,000 characters, a character the font lacks, or a
//! size or depth that is not positive and finite.
TextMesh text_mesh(const TextOptions& options);

}  // namespace dla
