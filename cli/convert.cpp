#include "commands.h"

#include "dla/io/mesh_writers.h"
#include "dla/mesh/mesh.h"

#include <cstdio>

namespace dla::cli {

int convert(const std::string& in, const std::string& out, bool quiet) {
  const TriangleMesh mesh = read_mesh(in);
  write_stl(mesh, out);
  if (!quiet)
    std::fprintf(stderr, "dla3d: wrote %s: %s triangles from %s\n", out.c_str(),
                 detail::format_count(mesh.triangles.size()).c_str(), in.c_str());
  return 0;
}

}  // namespace dla::cli
