// Leaves in the glb (--leaf, leaf.h): one node at each instancing point, placed, turned and
// scaled as the point says, referencing the leaf's mesh carried over with its data byte for
// byte; the leaf's own node transform goes with it; files that are not such a leaf are refused
// in one line.

#include "cli_util.h"
#include "test_util.h"
#include "dla/io/leaf.h"
#include "dla/io/mesh_writers.h"
#include "dla/models/dla.h"
#include "dla/run/output.h"
#include "dla/run/run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dla {
namespace {

using nlohmann::json;
using testing::ScratchDir;
using testing::read_file;

constexpr const char* kLeaf = DLA_EXAMPLES_DIR "/leaf.glb";

struct GlbFile {
  json gltf;
  std::string binary;
};

std::uint32_t word_at(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

GlbFile read_glb(const std::string& path) {
  const std::string bytes = read_file(path);
  const std::uint32_t json_length = word_at(bytes, 12);
  GlbFile glb{json::parse(bytes.substr(20, json_length)), ""};
  const std::size_t at = 20 + json_length;
  if (at + 8 <= bytes.size()) glb.binary = bytes.substr(at + 8, word_at(bytes, at));
  return glb;
}

std::string glb_bytes(const std::string& text, const std::string& binary) {
  std::string gltf = text;
  gltf.resize((gltf.size() + 3) / 4 * 4, ' ');
  const auto word = [](std::uint32_t value) { return std::string(reinterpret_cast<const char*>(&value), 4); };
  const std::size_t length = 12 + 8 + gltf.size() + (binary.empty() ? 0 : 8 + binary.size());
  std::string bytes = "glTF" + word(2) + word(static_cast<std::uint32_t>(length)) +
                      word(static_cast<std::uint32_t>(gltf.size())) + "JSON" + gltf;
  if (!binary.empty()) bytes += word(static_cast<std::uint32_t>(binary.size())) + std::string("BIN\0", 4) + binary;
  return bytes;
}

Cluster tree() {
  DlaOptions o;
  o.particles = 1500;
  o.rng_seed = 5;
  return grow(o);
}

Eigen::Vector3d vector_of(const json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

Eigen::Quaterniond rotation_of(const json& node) {
  const json& q = node["rotation"];
  return {q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>()};
}

TEST(Leaves, OneNodeAtEachInstancingPointAlongItsDirectionAndScale) {
  ScratchDir dir;
  const Cluster c = tree();
  const Look look = make_look(c, {});
  const Leaf leaf = read_leaf(kLeaf);
  write_glb(c, look, dir / "bare.glb");
  const GlbWritten written = write_glb(c, look, dir / "leafy.glb", {0, &leaf, {}});
  const std::vector<Instance> points = instancing_points(c, look.attributes, {});
  ASSERT_GT(points.size(), 100u);
  EXPECT_EQ(written.leaves, points.size());
  const GlbFile bare = read_glb(dir / "bare.glb"), leafy = read_glb(dir / "leafy.glb"), source = read_glb(kLeaf);

  const json& nodes = leafy.gltf["nodes"];
  ASSERT_EQ(nodes.size(), 2 + points.size());
  EXPECT_EQ(leafy.gltf["scenes"][0]["nodes"], json({0, 1}));
  EXPECT_EQ(nodes[1]["name"], "leaves");
  ASSERT_EQ(nodes[1]["children"].size(), points.size());
  const double size = (c.particles.back().position - c.particles.front().position).norm() + 1.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Instance& point = points[k];
    const json& node = nodes[2 + k];
    SCOPED_TRACE(node.dump());
    EXPECT_EQ(nodes[1]["children"][k], 2 + k);
    EXPECT_EQ(node["name"], "leaf " + std::to_string(point.particle));
    EXPECT_EQ(node["mesh"], 1);
    EXPECT_LT((vector_of(node["translation"]) - point.position).norm(), 1e-6 * size);
    const Eigen::Quaterniond q = rotation_of(node);
    EXPECT_NEAR(q.norm(), 1.0, 1e-6);
    EXPECT_GT((q * Eigen::Vector3d::UnitY()).dot(point.direction), 1.0 - 1e-6) << "the stem along the direction";
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(node["scale"][a].get<double>(), point.scale, 1e-6 * point.scale);
  }

  // The tubes are as without the leaf; the leaf's data follows them byte for byte, and its
  // mesh, materials and views point at it, renumbered.
  const std::string& tubes = bare.binary;
  ASSERT_EQ(leafy.binary.size(), tubes.size() + leaf.binary.size());
  EXPECT_EQ(leafy.binary.compare(0, tubes.size(), tubes), 0);
  EXPECT_EQ(leafy.binary.substr(tubes.size()), leaf.binary);
  const std::size_t views = bare.gltf["bufferViews"].size(), accessors = bare.gltf["accessors"].size();
  for (std::size_t v = 0; v < source.gltf["bufferViews"].size(); ++v) {
    const json& view = leafy.gltf["bufferViews"][views + v];
    EXPECT_EQ(view["buffer"], 0);
    EXPECT_EQ(view["byteOffset"].get<std::size_t>(),
              source.gltf["bufferViews"][v].value("byteOffset", std::size_t{0}) + tubes.size());
    EXPECT_EQ(view["byteLength"], source.gltf["bufferViews"][v]["byteLength"]);
  }
  for (std::size_t a = 0; a < source.gltf["accessors"].size(); ++a) {
    json expected = source.gltf["accessors"][a];
    expected["bufferView"] = expected["bufferView"].get<std::size_t>() + views;
    EXPECT_EQ(leafy.gltf["accessors"][accessors + a], expected);
  }
  const json& primitive = leafy.gltf["meshes"][1]["primitives"][0];
  const json& original = source.gltf["meshes"][0]["primitives"][0];
  for (const auto& [name, index] : original["attributes"].items())
    EXPECT_EQ(primitive["attributes"][name], index.get<std::size_t>() + accessors) << name;
  EXPECT_EQ(primitive["indices"], original["indices"].get<std::size_t>() + accessors);
  EXPECT_EQ(primitive["material"], 1);
  EXPECT_EQ(leafy.gltf["materials"][1], source.gltf["materials"][0]);
  EXPECT_EQ(leafy.gltf["buffers"][0]["byteLength"], leafy.binary.size());

  // The same again: the same bytes. The levels of detail carry no leaves.
  write_glb(c, look, dir / "again.glb", {1, &leaf, {}});
  EXPECT_EQ(read_file(dir / "again.glb"), read_file(dir / "leafy.glb"));
  EXPECT_EQ(read_glb(dir / "again_lod1.glb").gltf["nodes"].size(), 1u);

  // Thinned points, fewer leaves; each is one of the points.
  InstanceOptions every_third;
  every_third.every = 3;
  write_glb(c, look, dir / "sparse.glb", {0, &leaf, every_third});
  EXPECT_EQ(read_glb(dir / "sparse.glb").gltf["nodes"].size(), 2 + (points.size() + 2) / 3);
}

// A leaf whose mesh sits under nodes of its own (a parent's scale, its own offset and turn):
// every leaf node is the point's placement after that transform.
TEST(Leaves, TheLeafsOwnNodeTransformGoesWithIt) {
  ScratchDir dir;
  const GlbFile source = read_glb(kLeaf);
  json gltf = source.gltf;
  const double half = std::sqrt(0.5);
  gltf["nodes"] = json::array({{{"children", {1}}, {"scale", {2, 2, 2}}},
                               {{"mesh", 0}, {"translation", {0, 0.5, 0}}, {"rotation", {0, half, 0, half}}}});
  std::ofstream(dir / "nested.glb", std::ios::binary) << glb_bytes(gltf.dump(), source.binary);
  const Leaf leaf = read_leaf(dir / "nested.glb");
  const Cluster c = tree();
  const Look look = make_look(c, {});
  write_glb(c, look, dir / "tree.glb", {0, &leaf, {}});
  const std::vector<Instance> points = instancing_points(c, look.attributes, {});
  const GlbFile placed = read_glb(dir / "tree.glb");
  const json& nodes = placed.gltf["nodes"];
  ASSERT_EQ(nodes.size(), 2 + points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Instance& point = points[k];
    const json& node = nodes[2 + k];
    SCOPED_TRACE(node.dump());
    // The leaf's origin went 0.5 up its stem and was doubled: one point's scale along its direction.
    const Eigen::Vector3d expected = point.position + point.scale * point.direction;
    EXPECT_LT((vector_of(node["translation"]) - expected).norm(), 1e-5 * (1 + point.position.norm()));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(node["scale"][a].get<double>(), 2 * point.scale, 1e-6 * point.scale);
    // Its turn: a quarter about its stem (x to -z) before the stem is laid along the direction.
    const Eigen::Quaterniond along = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), point.direction);
    EXPECT_LT((rotation_of(node) * Eigen::Vector3d::UnitX() - along * -Eigen::Vector3d::UnitZ()).norm(), 1e-5);
  }
}

// Files that are not a leaf, each refused with one line naming `leaf`; a missing one is an
// IOError.
TEST(Leaves, FilesThatAreNotALeafAreRefusedInOneLine) {
  ScratchDir dir;
  const GlbFile source = read_glb(kLeaf);
  const auto edited = [&](const std::function<void(json&)>& edit) {
    json gltf = source.gltf;
    edit(gltf);
    return glb_bytes(gltf.dump(), source.binary);
  };
  std::string cut = read_file(kLeaf);
  cut.resize(cut.size() - 100);
  std::string version_one = read_file(kLeaf);
  version_one[4] = 1;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"solid ascii\nendsolid\n", "is not a binary glTF"},
      {version_one, "is glTF version 1, not 2"},
      {cut, "is cut short"},
      {glb_bytes("{\"asset\":", ""), "does not parse"},
      {glb_bytes("[1,2]", ""), "is not an object"},
      {glb_bytes(std::string(100000, '[') + std::string(100000, ']'), ""), "nests deeper than 256"},
      {edited([](json& g) { g.erase("meshes"); }), "has no mesh"},
      {edited([](json& g) { g["buffers"][0]["uri"] = "leaf.bin"; }), "another file"},
      {edited([](json& g) { g["buffers"].push_back({{"byteLength", 4}}); }), "has 2 buffers"},
      {edited([](json& g) { g["images"] = {{{"uri", "bark.png"}}}; }), "keeps an image in another file"},
      {edited([](json& g) { g["extensionsUsed"] = {"KHR_draco_mesh_compression"}; }), "compressed"},
      {edited([](json& g) { g["nodes"] = {{{"children", {0}}}}; }), "cycle"},
      {edited([](json& g) { g["nodes"][0]["mesh"] = 7; }), "names a mesh it does not have"},
      {edited([](json& g) { g["nodes"][0]["translation"] = {0, "up", 0}; }), "not a list of numbers"},
      {edited([](json& g) { g["meshes"][0]["primitives"][0]["attributes"] = 3; }), "attributes are not an object"},
      {edited([](json& g) { g["meshes"][0]["primitives"][0]["indices"] = -1; }), "is not an index"},
      {edited([](json& g) { g["accessors"][0]["bufferView"] = "zero"; }), "is not an index"},
      {edited([](json& g) { g["buffers"][0]["byteLength"] = 1 << 30; }), "is cut short"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string path = dir / ("case" + std::to_string(k) + ".glb");
    std::ofstream(path, std::ios::binary) << cases[k].first;
    try {
      read_leaf(path);
      ADD_FAILURE() << "case " << k << " was read: " << cases[k].second;
    } catch (const InvalidInput& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("`leaf` " + path + " ", 0), 0u) << message;
      EXPECT_NE(message.find(cases[k].second), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  EXPECT_THROW(read_leaf(dir / "missing.glb"), IOError);

  OutputOptions files;
  files.formats = parse_formats("csv");
  files.leaf = kLeaf;
  EXPECT_THROW(check_glb_options(files), InvalidInput) << "a leaf without the glb";
  files.formats = parse_formats("glb");
  EXPECT_NO_THROW(check_glb_options(files));
  files.leaf = dir / "case0.glb";
  EXPECT_NO_THROW(check_glb_options(files)) << "the formats' check reads no file";
  // The run reads the leaf once, before any mesh or growth.
  DlaRunOptions run;
  run.particles = 200;
  run.files.formats = parse_formats("glb");
  run.files.leaf = dir / "case0.glb";
  EXPECT_THROW(prepare_run(run), InvalidInput) << "read before growth";
}

// The leaf is read once, when the run is set up: the glb writes the leaf it read then, even
// when the file has changed since.
TEST(Leaves, TheLeafIsReadOnceWhenTheRunIsSetUp) {
  ScratchDir dir;
  std::filesystem::copy_file(kLeaf, dir / "leaf.glb");
  DlaRunOptions options;
  options.particles = 300;
  options.files.formats = parse_formats("glb");
  options.files.output = dir / "tree";
  options.files.leaf = dir / "leaf.glb";
  const std::unique_ptr<dla::Run> run = prepare_run(options);
  ASSERT_TRUE(run->leaf);
  EXPECT_EQ(run->leaf->path, options.files.leaf);
  std::ofstream(dir / "leaf.glb", std::ios::trunc) << "no longer a glb";
  RunRecord record;
  const Cluster tree = grow_recorded(*run, {}, nullptr, record);
  write_run(*run, tree, record);
  const std::string glb = read_file(dir / "tree.glb");
  EXPECT_NE(glb.find("\"name\":\"leaf "), std::string::npos) << "no leaf node in the glb";
}

// The command line: before growth, a bad leaf is refused and nothing is written; a good one
// puts a leaf node at each line of PREFIX_tips.ply.
TEST(Leaves, TheCommandLineChecksTheLeafBeforeGrowing) {
  ScratchDir dir;
  std::filesystem::copy_file(kLeaf, dir / "leaf.glb");
  std::ofstream(dir / "noise.glb") << "not a glb";
  testing::CliRun run = testing::dla3d(dir, "-n 400 --formats glb,tips --leaf noise.glb -o bad");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("leaf noise.glb is not a binary glTF"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
  run = testing::dla3d(dir, "-n 400 --formats csv --leaf leaf.glb -o bad");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("add glb to --formats"), std::string::npos) << run.err;
  run = testing::dla3d(dir, "-n 400 --formats glb,tips,json --tips-every 2 --leaf leaf.glb -o good");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json record = json::parse(read_file(dir / "good.json"));
  const std::string tips = read_file(dir / "good_tips.ply");
  const std::size_t at = tips.find("element vertex ") + 15;
  const std::size_t count = std::stoul(tips.substr(at));
  EXPECT_GT(count, 20u);
  EXPECT_EQ(read_glb(dir / "good.glb").gltf["nodes"].size(), 2 + count);
  EXPECT_EQ(record["leaves"], count);
  EXPECT_NE(run.err.find(std::to_string(count) + " leaves in the glb"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace dla
