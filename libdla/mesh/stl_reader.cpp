// STL, binary or ASCII: the reader behind read_mesh() for .stl (mesh_readers.h).

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace dla::detail {

namespace {

float read_float_le(const unsigned char* p) {
  std::uint32_t bits = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                       std::uint32_t(p[3]) << 24;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

TriangleMesh parse_binary_stl(std::string_view bytes, const std::string& name, std::uint64_t count) {
  Builder mesh(name);
  mesh.reserve(3 * count, count);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::uint64_t t = 0; t < count; ++t) {
    const unsigned char* facet = data + 84 + 50 * t + 12;  // skip the stored normal
    const std::string where = "triangle " + std::to_string(t + 1);
    std::vector<std::int64_t> ids;
    for (int v = 0; v < 3; ++v) {
      const unsigned char* p = facet + 12 * v;
      ids.push_back(static_cast<std::int64_t>(mesh.vertex_count()));
      mesh.vertex({read_float_le(p), read_float_le(p + 4), read_float_le(p + 8)}, where);
    }
    mesh.polygon(ids, where);
  }
  return mesh.finish();
}

TriangleMesh parse_ascii_stl(std::string_view text, const std::string& name) {
  Builder mesh(name);
  Words words(text);
  if (lower(words.next()) != "solid") malformed(name, "is neither a binary STL nor an ASCII STL starting with 'solid'");
  words.rest_of_line();  // the solid's name
  std::vector<std::int64_t> ids;
  bool ended = false;
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    const std::string key = lower(word);
    const std::string where = "line " + std::to_string(words.line());
    if (key == "vertex") {
      Vec3 v;
      for (int i = 0; i < 3; ++i)
        if (!parse_double(words.next(), v[i])) malformed(name, where + ": a vertex needs 3 numbers");
      ids.push_back(static_cast<std::int64_t>(mesh.vertex_count()));
      mesh.vertex(v, where);
    } else if (key == "endfacet") {
      if (ids.size() != 3) malformed(name, where + ": a facet has " + std::to_string(ids.size()) + " vertices, not 3");
      mesh.polygon(ids, where);
      ids.clear();
    } else if (key == "normal") {
      double ignored;
      for (int i = 0; i < 3; ++i)
        if (!parse_double(words.next(), ignored)) malformed(name, where + ": a normal needs 3 numbers");
    } else if (key == "endsolid") {
      ended = true;
      words.rest_of_line();
    } else if (key == "solid") {
      words.rest_of_line();  // files that hold several solids
    } else if (key != "facet" && key != "outer" && key != "loop" && key != "endloop") {
      malformed(name, where + ": unexpected '" + std::string(word.substr(0, 40)) + "' in an ASCII STL");
    }
  }
  if (!ids.empty() || !ended) malformed(name, "ends in the middle of the ASCII STL (no 'endsolid')");
  return mesh.finish();
}

}  // namespace

TriangleMesh parse_stl(std::string_view bytes, const std::string& name) {
  // Binary is decided by size: 84 + 50 x count. Some binary files begin with "solid" too.
  if (bytes.size() >= 84) {
    const std::uint64_t count = read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    if (bytes.size() == 84 + 50 * count) return parse_binary_stl(bytes, name, count);
  }
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && lower(bytes.substr(start, 5)) == "solid")
    return parse_ascii_stl(bytes, name);
  if (bytes.size() < 84) malformed(name, "is too short for an STL file (" + std::to_string(bytes.size()) + " bytes)");
  const std::uint64_t count = read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
  malformed(name, "is not a valid binary STL: its header counts " + std::to_string(count) + " triangles, " +
                      std::to_string(84 + 50 * count) + " bytes, but the file has " +
                      std::to_string(bytes.size()) + " bytes");
}

}  // namespace dla::detail
