// The inputs of docs/constraints.md's pictures of painted and entering seeds, made in code as an
// artist would make them in Blender: a bust with a patch painted red on its crown (Vertex Paint,
// then File > Export > PLY with colours), and two rods pushed into its head (two cylinders,
// exported as one STL).
//
//   artist_inputs BUST [PREFIX]    writes PREFIX_painted.ply and PREFIX_rods.stl (PREFIX: bust)
//   dla3d --stl bust_painted.ply --seed-paint red
//   dla3d --stl bust.stl --seed-mesh bust_rods.stl --radius seed-distance

#include "dla/io/mesh_writers.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/shapes.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: artist_inputs BUST [PREFIX]\n");
    return 2;
  }
  try {
    const dla::TriangleMesh bust = dla::read_mesh(argv[1]);
    const std::string prefix = argc > 2 ? argv[2] : "bust";
    const dla::Box box = dla::bounding_box(bust);
    constexpr int up = 2;  // the bust, like most scans, stands on z
    const dla::Vec3 crown = *std::max_element(bust.vertices.begin(), bust.vertices.end(),
                                              [&](const dla::Vec3& a, const dla::Vec3& b) { return a[up] < b[up]; });
    const double height = box.max[up] - box.min[up];

    // The crown painted red within a sixth of the height, the rest a light grey.
    std::ofstream ply(prefix + "_painted.ply");
    ply.precision(9);
    ply << "ply\nformat ascii 1.0\nelement vertex " << bust.vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
           "property uchar blue\nelement face " << bust.triangles.size()
        << "\nproperty list uchar uint vertex_indices\nend_header\n";
    for (const dla::Vec3& v : bust.vertices)
      ply << v.x() << ' ' << v.y() << ' ' << v.z() << ((v - crown).norm() < height / 6 ? " 255 0 0\n" : " 200 200 200\n");
    for (const auto& t : bust.triangles) ply << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    if (!ply.flush()) throw dla::IOError("cannot write " + prefix + "_painted.ply");

    // Two rods, a twentieth of the height across, down into the head either side of the crown.
    dla::TriangleMesh rods;
    for (const double side : {-1.0, 1.0}) {
      const dla::Vec3 base = crown + dla::Vec3(side * height / 8, 0.0, -height / 5);
      dla::append(rods, dla::make_open_can(base, height / 40, height / 2, 24));
    }
    dla::write_stl(rods, prefix + "_rods.stl");
    std::printf("wrote %s_painted.ply and %s_rods.stl\n", prefix.c_str(), prefix.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "artist_inputs: %s\n", e.what());
    return 1;
  }
  return 0;
}
