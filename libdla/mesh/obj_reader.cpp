// Wavefront OBJ: the reader behind read_mesh() for .obj (mesh_readers.h).

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace dla::detail {

TriangleMesh parse_obj(std::string_view text, const std::string& name) {
  Builder mesh(name);
  std::vector<std::int64_t> ids;
  std::size_t line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const std::string where = "line " + std::to_string(line_number);
    Words words(line, '#');
    const std::string_view key = words.next();
    if (key == "v") {
      Vec3 v;
      for (int a = 0; a < 3; ++a)
        if (!parse_double(words.next(), v[a])) malformed(name, where + ": a vertex needs 3 numbers");
      mesh.vertex(v, where);
      // `v x y z r g b`, as Blender and MeshLab write vertex colours; a lone fourth number is a weight.
      const std::string_view red = words.next();
      if (!red.empty()) {
        Vec3 rgb;
        if (parse_double(red, rgb[0]) && parse_double(words.next(), rgb[1]) && parse_double(words.next(), rgb[2]))
          mesh.color(rgb, rgb.maxCoeff() > 1.0 ? 255.0 : 1.0, where);
      }
    } else if (key == "f") {
      ids.clear();
      for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
        std::int64_t id = 0;
        if (!parse_integer(word.substr(0, word.find('/')), id) || id == 0)
          malformed(name, where + ": face index '" + std::string(word.substr(0, 40)) + "' is not a vertex number");
        // 1-based; negative counts back from the latest vertex.
        ids.push_back(id > 0 ? id - 1 : static_cast<std::int64_t>(mesh.vertex_count()) + id);
      }
      mesh.polygon(ids, where);
    }
    // Normals, texture coordinates, groups and materials do not shape the surface.
  }
  return mesh.finish();
}

}  // namespace dla::detail
