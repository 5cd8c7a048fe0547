// The solid in the programs makers and VFX artists open it with: PrusaSlicer reads the STL and
// the 3MF as one manifold part of dla3d's volume and slices it to G-code, admesh finds nothing to
// fix, Blender's 3D-Print Toolbox finds no non-manifold edge and no intersecting face, Blender
// reads the .vdb's grids, and Cycles renders the solid and the volume. Each test skips, by name,
// when its client is missing (clients.h).
#include "cli_util.h"
#include "clients.h"
#include "png_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

//! The number after `key` and `sep` in `text` (the first match), or NaN.
double number_after(const std::string& text, const std::string& key, const std::string& sep = " = ") {
  const std::size_t at = text.find(key + sep);
  return at == std::string::npos ? std::nan("") : std::atof(text.c_str() + at + key.size() + sep.size());
}

//! Runs a shell command in `dir`, its output to `log`; returns the output, failing on a non-zero
//! exit.
std::string run_in(const ScratchDir& dir, const std::string& command, const std::string& log) {
  const int status = std::system(("cd '" + dir.path().string() + "' && " + command + " > " + log + " 2>&1").c_str());
  const std::string out = read_file(dir / log);
  EXPECT_EQ(status, 0) << command << "\n" << out;
  return out;
}

//! The solids PrusaSlicer is given: a DLA tree with the pipe radius, a space colonization tree
//! and a blob (metaball spheres, smoothed), each sized to 60 mm.
struct Case {
  const char* name;
  const char* command;
};
constexpr Case kCases[] = {
    {"dla", "-n 1200 --radius pipe"},
    {"colonize", "colonize --attractors 600"},
    {"blob", "-n 400 --solid-shape spheres --radius uniform --base-radius 0.6 --solid-smooth 0.5"},
};

TEST(PrusaSlicer, ReadsEachSolidAsOneManifoldPartOfItsVolumeAndSlicesIt) {
  DLA_NEED_PRUSA_SLICER();
  ScratchDir dir;
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const std::string prefix = k.name;
    const testing::CliRun grown =
        testing::dla3d(dir, std::string(k.command) + " --print-size 60 --formats stl,3mf,json -q -o " + prefix);
    ASSERT_EQ(grown.exit_code, 0) << grown.err;
    const std::string json = read_file(dir / (prefix + ".json"));
    const double volume = number_after(json, "\"volume\"", ": ");
    EXPECT_EQ(number_after(json, "\"shells\"", ": "), 1.0);
    for (const std::string& file : {prefix + ".stl", prefix + ".3mf"}) {
      SCOPED_TRACE(file);
      const std::string info = run_in(dir, "prusa-slicer --info '" + file + "'", "info.txt");
      EXPECT_NE(info.find("manifold = yes"), std::string::npos) << info;
      EXPECT_EQ(number_after(info, "number_of_parts"), 1.0) << info;
      EXPECT_NEAR(number_after(info, "volume"), volume, 0.01 * volume) << info;
      EXPECT_NEAR(std::max({number_after(info, "size_x"), number_after(info, "size_y"), number_after(info, "size_z")}),
                  60.0, 1e-3) << info;
    }
  }
  // Sliced at 0.2 mm layers into G-code, with no error.
  run_in(dir, "prusa-slicer --export-gcode --layer-height 0.2 --center 100,100 --output dla.gcode dla.stl", "slice.txt");
  const std::string gcode = read_file(dir / "dla.gcode");
  EXPECT_GT(std::count(gcode.begin(), gcode.end(), '\n'), 1000) << read_file(dir / "slice.txt");
  EXPECT_NE(gcode.find(";LAYER_CHANGE"), std::string::npos);
}

TEST(Admesh, FindsNothingToFixInTheStl) {
  DLA_NEED_ADMESH();
  ScratchDir dir;
  const testing::CliRun grown = testing::dla3d(dir, "-n 800 --radius pipe --formats stl,json -q -o tree");
  ASSERT_EQ(grown.exit_code, 0) << grown.err;
  const std::string report = run_in(dir, "admesh tree.stl", "admesh.txt");
  EXPECT_EQ(number_after(report, "Total disconnected facets", "        :"), 0.0) << report;
  for (const char* line : {"Number of parts       :     1", "Degenerate facets     :     0", "Edges fixed           :     0",
                           "Facets removed        :     0", "Facets added          :     0", "Facets reversed       :     0",
                           "Backwards edges       :     0", "Normals fixed         :     0"})
    EXPECT_NE(report.find(line), std::string::npos) << line << "\n" << report;
}

TEST(GltfValidator, FindsNoErrorInTheSolidGlb) {
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  for (const char* colour : {"none", "age"}) {
    SCOPED_TRACE(colour);
    const testing::CliRun grown = testing::dla3d(
        dir, std::string("-n 400 --radius pipe --formats solid-glb -q -o ") + colour + " --color-by " + colour);
    ASSERT_EQ(grown.exit_code, 0) << grown.err;
    EXPECT_EQ(testing::validate_glb(dir / (std::string(colour) + "_solid.glb")), "");
  }
}

//! Pixels that differ from the render's dark background by more than its noise.
long lit_pixels(const testing::Picture& picture) {
  const std::array<int, 3> background = picture.at(0, 0);
  long lit = 0;
  for (std::size_t y = 0; y < picture.height; ++y)
    for (std::size_t x = 0; x < picture.width; ++x) {
      const std::array<int, 3> p = picture.at(x, y);
      lit += std::abs(p[0] - background[0]) + std::abs(p[1] - background[1]) + std::abs(p[2] - background[2]) > 40;
    }
  return lit;
}

TEST(Blender, ChecksTheSolidWithItsPrintToolboxAndRendersItAndTheVolume) {
  DLA_NEED_BLENDER();
  ScratchDir dir;
  const testing::CliRun grown =
      testing::dla3d(dir, "-n 600 --radius pipe --color-by age --formats stl,solid-glb,vdb,json -q -o tree");
  ASSERT_EQ(grown.exit_code, 0) << grown.err;
  const std::string log =
      run_in(dir, "blender -b --factory-startup --python-exit-code 1 --python '" TEST_CLIENTS_DIR
                  "/blender_solid.py' -- tree.stl tree_solid.glb tree.vdb render", "blender.txt");
  const std::size_t at = log.find("DLA3D ");
  ASSERT_NE(at, std::string::npos) << log;
  const std::string line = log.substr(at, log.find('\n', at) - at);
  for (const char* mesh : {"stl", "glb"}) {
    SCOPED_TRACE(mesh);
    const std::string m = mesh;
    EXPECT_EQ(number_after(line, "\"" + m + "_objects\"", ": "), 1.0) << line;
    EXPECT_GT(number_after(line, "\"" + m + "_faces\"", ": "), 1000.0) << line;
    EXPECT_EQ(number_after(line, "\"" + m + "_non_manifold\"", ": "), 0.0) << line;
    EXPECT_EQ(number_after(line, "\"" + m + "_bad_contiguous\"", ": "), 0.0) << line;
    EXPECT_EQ(number_after(line, "\"" + m + "_intersecting\"", ": "), 0.0) << line;
  }
  EXPECT_NE(line.find("\"grids\": [\"age\", \"density\", \"surface\"]"), std::string::npos) << line;
  for (const char* render : {"render_solid.png", "render_volume.png"}) {
    SCOPED_TRACE(render);
    const testing::Picture picture = testing::read_png(dir / render);
    ASSERT_EQ(picture.width, 200u);
    const long lit = lit_pixels(picture);
    // Not blank, and framed: the structure covers part of the picture, not all of it.
    EXPECT_GT(lit, static_cast<long>(picture.width * picture.height / 20)) << lit;
    EXPECT_LT(lit, static_cast<long>(picture.width * picture.height * 9 / 10)) << lit;
  }
}

// A discharge's .vdb is a glow: Blender imports it as a volume, and Cycles renders its density
// as emission on a black sky, the bolt lit and framed.
TEST(Blender, RendersADischargesVolumeAsAGlow) {
  DLA_NEED_BLENDER();
  ScratchDir dir;
  const testing::CliRun grown = testing::dla3d(
      dir, "breakdown -n 3000 --eta 2 --target-plane y=-20 --radius pipe --formats vdb,json -q -o bolt");
  ASSERT_EQ(grown.exit_code, 0) << grown.err;
  const std::string log =
      run_in(dir, "blender -b --factory-startup --python-exit-code 1 --python '" TEST_CLIENTS_DIR
                  "/blender_glow.py' -- bolt.vdb glow.png", "blender.txt");
  const std::size_t at = log.find("DLA3D ");
  ASSERT_NE(at, std::string::npos) << log;
  const std::string line = log.substr(at, log.find('\n', at) - at);
  EXPECT_NE(line.find("\"density\""), std::string::npos) << line;
  const testing::Picture picture = testing::read_png(dir / "glow.png");
  ASSERT_EQ(picture.width, 200u);
  const std::array<int, 3> sky = picture.at(0, 0);
  EXPECT_LE(std::max({sky[0], sky[1], sky[2]}), 4);  // black, but for the view transform's floor
  const long lit = lit_pixels(picture);
  EXPECT_GT(lit, static_cast<long>(picture.width * picture.height / 40)) << lit;
  EXPECT_LT(lit, static_cast<long>(picture.width * picture.height / 2)) << lit;
}

}  // namespace
}  // namespace dla
