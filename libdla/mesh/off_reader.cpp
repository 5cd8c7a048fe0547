// OFF and COFF: the reader behind read_mesh() for .off (mesh_readers.h).

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace dla::detail {

TriangleMesh parse_off(std::string_view text, const std::string& name) {
  Words words(text, '#');
  const std::string header = std::string(words.next());
  if (header != "OFF" && header != "COFF" && header != "NOFF" && header != "CNOFF")
    malformed(name, "does not begin with OFF");
  const bool colored = header.front() == 'C', normals = header.find('N') != std::string::npos;
  std::uint64_t nv = 0, nf = 0, ne = 0;
  if (!parse_integer(words.next(), nv) || !parse_integer(words.next(), nf) || !parse_integer(words.next(), ne))
    malformed(name, "has no vertex, face and edge counts after OFF");
  // A vertex takes at least 6 bytes ("0 0 0\n"), a triangle 8: refuse counts the file cannot hold.
  if (nv > text.size() / 6 || nf > text.size() / 8)
    malformed(name, "counts " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                        " faces, more than its " + std::to_string(text.size()) + " bytes can hold");
  Builder mesh(name);
  mesh.reserve(nv, nf);
  for (std::uint64_t i = 0; i < nv; ++i) {
    words.skip();
    const std::string where = "vertex " + std::to_string(i) + " (line " + std::to_string(words.line()) + ")";
    Vec3 v;
    for (int a = 0; a < 3; ++a)
      if (!parse_double(words.next(), v[a])) malformed(name, where + " is not 3 numbers");
    mesh.vertex(v, where);
    Words rest(words.rest_of_line());  // NOFF's normal, then COFF's colour and alpha
    if (normals)
      for (int a = 0; a < 3; ++a) rest.next();
    if (colored) {
      // Geomview's rule: integers count to 255, any other number to 1.
      Vec3 rgb;
      bool integers = true;
      for (int a = 0; a < 3; ++a) {
        const std::string_view word = rest.next();
        if (!parse_double(word, rgb[a])) malformed(name, where + " has no red, green and blue after its place");
        integers = integers && word.find_first_of(".eE") == std::string_view::npos;
      }
      mesh.color(rgb, integers ? 255.0 : 1.0, where);
    }
  }
  std::vector<std::int64_t> ids;
  for (std::uint64_t f = 0; f < nf; ++f) {
    words.skip();
    const std::string where = "face " + std::to_string(f) + " (line " + std::to_string(words.line()) + ")";
    std::uint32_t n = 0;
    if (!parse_integer(words.next(), n)) malformed(name, where + " does not begin with its vertex count");
    if (n > nv) malformed(name, where + " has " + std::to_string(n) + " vertices, more than the mesh");
    ids.assign(n, 0);
    for (std::uint32_t i = 0; i < n; ++i)
      if (!parse_integer(words.next(), ids[i])) malformed(name, where + " has a vertex index that is not a number");
    words.rest_of_line();  // an optional colour
    mesh.polygon(ids, where);
  }
  return mesh.finish();
}

}  // namespace dla::detail
