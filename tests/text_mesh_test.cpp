// 3D text (--text): the extruded glyphs are a closed, consistently oriented mesh, the inside
// test agrees with solid angles on it, its volume is the glyphs' area times the depth, and
// each letter gets a seed deep inside.

#include "dla/mesh/constraint.h"
#include "dla/mesh/mesh_repair.h"
#include "dla/mesh/text.h"
#include "mesh_util.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <utility>

namespace dla {
namespace {

double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  return volume;
}

TextMesh text(const std::string& words) {
  TextOptions options;
  options.text = words;
  return text_mesh(options);
}

TEST(TextMesh, IsClosedAndConsistentlyOriented) {
  const TextMesh dla = text("DLA");
  // Every edge once each way: closed, and each triangle agrees with its neighbours.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : dla.mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << edge.first << " -> " << edge.second;
    ASSERT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << " -> " << edge.second << " is a border";
  }
  EXPECT_GT(signed_volume(dla.mesh), 0.0) << "facing in";
  RepairReport report;
  repair_mesh(dla.mesh, {}, &report);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.summary(), "nothing to repair");
  const Box box = bounding_box(dla.mesh);
  EXPECT_DOUBLE_EQ(box.min.z(), 0.0);
  EXPECT_DOUBLE_EQ(box.max.z(), 25.0);
  EXPECT_NEAR(box.max.y() - box.min.y(), 73.0, 2.0);  // a capital's height, in a 100 em
}

TEST(TextMesh, VolumeIsTheGlyphsAreaTimesTheDepth) {
  // DejaVu Sans Bold's I is a plain bar: its box is the glyph.
  const TextMesh bar = text("I");
  const Box box = bounding_box(bar.mesh);
  const Vec3 size = box.max - box.min;
  EXPECT_NEAR(signed_volume(bar.mesh), size.x() * size.y() * size.z(), 1e-6 * size.prod());
  // A line below: the second line's letters stand lower by the font's line height.
  const TextMesh lines = text("I\nI");
  ASSERT_EQ(lines.glyph_seeds.size(), 2u);
  EXPECT_NEAR(lines.glyph_seeds[0].x(), lines.glyph_seeds[1].x(), 1e-9);
  EXPECT_LT(lines.glyph_seeds[1].y(), lines.glyph_seeds[0].y() - 100.0);
  EXPECT_NEAR(signed_volume(lines.mesh), 2 * signed_volume(bar.mesh), 1e-6 * size.prod());
}

TEST(TextMesh, InsideTestMatchesSolidAnglesAndTheGlyphs) {
  const TextMesh words = text("DLA O");
  const MeshConstraint constraint(words.mesh, {}, 1.0);
  const Box box = bounding_box(words.mesh);
  Rng rng(3, 0);
  for (int i = 0; i < 1500; ++i) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] - 3 + (box.max[a] - box.min[a] + 6) * rng.uniform();
    ASSERT_EQ(constraint.inside_test().contains(p), testing::generalized_winding_number(words.mesh, p) > 0.5)
        << p.transpose();
  }
  // The O's counter is outside, its ring inside, and nothing is inside beyond the depth.
  const TextMesh o = text("O");
  const MeshConstraint ring(o.mesh, {}, 1.0);
  const Box o_box = bounding_box(o.mesh);
  const Vec3 centre = 0.5 * (o_box.min + o_box.max);
  EXPECT_FALSE(ring.inside_test().contains(centre)) << "the counter";
  EXPECT_TRUE(ring.inside_test().contains(Vec3(o_box.min.x() + 4.0, centre.y(), centre.z()))) << "the ring";
  EXPECT_FALSE(ring.inside_test().contains(Vec3(o_box.min.x() + 4.0, centre.y(), 25.5))) << "beyond the depth";
  // A seed in each letter (the space has none), deep in it.
  ASSERT_EQ(words.glyph_seeds.size(), 4u);
  for (const Vec3& seed : words.glyph_seeds) {
    EXPECT_TRUE(constraint.inside_test().contains(seed)) << seed.transpose();
    EXPECT_GT(constraint.distance_to_surface(seed), 5.0) << seed.transpose();
  }
}

TEST(TextMesh, BadTextAndFontsAreClearErrors) {
  EXPECT_THROW(text(""), InvalidInput);
  EXPECT_THROW(text("   \n "), InvalidInput);
  EXPECT_THROW(text("\xff"), InvalidInput);      // not UTF-8
  EXPECT_THROW(text("\xe2\x82"), InvalidInput);  // cut short
  EXPECT_THROW(text("\xf3\xa0\x80\x80"), InvalidInput);  // a character DejaVu does not have
  EXPECT_THROW(text(std::string(10'001, 'x')), InvalidInput);
  TextOptions options;
  options.text = "DLA";
  options.font = "/nonexistent/font.ttf";
  EXPECT_THROW(text_mesh(options), IOError);
  options.font = kDefaultFont;
  options.depth = 0.0;
  EXPECT_THROW(text_mesh(options), InvalidInput);
  options.depth = 25.0;
  options.size = std::numeric_limits<double>::infinity();
  EXPECT_THROW(text_mesh(options), InvalidInput);
}

}  // namespace
}  // namespace dla
