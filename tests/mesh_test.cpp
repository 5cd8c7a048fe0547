// Mesh files, repair, the inside test and the Embree intersector, each against an
// independent reference: files written and read back, the generalized winding number by solid
// angles, and segment/triangle hits by brute force.

#include "dla/io/mesh_writers.h"
#include "dla/mesh/constraint.h"
#include "dla/mesh/inside_test.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/mesh_repair.h"
#include "dla/mesh/shapes.h"
#include "dla/mesh/surface_distance.h"
#include "dla/mesh/surface_intersector.h"
#include "mesh_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace dla {
namespace {

using testing::ScratchDir;

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

//! A malformed file: its extension, its bytes, and what the message must say.
struct Fault {
  const char* ext;
  std::string bytes;
  const char* says;
};

//! Each fault read by parse(bytes, ext, name) is refused with a message that starts with the
//! file's name and says what is wrong.
template <class Parse>
void expect_named_faults(const std::vector<Fault>& faults, Parse&& parse) {
  for (const Fault& c : faults) {
    const std::string name = std::string("bad.") + c.ext;
    const std::string what = message_of([&] { parse(c.bytes, c.ext, name); });
    EXPECT_EQ(what.rfind(name + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(c.says), std::string::npos) << what;
  }
}

TEST(MeshFiles, BinaryStlRoundTrips) {
  ScratchDir dir;
  const TriangleMesh box = make_box(Vec3(-1, -2, -3), Vec3(1, 2, 3));
  write_stl(box, dir / "box.stl");
  EXPECT_NE(testing::read_file(dir / "box.stl").substr(0, 5), "solid");
  const TriangleMesh back = read_mesh(dir / "box.stl");
  ASSERT_EQ(back.triangles.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(back.vertices[back.triangles[t][k]], box.vertices[box.triangles[t][k]]);
}

TEST(MeshFiles, BinaryStlWhoseHeaderSaysSolid) {
  ScratchDir dir;
  write_stl(make_box(Vec3::Zero(), Vec3::Ones()), dir / "box.stl");
  std::string bytes = testing::read_file(dir / "box.stl");
  std::memcpy(bytes.data(), "solid box", 9);
  write_bytes(dir / "solid.stl", bytes);
  EXPECT_EQ(read_mesh(dir / "solid.stl").triangles.size(), 12u);
}

TEST(MeshFiles, AsciiStlWithCrlfAndWrongNormals) {
  const std::string text =
      "solid t\r\n facet normal 0 0 0\r\n  outer loop\r\n   vertex 0 0 0\r\n   vertex 1 0 0\r\n"
      "   vertex 0 1 0\r\n  endloop\r\n endfacet\r\n facet normal 9 9 9\r\n  outer loop\r\n   vertex 1 0 0\r\n"
      "   vertex 1 1 0\r\n   vertex 0 1 0\r\n  endloop\r\n endfacet\r\nendsolid t\r\n";
  const TriangleMesh mesh = parse_mesh(text, "stl", "t.stl");
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices[mesh.triangles[1][1]], Vec3(1, 1, 0));
}

TEST(MeshFiles, OffObjAndPlyPolygonsBecomeFans) {
  const std::string off = "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  EXPECT_EQ(parse_mesh(off, "off", "sq.off").triangles.size(), 2u);
  const std::string obj = "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 -1//1\n";
  const TriangleMesh from_obj = parse_mesh(obj, "obj", "sq.obj");
  ASSERT_EQ(from_obj.triangles.size(), 2u);
  EXPECT_EQ(from_obj.triangles[1][2], 3u);
  const std::string ply_ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 255\n1 0 0 255\n1 1 0 255\n0 1 0 255\n4 0 1 2 3\n";
  EXPECT_EQ(parse_mesh(ply_ascii, "ply", "sq.ply").triangles.size(), 2u);
  std::string ply_binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const double xyz[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
  ply_binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const unsigned char count = 3;
  const std::uint32_t ids[3] = {0, 1, 2};
  ply_binary.append(reinterpret_cast<const char*>(&count), 1);
  ply_binary.append(reinterpret_cast<const char*>(ids), sizeof ids);
  const TriangleMesh from_ply = parse_mesh(ply_binary, "ply", "t.ply");
  ASSERT_EQ(from_ply.triangles.size(), 1u);
  EXPECT_EQ(from_ply.vertices[1], Vec3(2, 0, 0));
}

TEST(MeshFiles, VertexColoursFromPlyOffAndObj) {
  // PLY: integer channels count to 255 (to 65535 for 16 bits), floats to 1.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 255 0 0 255\n1 0 0 0 51 0 255\n0 1 0 255 255 255 255\n3 0 1 2\n";
  const TriangleMesh from_ply = parse_mesh(ply, "ply", "t.ply");
  ASSERT_EQ(from_ply.colors.size(), 3u);
  EXPECT_EQ(from_ply.colors[0], Vec3(1, 0, 0));
  EXPECT_EQ(from_ply.colors[1], Vec3(0, 0.2, 0));
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const float rows[18] = {0, 0, 0, 0.5f, 0.25f, 1, 1, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1, 1};
  binary.append(reinterpret_cast<const char*>(rows), sizeof rows);
  const unsigned char count = 3;
  const std::uint32_t ids[3] = {0, 1, 2};
  binary.append(reinterpret_cast<const char*>(&count), 1);
  binary.append(reinterpret_cast<const char*>(ids), sizeof ids);
  EXPECT_EQ(parse_mesh(binary, "ply", "t.ply").colors[0], Vec3(0.5, 0.25, 1));
  // COFF: Geomview's integers to 255 or floats to 1, with an alpha or not; CNOFF has normals first.
  const TriangleMesh coff = parse_mesh("COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 0.5 0 1\n0 1 0 0 0 51\n3 0 1 2\n", "off", "t.off");
  ASSERT_EQ(coff.colors.size(), 3u);
  EXPECT_EQ(coff.colors[0], Vec3(1, 0, 0));
  EXPECT_EQ(coff.colors[1], Vec3(0, 0.5, 0));
  EXPECT_EQ(coff.colors[2], Vec3(0, 0, 0.2));
  const TriangleMesh cnoff = parse_mesh("CNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0\n1 0 0 0 0 1 0 255 0\n0 1 0 0 0 1 0 0 255\n3 0 1 2\n",
                                        "off", "t.off");
  EXPECT_EQ(cnoff.colors[2], Vec3(0, 0, 1));
  EXPECT_TRUE(parse_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off", "t.off").colors.empty());
  // OBJ: `v x y z r g b`; vertices left uncoloured are white.
  const TriangleMesh obj = parse_mesh("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0\nv 0 0 1 0 0 255\nf 1 2 3\nf 1 2 4\n", "obj", "t.obj");
  ASSERT_EQ(obj.colors.size(), 4u);
  EXPECT_EQ(obj.colors[1], Vec3(0, 1, 0));
  EXPECT_EQ(obj.colors[2], Vec3(1, 1, 1));
  EXPECT_EQ(obj.colors[3], Vec3(0, 0, 1));
  EXPECT_TRUE(parse_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "obj", "t.obj").colors.empty());
}

TEST(MeshFiles, AppendKeepsBothPartsAndTheirColours) {
  TriangleMesh mesh = make_box(Vec3::Zero(), Vec3::Ones());
  const std::size_t vertices = mesh.vertices.size(), triangles = mesh.triangles.size();
  TriangleMesh painted = make_box(Vec3::Constant(2), Vec3::Constant(3));
  painted.colors.assign(painted.vertices.size(), Vec3(1, 0, 0));
  append(mesh, painted);
  ASSERT_EQ(mesh.vertices.size(), 2 * vertices);
  ASSERT_EQ(mesh.triangles.size(), 2 * triangles);
  EXPECT_EQ(mesh.vertices[mesh.triangles[triangles][0]], painted.vertices[painted.triangles[0][0]]);
  ASSERT_EQ(mesh.colors.size(), mesh.vertices.size());
  EXPECT_EQ(mesh.colors.front(), Vec3(1, 1, 1));  // the part without colours is white
  EXPECT_EQ(mesh.colors.back(), Vec3(1, 0, 0));
  EXPECT_EQ(bounding_box(mesh).max, Vec3::Constant(3));
}

TEST(MeshFiles, MalformedFilesNameTheFileAndTheFault) {
  expect_named_faults({
      {"stl", "", "is empty"},
      {"stl", std::string(84, '\0'), "has no triangles"},
      {"stl", std::string(80, 'x') + std::string("\x02\0\0\0", 4) + std::string(50, '\0'), "not a valid binary STL"},
      {"stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0", "a vertex needs 3 numbers"},
      {"stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 nan\n vertex 1 0 0\n vertex 0 1 0\n endloop\n endfacet\nendsolid",
       "not a finite number"},
      {"off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n", "more than its"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "uses vertex 7"},
      {"obj", "v 0 0 0\nf 1 2 3\n", "uses vertex 1"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n0\n0\n", "without x, y and z"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n", "more than its 0 data bytes"},
      {"xyz", "1 2 3", "unknown mesh format"},
      {"off", "hello, world\n", "does not begin with OFF"},
      {"off", "COFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n", "vertex 0 (line 3) has a colour outside 0 to 255"},
      {"off", "COFF\n3 1 0\n0 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n", "no red, green and blue"},
      {"obj", "v 0 0 0 1 -0.5 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1 has a colour outside 0 to 1"},
  }, [](std::string_view bytes, std::string_view ext, const std::string& name) { parse_mesh(bytes, ext, name); });
}

TEST(PointFiles, CsvRowsHeadersAndPlyVertices) {
  const std::vector<Vec3> three{Vec3(1, 2, 3), Vec3(-4.5, 0, 6e-3), Vec3(7, 8, 9)};
  EXPECT_EQ(parse_points("1,2,3\n-4.5,0,6e-3\n\n7,8,9", "csv", "p.csv"), three);
  EXPECT_EQ(parse_points("# x y z\n1 2 3\r\n-4.5\t0 6e-3\n7, 8, 9\n", "xyz", "p.xyz"), three);
  // A header names the columns: dla3d's own CSV reads back.
  EXPECT_EQ(parse_points("id,x,y,z,parent,seed\n0,1,2,3,-1,0\n1,-4.5,0,6e-3,0,0\n2,7,8,9,1,0\n", "CSV", "d.csv"), three);
  EXPECT_EQ(parse_points("Z,Y,X\n3,2,1\n", "txt", "p.txt"), std::vector<Vec3>{Vec3(1, 2, 3)});
  // A PLY's vertices, faces read past; binary too.
  const std::string ply_ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n1 2 3\n-4.5 0 0.006\n7 8 9\n3 0 1 2\n";
  const std::vector<Vec3> from_ply = parse_points(ply_ascii, "ply", "p.ply");
  ASSERT_EQ(from_ply.size(), 3u);
  EXPECT_NEAR((from_ply[1] - three[1]).norm(), 0.0, 1e-6);
  std::string ply_binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nend_header\n";
  const double xyz[9] = {1, 2, 3, -4.5, 0, 6e-3, 7, 8, 9};
  ply_binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  EXPECT_EQ(parse_points(ply_binary, "ply", "b.ply"), three);
  ScratchDir dir;
  write_bytes(dir / "p.csv", "1,2,3\n-4.5,0,6e-3\n7,8,9\n");
  EXPECT_EQ(read_points(dir / "p.csv"), three);
  EXPECT_THROW(read_points(dir / "missing.csv"), IOError);
}

TEST(PointFiles, MalformedFilesNameTheFileAndTheFault) {
  expect_named_faults({
      {"csv", "", "is empty"},
      {"csv", "# nothing\n\n", "holds no points"},
      {"csv", "1,2\n", "line 1 has fewer than 3 fields"},
      {"csv", "1,2,3\n4,5,nan\n", "line 2: 'nan' is not a finite number"},
      {"csv", "1,2,3\n4,five,6\n", "line 2: 'five' is not a finite number"},
      {"csv", "a,b,c\n1,2,3\n", "a header without x, y and z"},
      {"csv", "x,y,z\n1,2,1e999\n", "not a finite number"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
       "holds no points"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", "without x, y and z"},
      {"json", "[1, 2, 3]", "unknown point file format"},
  }, [](std::string_view bytes, std::string_view ext, const std::string& name) { parse_points(bytes, ext, name); });
}

TEST(MeshRepair, MergesDropsAndClosesAHole) {
  TriangleMesh mesh = make_sphere(Vec3::Zero(), 5.0, 12, 24);
  const std::size_t full = mesh.triangles.size();
  mesh.triangles.erase(mesh.triangles.begin(), mesh.triangles.begin() + 24);  // the north cap
  mesh.triangles.push_back(mesh.triangles.front());                           // a repeat
  mesh.vertices.push_back(mesh.vertices[mesh.triangles[0][0]]);               // a duplicate vertex...
  mesh.triangles.push_back({mesh.triangles[5][0], mesh.triangles[5][1], static_cast<std::uint32_t>(mesh.vertices.size() - 1)});
  mesh.triangles.push_back({0, 0, 1});  // ...and a degenerate triangle
  RepairReport report;
  const TriangleMesh repaired = repair_mesh(mesh, {}, &report);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.holes_closed, 1u);
  EXPECT_EQ(report.merged_vertices, 1u);
  EXPECT_EQ(report.dropped_triangles, 2u);
  EXPECT_EQ(repaired.triangles.size(), full - 24 + 1 + report.hole_triangles);
  EXPECT_NE(report.summary().find("closed 1 hole"), std::string::npos) << report.summary();
}

TEST(MeshRepair, TurnsFlippedTrianglesToFaceOut) {
  TriangleMesh mesh = make_sphere(Vec3(1, 2, 3), 4.0);
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 2) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  RepairReport report;
  const TriangleMesh repaired = repair_mesh(mesh, {}, &report);
  EXPECT_EQ(report.reoriented_triangles, (mesh.triangles.size() + 1) / 2);
  EXPECT_NEAR(testing::generalized_winding_number(repaired, Vec3(1, 2, 3)), 1.0, 1e-9);

  TriangleMesh inside_out = make_sphere(Vec3::Zero(), 1.0);
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  const TriangleMesh turned = repair_mesh(inside_out);
  EXPECT_NEAR(testing::generalized_winding_number(turned, Vec3::Zero()), 1.0, 1e-9);
}

TEST(MeshRepair, KeepsEachVertexsColour) {
  // As an STL-like soup (every corner its own vertex) with a hole: colour by height.
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 5.0, 12, 24);
  TriangleMesh soup;
  for (std::size_t t = 24; t < sphere.triangles.size(); ++t) {  // the north cap left open
    std::array<std::uint32_t, 3> ids;
    for (int k = 0; k < 3; ++k) {
      ids[k] = static_cast<std::uint32_t>(soup.vertices.size());
      const Vec3& v = sphere.vertices[sphere.triangles[t][k]];
      soup.vertices.push_back(v);
      soup.colors.push_back(Vec3(v.z() > 0 ? 1.0 : 0.0, 0.5, 0.0));
    }
    soup.triangles.push_back(ids);
  }
  RepairReport report;
  const TriangleMesh repaired = repair_mesh(soup, {}, &report);
  ASSERT_TRUE(report.closed);
  ASSERT_EQ(repaired.colors.size(), repaired.vertices.size());
  for (std::size_t v = 0; v < repaired.vertices.size(); ++v)
    EXPECT_EQ(repaired.colors[v], Vec3(repaired.vertices[v].z() > 0 ? 1.0 : 0.0, 0.5, 0.0)) << v;
  EXPECT_TRUE(repair_mesh(sphere).colors.empty());
}

TEST(MeshRepair, AllDegenerateIsAnError) {
  TriangleMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  mesh.triangles = {{0, 1, 2}, {0, 0, 1}};
  EXPECT_NE(message_of([&] { repair_mesh(mesh); }).find("degenerate"), std::string::npos);
}

// The exact winding number against solid angles, and the grid against the exact test, at
// random points around `mesh` and as many within a millionth of its surface (the surface spawn
// asks there), on either side. At least one in `part` of the random points falls on each side.
void expect_inside_test_matches(const TriangleMesh& mesh, int samples, std::uint64_t seed, int part = 20) {
  const double band = 0.3;
  const InsideTest test(mesh, band, 0.25);
  const Box box = bounding_box(mesh);
  const Vec3 lo = box.min.array() - 1.0, hi = box.max.array() + 1.0;
  Rng rng(seed);
  int inside = 0;
  for (int i = 0; i < 2 * samples; ++i) {
    Vec3 p;
    if (i < samples) {
      for (int a = 0; a < 3; ++a) p[a] = lo[a] + (hi[a] - lo[a]) * rng.uniform();
    } else {
      const auto& t = mesh.triangles[std::min(mesh.triangles.size() - 1,
                                              static_cast<std::size_t>(rng.uniform() * mesh.triangles.size()))];
      double u = rng.uniform(), v = rng.uniform();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
      const Vec3 normal = (b - a).cross(c - a).normalized();
      if (!normal.allFinite()) continue;
      p = a + u * (b - a) + v * (c - a) + (rng.uniform() < 0.5 ? -1e-6 : 1e-6) * normal;
    }
    const double gwn = testing::generalized_winding_number(mesh, p);
    if (std::abs(gwn - std::round(gwn)) > 1e-6) continue;  // on the surface, up to rounding
    ASSERT_EQ(test.winding_number(p), static_cast<int>(std::lround(gwn))) << p.transpose();
    if (i >= samples) continue;
    inside += test.contains(p);
    const Region region = test.region(p);
    if (region != Region::surface) {
      EXPECT_EQ(test.contains(p), region == Region::inside) << p.transpose();
    }
  }
  EXPECT_GT(inside, samples / part);
  EXPECT_LT(inside, samples - samples / part);
}

// Every cell's bit against the set it was made from, on a grid whose sides are not whole
// bricks, sparse (most bricks hold no set cell and answer from their own bit) and dense.
TEST(BrickBits, MatchesTheSetCellByCell) {
  const VoxelGrid grid(Box{Vec3(-1.0, 2.0, 0.5), Vec3(8.0, 7.5, 11.0)}, 0.25, 0.5);
  ASSERT_EQ(grid.dims, (std::array<std::size_t, 3>{19, 12, 22}));
  for (const double density : {0.004, 0.5}) {
    Rng rng(7);
    std::vector<bool> set(grid.size());
    for (std::size_t i = 0; i < set.size(); ++i) set[i] = rng.uniform() < density;
    const BrickBits bits(grid, [&](std::size_t i) { return set[i]; });
    std::size_t found = 0;
    for (std::size_t z = 0; z < grid.dims[2]; ++z)
      for (std::size_t y = 0; y < grid.dims[1]; ++y)
        for (std::size_t x = 0; x < grid.dims[0]; ++x) {
          std::array<std::size_t, 3> c;
          ASSERT_TRUE(grid.locate(grid.center(x, y, z), c));
          ASSERT_EQ(c, (std::array<std::size_t, 3>{x, y, z}));
          const std::size_t i = (z * grid.dims[1] + y) * grid.dims[0] + x;
          ASSERT_EQ(grid.index(grid.center(x, y, z)), i);
          ASSERT_EQ(bits.test(c), set[i]) << x << ' ' << y << ' ' << z << " at density " << density;
          found += set[i];
        }
    EXPECT_GT(found, 0u);
  }
  std::array<std::size_t, 3> c;
  EXPECT_FALSE(grid.locate(grid.origin - Vec3::Constant(0.1), c));
  EXPECT_EQ(grid.index(grid.origin - Vec3::Constant(0.1)), grid.size());
}

TEST(InsideTest, MatchesSolidAnglesOnAClosedMesh) {
  expect_inside_test_matches(make_sphere(Vec3(0.5, -1, 2), 3.0, 10, 16), 4000, 1);
  expect_inside_test_matches(make_box(Vec3::Zero(), Vec3(2, 3, 4)), 4000, 2);
}

TEST(InsideTest, MatchesOnAnOpenMeshOnceItsHoleIsClosed) {
  const TriangleMesh open = read_mesh(TEST_DATA_DIR "/open_box.off");
  RepairReport report;
  const TriangleMesh closed = repair_mesh(open, {}, &report);
  ASSERT_TRUE(report.closed);
  expect_inside_test_matches(closed, 3000, 3);
  const InsideTest test(closed, 0.1, 0.5);
  EXPECT_TRUE(test.contains(Vec3(5, 5, 9.9)));  // just under the missing top
  EXPECT_FALSE(test.contains(Vec3(5, 5, 10.1)));
}

TEST(InsideTest, MatchesWithFlippedFacesOnceRepaired) {
  TriangleMesh mesh = make_sphere(Vec3::Zero(), 2.0, 8, 12);
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) std::swap(mesh.triangles[t][0], mesh.triangles[t][1]);
  expect_inside_test_matches(repair_mesh(mesh), 3000, 4);
}

TEST(InsideTest, CountsOverlapsOfASelfIntersectingMesh) {
  TriangleMesh two = make_box(Vec3::Zero(), Vec3(2, 2, 2));
  const TriangleMesh other = make_box(Vec3(1, 1, 1), Vec3(3, 3, 3));
  for (auto t : other.triangles) {
    for (auto& id : t) id += static_cast<std::uint32_t>(two.vertices.size());
    two.triangles.push_back(t);
  }
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  const InsideTest test(two, 0.1, 0.2);
  EXPECT_EQ(test.winding_number(Vec3(1.5, 1.5, 1.5)), 2);
  EXPECT_EQ(test.winding_number(Vec3(0.5, 0.5, 0.5)), 1);
  EXPECT_EQ(test.winding_number(Vec3(2.5, 0.5, 0.5)), 0);
  // Rays through a shared edge (the diagonal of a face) or a corner still count once.
  EXPECT_EQ(test.winding_number(Vec3(1, 1, 0.5)), 1);
  EXPECT_EQ(test.winding_number(Vec3(1.25, 0.75, 1.5)), 1);
  EXPECT_EQ(test.winding_number(Vec3(2.5, 1.5, 1.5)), 1);
}

// Two overlapping boxes are closed, so the winding number may count below a point as well as
// above it: the overlap still counts twice, at random points and near every face.
TEST(InsideTest, CountsOverlapsNearTheSurface) {
  TriangleMesh two = make_box(Vec3::Zero(), Vec3(2, 2, 2));
  append(two, make_box(Vec3(1, 1, 1), Vec3(3, 3, 3)));
  expect_inside_test_matches(two, 3000, 6);
}

// A mesh with a hole keeps the ray up: the crossings above a point, as a scan of every triangle
// counts them.
TEST(InsideTest, AnOpenMeshCountsTheCrossingsAbove) {
  const TriangleMesh open = read_mesh(TEST_DATA_DIR "/open_box.off");
  const InsideTest test(open, 0.3, 0.25);
  const Box box = bounding_box(open);
  Rng rng(7);
  int counted = 0;
  for (int i = 0; i < 3000; ++i) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] - 1.0 + (box.max[a] - box.min[a] + 2.0) * rng.uniform();
    int crossings = 0;  // signed, as the normal's z
    for (const auto& t : open.triangles) {
      const Vec3 &a = open.vertices[t[0]], &b = open.vertices[t[1]], &c = open.vertices[t[2]];
      const Vec3 n = (b - a).cross(c - a);
      if (n.z() == 0.0) continue;
      const double z = a.z() - (n.x() * (p.x() - a.x()) + n.y() * (p.y() - a.y())) / n.z();
      const Vec3 q(p.x(), p.y(), z);
      if (z > p.z() && n.dot((b - a).cross(q - a)) > 0 && n.dot((c - b).cross(q - b)) > 0 &&
          n.dot((a - c).cross(q - c)) > 0)
        crossings += n.z() > 0 ? 1 : -1;
    }
    ASSERT_EQ(test.winding_number(p), crossings) << p.transpose();
    counted += crossings != 0;
  }
  EXPECT_GT(counted, 100);  // below the box: inside it, the ray leaves by the hole
}

// A CAD model's cylinder: caps fanned from their centres into long, thin, slanted triangles,
// which the buckets take by their shadows, not their bounding boxes.
TEST(InsideTest, MatchesSolidAnglesOnFannedCaps) {
  constexpr int segments = 200;
  TriangleMesh can;
  can.vertices = {Vec3(0, 0, 0), Vec3(0, 0, 4)};
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / segments;
    const Vec3 rim(5 * std::cos(a), 5 * std::sin(a), 0.0);
    can.vertices.push_back(rim);
    can.vertices.push_back(rim + Vec3(0, 0, 4));
  }
  for (int i = 0; i < segments; ++i) {
    const auto b = static_cast<std::uint32_t>(2 + 2 * i), n = static_cast<std::uint32_t>(2 + 2 * ((i + 1) % segments));
    can.triangles.push_back({0, n, b});
    can.triangles.push_back({1, b + 1, n + 1});
    can.triangles.push_back({b, n, n + 1});
    can.triangles.push_back({b, n + 1, b + 1});
  }
  // Turned a little about x, so that the caps slant across the columns.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.3, Vec3::UnitX()).toRotationMatrix();
  for (Vec3& v : can.vertices) v = tilt * v;
  expect_inside_test_matches(can, 2000, 9);
}

// CGAL's meshes, repaired as a constraint repairs them: three bodies in one mesh, and shapes
// with thin limbs (an elephant's trunk, a hand's fingers, a cactus' arms).
TEST(InsideTest, MatchesSolidAnglesOnCgalsMeshes) {
  int checked = 0;
  for (const char* name : {"blobby_3cc", "elephant", "hand", "cactus"}) {
    const std::string path = std::string(CGAL_MESHES_DIR) + "/" + name + ".off";
    if (!std::filesystem::exists(path)) continue;
    SCOPED_TRACE(name);
    TriangleMesh mesh = repair_mesh(read_mesh(path));
    const Box box = bounding_box(mesh);
    for (Vec3& v : mesh.vertices) v = (v - box.min) * (10.0 / (box.max - box.min).maxCoeff());  // 10 long
    expect_inside_test_matches(mesh, 400, 8, 50);  // the elephant fills 4% of its box
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "CGAL's meshes are missing: install libcgal-demo and run cmake again";
}

TEST(InsideTest, MatchesSolidAnglesOnTheBust) {
  DLA_NEED_BUST(path);
  const TriangleMesh bust = repair_mesh(read_mesh(path));
  expect_inside_test_matches(bust, 300, 5);
}

struct ClearCount {
  int clear = 0;      // offset triangles the test calls clear
  int near = 0;       // offset triangles a scan finds within the margin or across the surface
  int asked = 0;
};

// Triangles of `mesh` moved `offset` along their normals, each asked whether it is clear of the
// surface. Every one called clear is checked by a scan of every triangle at its corners and at
// random points of it: farther than the margin from all, with the winding number of its centre
// at all. Those the scan finds near or across the surface must not be called clear.
ClearCount check_clear_triangles(const TriangleMesh& mesh, double offset, int count, std::uint64_t seed) {
  const InsideTest test(mesh, std::abs(offset) + 0.1, 0.2);
  const double margin = 1e-4 * std::max(std::abs(offset), 1e-3);
  Rng rng(seed);
  ClearCount counted;
  for (int i = 0; i < count; ++i) {
    const auto& t = mesh.triangles[std::min(mesh.triangles.size() - 1,
                                            static_cast<std::size_t>(rng.uniform() * mesh.triangles.size()))];
    const Vec3 normal = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).normalized();
    if (!normal.allFinite()) continue;
    const Vec3 a = mesh.vertices[t[0]] + offset * normal, b = mesh.vertices[t[1]] + offset * normal,
               c = mesh.vertices[t[2]] + offset * normal;
    const bool clear = test.clear_of_surface(a, b, c, margin);
    ++counted.asked;
    counted.clear += clear;
    const int centre = test.winding_number((a + b + c) / 3.0);
    bool near = false;
    for (int k = 0; k < 8 && !near; ++k) {
      double u = k == 1 ? 1.0 : k < 3 ? 0.0 : rng.uniform(), v = k == 2 ? 1.0 : k < 3 ? 0.0 : rng.uniform();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const Vec3 p = a + u * (b - a) + v * (c - a);
      for (const auto& q : mesh.triangles) {
        const Vec3 closest = closest_point_on_triangle(p, mesh.vertices[q[0]], mesh.vertices[q[1]], mesh.vertices[q[2]]);
        if ((closest - p).norm() <= margin) near = true;
      }
      if (!near && std::abs(testing::generalized_winding_number(mesh, p) - centre) > 0.5) near = true;
    }
    counted.near += near;
    EXPECT_FALSE(near && clear) << "a triangle of " << a.transpose() << ", " << b.transpose() << ", " << c.transpose();
  }
  return counted;
}

// The mesh's own triangles are never clear; moved off it, most are, except where the mesh is
// thinner than the move or crosses itself.
TEST(InsideTest, ClearTrianglesKeepTheirMarginAndOneWindingNumber) {
  const TriangleMesh sphere = make_sphere(Vec3(0.5, -1, 2), 3.0, 12, 24);
  EXPECT_EQ(check_clear_triangles(sphere, 0.0, 50, 1).clear, 0);
  for (const double offset : {-0.3, 0.3}) {
    const ClearCount counted = check_clear_triangles(sphere, offset, 200, 2);
    EXPECT_GT(counted.clear, counted.asked * 9 / 10) << offset;
  }
  // A box thinner than the move: moved in, a face's triangles cross the sides.
  const ClearCount thin = check_clear_triangles(make_box(Vec3::Zero(), Vec3(1.6, 1.6, 0.5)), -0.3, 100, 3);
  EXPECT_GT(thin.near, 10);
  // Two spheres that overlap: the triangles of each near the curve where they cross stay near.
  TriangleMesh two = make_sphere(Vec3::Zero(), 2.0, 12, 24);
  append(two, make_sphere(Vec3(2.5, 0.3, 0.2), 2.0, 12, 24));
  const ClearCount overlap = check_clear_triangles(two, -0.2, 300, 4);
  EXPECT_GT(overlap.near, 10);
  EXPECT_GT(overlap.clear, 10);
}

TEST(InsideTest, ClearTrianglesOnTheBust) {
  DLA_NEED_BUST(path);
  const TriangleMesh bust = repair_mesh(read_mesh(path));
  for (const double offset : {-0.05, 0.2}) {  // half the fine spacing inward, half the default outward
    const ClearCount counted = check_clear_triangles(bust, offset, 60, 5);
    EXPECT_GT(counted.clear, counted.asked * 2 / 3) << offset;
  }
}

TEST(SurfaceIntersector, MatchesBruteForce) {
  const TriangleMesh mesh = make_sphere(Vec3(0.2, 0.1, -0.3), 2.0, 10, 20);
  const SurfaceIntersector hits(mesh);
  Rng rng(7);
  int hit_count = 0;
  for (int i = 0; i < 3000; ++i) {
    Vec3 a, b;
    for (int k = 0; k < 3; ++k) {
      a[k] = 6.0 * rng.uniform() - 3.0;
      b[k] = a[k] + 3.0 * rng.uniform() - 1.5;
    }
    const double expected = testing::brute_first_hit(mesh, a, b);
    const double t = hits.first_hit(a, b, 0.0, 1.0);
    if (expected >= 0.0) {
      ++hit_count;
      EXPECT_NEAR(t, expected, 1e-5) << a.transpose() << " -> " << b.transpose();
    } else if (t >= 0.0) {
      EXPECT_GT(t, 1.0 - 1e-5) << "a hit the brute force does not see";  // float rounding at the end
    }
  }
  EXPECT_GT(hit_count, 300);
}

TEST(SurfaceIntersector, SegmentsThroughVerticesAndEdgesHit) {
  // Embree's default scene lets some of these through; the robust one must not.
  const TriangleMesh mesh = make_sphere(Vec3::Zero(), 1.0, 16, 32);
  const SurfaceIntersector hits(mesh);
  for (const Vec3& v : mesh.vertices) EXPECT_GE(hits.first_hit(0.5 * v, 1.5 * v, 0.0, 1.0), 0.0) << v.transpose();
  for (const auto& t : mesh.triangles) {
    const Vec3 mid = 0.5 * (mesh.vertices[t[0]] + mesh.vertices[t[1]]);
    EXPECT_GE(hits.first_hit(0.5 * mid, 1.5 * mid, 0.0, 1.0), 0.0) << mid.transpose();
  }
}

}  // namespace
}  // namespace dla
