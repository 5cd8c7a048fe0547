// read_leaf() and the leaf's objects renumbered for the glb (leaf.h, leaf_parts.h). The leaf's
// JSON is read as a tree by nlohmann's JSON library, so everything the glb carries over
// (extensions, extras, material settings dla3d does not know) passes through unchanged, and only
// the indices that point into the merged arrays move.

#include "leaf_parts.h"

#include "dla/core/input_file.h"

#include "dla/core/errors.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace dla {

namespace {

using nlohmann::json;

[[noreturn]] void refuse(const Leaf& leaf, const std::string& why) {
  throw InvalidInput("`leaf` " + leaf.path + " " + why);
}

//! How deep the text's arrays and objects nest, outside strings.
std::size_t nesting(const std::string& text) {
  std::size_t depth = 0, deepest = 0;
  bool quoted = false, escaped = false;
  for (const char c : text) {
    if (quoted) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

json parse(const Leaf& leaf) {
  // Writing the JSON back recurses once a level: a glTF nests a few levels, a hostile file
  // could nest deep enough to overflow the stack.
  constexpr std::size_t kDeepest = 256;
  if (nesting(leaf.json) > kDeepest)
    refuse(leaf, "is not a glTF: its JSON nests deeper than " + std::to_string(kDeepest) + " levels");
  try {
    json root = json::parse(leaf.json);
    if (!root.is_object()) refuse(leaf, "is not a glTF: its JSON is not an object");
    return root;
  } catch (const json::exception& e) {
    refuse(leaf, std::string("is not a glTF: its JSON does not parse (") + e.what() + ")");
  }
}

//! root[key] as an array, empty if absent.
json& array_at(const Leaf& leaf, json& root, const char* key) {
  if (!root.contains(key)) root[key] = json::array();
  json& array = root[key];
  if (!array.is_array()) refuse(leaf, std::string("is not a glTF: its `") + key + "` is not an array");
  return array;
}

//! Moves the index at object[key], if there is one, on by `offset`.
void shift(const Leaf& leaf, json& object, const char* key, std::size_t offset) {
  if (!object.is_object()) refuse(leaf, std::string("is not a glTF: an object holding `") + key + "` is not one");
  const auto it = object.find(key);
  if (it == object.end()) return;
  if (!it->is_number_unsigned()) refuse(leaf, std::string("is not a glTF: a `") + key + "` is not an index");
  *it = it->get<std::size_t>() + offset;
}

//! Each of the array's values (an object's members) moved on by `offset`.
void shift_all(const Leaf& leaf, json& object, std::size_t offset) {
  if (!object.is_object()) refuse(leaf, "is not a glTF: a primitive's attributes are not an object");
  for (auto& [name, value] : object.items()) shift(leaf, object, name.c_str(), offset);
}

std::string joined(const json& array) {
  std::string text;
  for (const json& item : array) text += (text.empty() ? "" : ",") + item.dump();
  return text;
}

std::vector<std::string> words(const Leaf& leaf, const json& root, const char* key) {
  if (!root.contains(key)) return {};
  try {
    return root[key].get<std::vector<std::string>>();
  } catch (const json::exception&) {
    refuse(leaf, std::string("is not a glTF: its `") + key + "` is not a list of names");
  }
}

double number_at(const Leaf& leaf, const json& array, std::size_t i) {
  if (!array.is_array() || i >= array.size() || !array[i].is_number())
    refuse(leaf, "is not a glTF: a node's transform is not a list of numbers");
  return array[i].get<double>();
}

//! A node's own transform: its matrix, or its translation, rotation and scale.
Eigen::Affine3d local_transform(const Leaf& leaf, const json& node) {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  if (node.contains("matrix")) {
    const json& a = node["matrix"];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) m.matrix()(r, c) = number_at(leaf, a, static_cast<std::size_t>(4 * c + r));
    return m;
  }
  if (node.contains("translation")) {
    const json& t = node["translation"];
    m.translate(Eigen::Vector3d(number_at(leaf, t, 0), number_at(leaf, t, 1), number_at(leaf, t, 2)));
  }
  if (node.contains("rotation")) {
    const json& q = node["rotation"];
    const Eigen::Quaterniond rotation(number_at(leaf, q, 3), number_at(leaf, q, 0), number_at(leaf, q, 1),
                                      number_at(leaf, q, 2));
    if (rotation.norm() > 0) m.rotate(rotation.normalized());
  }
  if (node.contains("scale")) {
    const json& s = node["scale"];
    m.scale(Eigen::Vector3d(number_at(leaf, s, 0), number_at(leaf, s, 1), number_at(leaf, s, 2)));
  }
  return m;
}

//! The first node with a mesh, depth first through the default scene, and its transform.
bool find_mesh_node(const Leaf& leaf, const json& nodes, std::size_t n, const Eigen::Affine3d& parent, int depth,
                    std::size_t& mesh, Eigen::Affine3d& transform) {
  // A node has one parent, so no path is longer than there are nodes: deeper is a cycle.
  if (n >= nodes.size() || depth > static_cast<int>(nodes.size()))
    refuse(leaf, "is not a glTF: its scene names a node it does not have, or nodes in a cycle");
  const json& node = nodes[n];
  if (!node.is_object()) refuse(leaf, "is not a glTF: a node is not an object");
  const Eigen::Affine3d world = parent * local_transform(leaf, node);
  if (node.contains("mesh")) {
    if (!node["mesh"].is_number_unsigned()) refuse(leaf, "is not a glTF: a node's `mesh` is not an index");
    mesh = node["mesh"].get<std::size_t>();
    transform = world;
    return true;
  }
  if (!node.contains("children")) return false;
  for (const json& child : node["children"]) {
    if (!child.is_number_unsigned()) refuse(leaf, "is not a glTF: a node's child is not an index");
    if (find_mesh_node(leaf, nodes, child.get<std::size_t>(), world, depth + 1, mesh, transform)) return true;
  }
  return false;
}

std::uint32_t word_at(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

}  // namespace

namespace detail {

LeafParts leaf_parts(const Leaf& leaf, const GlbCounts& before) {
  json root = parse(leaf);
  LeafParts parts;
  for (json& accessor : array_at(leaf, root, "accessors")) {
    shift(leaf, accessor, "bufferView", before.buffer_views);
    if (accessor.contains("sparse")) {
      json& sparse = accessor["sparse"];
      if (!sparse.is_object()) refuse(leaf, "is not a glTF: an accessor's `sparse` is not an object");
      shift(leaf, sparse["indices"], "bufferView", before.buffer_views);
      shift(leaf, sparse["values"], "bufferView", before.buffer_views);
    }
  }
  for (json& view : array_at(leaf, root, "bufferViews")) {
    if (!view.is_object()) refuse(leaf, "is not a glTF: a buffer view is not an object");
    const json offset = view.value("byteOffset", json(0));
    if (!offset.is_number_unsigned()) refuse(leaf, "is not a glTF: a buffer view's `byteOffset` is not a count");
    view["byteOffset"] = offset.get<std::uint64_t>() + before.binary_offset;
    view["buffer"] = 0;
  }
  json& meshes = array_at(leaf, root, "meshes");
  for (json& mesh : meshes) {
    if (!mesh.is_object()) refuse(leaf, "is not a glTF: a mesh is not an object");
    for (json& primitive : array_at(leaf, mesh, "primitives")) {
      if (!primitive.is_object() || !primitive.contains("attributes"))
        refuse(leaf, "is not a glTF: a mesh primitive has no attributes");
      shift_all(leaf, primitive["attributes"], before.accessors);
      shift(leaf, primitive, "indices", before.accessors);
      shift(leaf, primitive, "material", before.materials);
      if (primitive.contains("targets"))
        for (json& target : array_at(leaf, primitive, "targets")) shift_all(leaf, target, before.accessors);
    }
  }
  for (json& image : array_at(leaf, root, "images")) shift(leaf, image, "bufferView", before.buffer_views);
  parts.accessors = joined(root["accessors"]);
  parts.buffer_views = joined(root["bufferViews"]);
  parts.meshes = joined(meshes);
  parts.materials = joined(array_at(leaf, root, "materials"));
  parts.textures = joined(array_at(leaf, root, "textures"));
  parts.images = joined(root["images"]);
  parts.samplers = joined(array_at(leaf, root, "samplers"));
  parts.extensions_used = words(leaf, root, "extensionsUsed");
  parts.extensions_required = words(leaf, root, "extensionsRequired");

  std::size_t mesh = 0;
  if (root.contains("scenes") && root.contains("nodes")) {
    const json& scenes = array_at(leaf, root, "scenes");
    const json scene_index = root.value("scene", json(0));
    if (!scene_index.is_number_unsigned() || scene_index.get<std::size_t>() >= scenes.size())
      refuse(leaf, "is not a glTF: its `scene` is not one of its scenes");
    const json& scene = scenes[scene_index.get<std::size_t>()];
    const json& nodes = array_at(leaf, root, "nodes");
    if (scene.is_object() && scene.contains("nodes"))
      for (const json& n : scene["nodes"]) {
        if (!n.is_number_unsigned()) refuse(leaf, "is not a glTF: a scene's node is not an index");
        if (find_mesh_node(leaf, nodes, n.get<std::size_t>(), Eigen::Affine3d::Identity(), 0, mesh, parts.transform))
          break;
      }
  }
  if (mesh >= meshes.size()) refuse(leaf, "is not a glTF: a node names a mesh it does not have");
  if (!parts.transform.matrix().allFinite()) refuse(leaf, "has a transform that is not finite");
  parts.mesh = before.meshes + mesh;
  return parts;
}

Leaf parse_leaf(const std::string& bytes, const std::string& path) {
  Leaf leaf{path, {}, {}};
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) refuse(leaf, "is not a binary glTF (.glb)");
  if (word_at(bytes, 4) != 2) refuse(leaf, "is glTF version " + std::to_string(word_at(bytes, 4)) + ", not 2");
  const std::uint64_t length = word_at(bytes, 8);  // the header's: a file may have bytes after it
  if (length > bytes.size())
    refuse(leaf, "is cut short: its header says " + std::to_string(length) + " bytes, the file has " +
                     std::to_string(bytes.size()));
  const std::uint64_t json_length = word_at(bytes, 12);
  if (word_at(bytes, 16) != 0x4E4F534A || 20 + json_length > length) refuse(leaf, "has no JSON chunk first");
  leaf.json = bytes.substr(20, json_length);
  const std::uint64_t at = 20 + json_length;
  if (at + 8 <= length && word_at(bytes, at + 4) == 0x004E4942) {
    const std::uint64_t binary_length = word_at(bytes, at);
    if (at + 8 + binary_length > length) refuse(leaf, "is cut short: its binary chunk runs past its end");
    leaf.binary = bytes.substr(at + 8, binary_length);
    leaf.binary.resize((leaf.binary.size() + 3) / 4 * 4, '\0');
  }

  json root = parse(leaf);
  if (!root.contains("meshes") || !root["meshes"].is_array() || root["meshes"].empty()) refuse(leaf, "has no mesh");
  const json& buffers = array_at(leaf, root, "buffers");
  if (buffers.size() > 1)
    refuse(leaf, "has " + std::to_string(buffers.size()) + " buffers: give a .glb with all its data in its own");
  if (!buffers.empty()) {
    const json& buffer = buffers[0];
    if (!buffer.is_object() || buffer.contains("uri"))
      refuse(leaf, "keeps its data in another file: give a .glb with all its data inside");
    const json byte_length = buffer.value("byteLength", json(0));
    if (!byte_length.is_number_unsigned() || byte_length.get<std::uint64_t>() > leaf.binary.size())
      refuse(leaf, "is cut short: its buffer is longer than its binary chunk");
  }
  for (const json& image : array_at(leaf, root, "images"))
    if (!image.is_object() || image.contains("uri"))
      refuse(leaf, "keeps an image in another file: give a .glb with its images inside");
  for (const std::string& name : words(leaf, root, "extensionsUsed"))
    if (name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression")
      refuse(leaf, "is compressed with " + name + ", which the glb cannot carry over: export it uncompressed");
  leaf_parts(leaf, {});  // the rest of its structure, checked once here
  return leaf;
}

}  // namespace detail

Leaf read_leaf(const std::string& path) { return detail::parse_leaf(read_input_file(path, "leaf"), path); }

}  // namespace dla
