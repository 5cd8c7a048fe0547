// libFuzzer target for one mesh reader, chosen at build time (DLA_FUZZ_FORMAT: stl, off, obj or
// ply), or for the rows of a point file ("points": read_points' CSV). Any input must either
// parse into a mesh whose indices are in range and coordinates finite (or points, all finite),
// or be refused with InvalidInput: never crash, hang, leak or read out of bounds.
// Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "dla/mesh/mesh.h"
#include "special_files.h"

#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const bool points = std::string_view(DLA_FUZZ_FORMAT) == "points";
  dla::fuzz::read_special_files(points ? ".csv" : "." DLA_FUZZ_FORMAT, [&](const std::string& path) {
    if (points) dla::read_points(path);
    else dla::read_mesh(path);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    if (std::string_view(DLA_FUZZ_FORMAT) == "points") {
      for (const dla::Vec3& p : dla::parse_points(bytes, "csv", "fuzz"))
        if (!p.allFinite()) std::abort();
      return 0;
    }
    const dla::TriangleMesh mesh = dla::parse_mesh(bytes, DLA_FUZZ_FORMAT, "fuzz");
    for (const auto& t : mesh.triangles)
      for (std::uint32_t id : t)
        if (id >= mesh.vertices.size()) std::abort();
    for (const dla::Vec3& v : mesh.vertices)
      if (!v.allFinite()) std::abort();
  } catch (const dla::InvalidInput&) {
  }
  return 0;
}
