#include "dla/io/mesh_writers.h"
#include "dla/io/solid_writers.h"

#include "dla/io/json.h"
#include "dla/version.h"
#include "glb_limit.h"
#include "leaf_parts.h"
#include "output_file.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>

namespace dla {

namespace {

//! The look's tubes, walked once a pass, with the radii and the texture worked out once.
class LookTubes {
 public:
  static constexpr bool textured = true;  //!< its pieces have uvs and tangents
  static constexpr detail::GlbContent content = detail::GlbContent::tubes;

  LookTubes(const Cluster& cluster, const Look& look)
      : cluster_(cluster), look_(look), radii_(look.radii),
        texture_(tube_texture(cluster, radii_, look.options.tubes.uv_scale)) {}

  template <class Visit>
  void operator()(Visit&& visit) const {
    for_each_tube(cluster_, look_.attributes, radii_, texture_, look_.options.tubes, std::forward<Visit>(visit));
  }
  float radius(std::size_t i) const { return radii_[i]; }
  const std::vector<float>& radii() const { return radii_; }
  const TubeTexture& texture() const { return texture_; }

 private:
  const Cluster& cluster_;
  const Look& look_;
  const std::vector<float>& radii_;
  TubeTexture texture_;
};

//! One level of detail of the look's tubes: the tubes of branches of `min_branch` particles or
//! more, each simplified by meshoptimizer toward `keep` of its triangles with no vertex moving by
//! more than a quarter of the tube's thinnest radius, so a trunk keeps its silhouette. The
//! simplifier welds a seam's vertices by position and keeps the seam.
class LodTubes {
 public:
  static constexpr bool textured = true;
  static constexpr detail::GlbContent content = detail::GlbContent::tubes;

  LodTubes(const Cluster& cluster, const Look& look, const LookTubes& full, int min_branch, double keep)
      : cluster_(cluster), look_(look), full_(full), options_(look.options.tubes), keep_(keep) {
    options_.min_branch = min_branch;
  }

  template <class Visit>
  void operator()(Visit&& visit) const {
    for_each_tube(cluster_, look_.attributes, full_.radii(), full_.texture(), options_, [&](const TubePiece& piece) {
      if (keep_ >= 1.0) return visit(piece);
      simplify(piece);
      visit(static_cast<const TubePiece&>(simplified_));
    });
  }
  float radius(std::size_t i) const { return full_.radius(i); }

 private:
  void simplify(const TubePiece& piece) const {
    const std::size_t index_count = piece.triangles.size() * 3, vertex_count = piece.positions.size();
    const auto* indices = reinterpret_cast<const unsigned int*>(piece.triangles.data());
    const float* positions = piece.positions.front().data();
    float thinnest = std::numeric_limits<float>::infinity();
    for (const std::int32_t p : piece.particles)
      thinnest = std::min(thinnest, full_.radius(static_cast<std::size_t>(p)));
    const float extent = meshopt_simplifyScale(positions, vertex_count, sizeof(Eigen::Vector3f));
    const float error = extent > 0 ? 0.25f * thinnest * static_cast<float>(cluster_.spacing) / extent : 0.0f;
    const auto target = static_cast<std::size_t>(keep_ * static_cast<double>(piece.triangles.size())) * 3;
    kept_.resize(index_count);
    kept_.resize(meshopt_simplify(kept_.data(), indices, index_count, positions, vertex_count, sizeof(Eigen::Vector3f),
                                  std::max<std::size_t>(target, 3), error, 0, nullptr));
    // The vertices the kept triangles use, in their order in the piece.
    remap_.assign(vertex_count, kUnused);
    for (const unsigned int v : kept_) remap_[v] = 0;
    simplified_.clear();
    for (std::size_t v = 0; v < vertex_count; ++v) {
      if (remap_[v] == kUnused) continue;
      remap_[v] = static_cast<std::uint32_t>(simplified_.positions.size());
      simplified_.positions.push_back(piece.positions[v]);
      simplified_.normals.push_back(piece.normals[v]);
      simplified_.uvs.push_back(piece.uvs[v]);
      simplified_.tangents.push_back(piece.tangents[v]);
      simplified_.particles.push_back(piece.particles[v]);
    }
    for (std::size_t i = 0; i < kept_.size(); i += 3)
      simplified_.triangles.push_back({remap_[kept_[i]], remap_[kept_[i + 1]], remap_[kept_[i + 2]]});
  }

  static constexpr std::uint32_t kUnused = ~std::uint32_t{0};
  const Cluster& cluster_;
  const Look& look_;
  const LookTubes& full_;
  TubeOptions options_;
  double keep_;
  mutable TubePiece simplified_;
  mutable std::vector<unsigned int> kept_;
  mutable std::vector<std::uint32_t> remap_;
};

//! What a glTF needs before its binary chunk: counts and the positions' exact bounds.
struct TubeTotals {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  Eigen::Vector3f min = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector3f max = -min;
};

template <class Pieces>
TubeTotals tube_totals(const Pieces& each_tube) {
  TubeTotals totals;
  each_tube([&](const TubePiece& piece) {
    totals.vertices += piece.positions.size();
    totals.triangles += piece.triangles.size();
    for (const Eigen::Vector3f& p : piece.positions) {
      totals.min = totals.min.cwiseMin(p);
      totals.max = totals.max.cwiseMax(p);
    }
  });
  return totals;
}

std::array<std::uint8_t, 4> vertex_color(const ColorScale& scale, std::size_t particle) {
  const std::array<double, 3> rgb = color_at(scale(particle));
  return {static_cast<std::uint8_t>(rgb[0] * 255.0 + 0.5), static_cast<std::uint8_t>(rgb[1] * 255.0 + 0.5),
          static_cast<std::uint8_t>(rgb[2] * 255.0 + 0.5), 255};
}

//! The per-vertex attributes, in the order of the glTF's `_` accessors.
constexpr const char* kAttributeNames[] = {"_AGE", "_DEPTH", "_DESCENDANTS", "_ORDER", "_SEED", "_RADIUS"};

template <class Pieces>
std::array<float, 6> vertex_attributes(const Cluster& cluster, const Look& look, const Pieces& tubes,
                                      std::size_t i) {
  const Attributes& a = look.attributes;
  return {a.age(i), static_cast<float>(a.depth[i]), static_cast<float>(a.descendants[i]),
          static_cast<float>(a.strahler(i)), static_cast<float>(cluster.particles[i].seed),
          static_cast<float>(static_cast<double>(tubes.radius(i)) * cluster.spacing)};
}

//! A vector as a JSON array, each number as json::number writes it: a float's read back
//! exactly, as glTF's accessors' min and max must be.
template <class Vector>
std::string number_list(const Vector& v) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) text += (i ? "," : "") + json::number(static_cast<double>(v[i]));
  return text + "]";
}

//! The leaf and the points it goes to.
struct PlacedLeaves {
  const Leaf& leaf;
  std::vector<Instance> points;
};

//! One node a point: the leaf's +Y (after its own node's transform) along the point's direction,
//! scaled by the point's scale, as translation, rotation and scale.
std::string leaf_nodes(const PlacedLeaves& leaves, const detail::LeafParts& parts) {
  std::string nodes;
  for (const Instance& point : leaves.points) {
    const Eigen::Affine3d placed = Eigen::Translation3d(point.position) *
                                   Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), point.direction) *
                                   Eigen::Scaling(point.scale) * parts.transform;
    const Eigen::Matrix3d linear = placed.linear();
    Eigen::Vector3d scale = linear.colwise().norm().transpose();
    Eigen::Matrix3d rotation = linear;
    for (int c = 0; c < 3; ++c)
      rotation.col(c) = scale[c] > 0 ? (linear.col(c) / scale[c]).eval() : Eigen::Vector3d::Unit(c).eval();
    if (rotation.determinant() < 0) {  // a leaf mirrored in its own file: a negative scale
      scale.x() = -scale.x();
      rotation.col(0) = -rotation.col(0);
    }
    const Eigen::Quaterniond q = Eigen::Quaterniond(rotation).normalized();
    nodes += ",{\"name\":\"leaf " + std::to_string(point.particle) + "\",\"mesh\":" + std::to_string(parts.mesh) +
             ",\"translation\":" + number_list(placed.translation()) + ",\"rotation\":" + number_list(q.coeffs()) +
             ",\"scale\":" + number_list(scale) + "}";
  }
  return nodes;
}

std::string names_list(const std::vector<std::string>& names) {
  std::string text = "[";
  for (const std::string& name : names) text += (text.size() > 1 ? "," : "") + json::string(name);
  return text + "]";
}

//! The glTF of the meshes `each_tube` walks: any source with the visitor call, radius(i),
//! `textured` and `content` of LookTubes, whose pieces' vertices name their particles; and the
//! leaves, if any and if there are tubes. Returns its counts.
template <class Pieces>
TubeTotals glb_of(const Cluster& cluster, const Look& look, const Pieces& each_tube, const std::string& path,
                  const PlacedLeaves* leaves = nullptr) {
  const TubeTotals totals = tube_totals(each_tube);
  const bool colored = look.options.color_by != ColorBy::none;
  constexpr bool textured = Pieces::textured;
  // One interleaved vertex: position, normal, [tangent, texture coordinates], [colour], the
  // attributes.
  const std::size_t stride = 12 + 12 + (textured ? 16 + 8 : 0) + (colored ? 4 : 0) + 4 * std::size(kAttributeNames);
  const std::size_t vertex_bytes = totals.vertices * stride;
  const std::size_t index_bytes = totals.triangles * 3 * 4;
  const bool empty = totals.triangles == 0;
  const bool has_leaves = !empty && leaves && !leaves->points.empty();
  const std::size_t buffer_bytes = vertex_bytes + index_bytes + (has_leaves ? leaves->leaf.binary.size() : 0);

  std::string gltf = "{\"asset\":{\"version\":\"2.0\",\"generator\":" + json::string(std::string("dla3d ") + version) +
                     "},\"scene\":0,";
  if (empty) {
    gltf += "\"scenes\":[{}]}";
  } else {
    const std::string count = std::to_string(totals.vertices);
    std::string accessors = "{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":" + count +
                            ",\"type\":\"VEC3\",\"min\":" + number_list(totals.min) + ",\"max\":" + number_list(totals.max) + "}";
    accessors += ",{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":" + count + ",\"type\":\"VEC3\"}";
    std::string attributes = "\"POSITION\":0,\"NORMAL\":1";
    std::size_t offset = 24, accessor = 2;
    if (textured) {
      accessors += ",{\"bufferView\":0,\"byteOffset\":24,\"componentType\":5126,\"count\":" + count +
                   ",\"type\":\"VEC4\"},{\"bufferView\":0,\"byteOffset\":40,\"componentType\":5126,\"count\":" +
                   count + ",\"type\":\"VEC2\"}";
      attributes += ",\"TANGENT\":2,\"TEXCOORD_0\":3";
      offset += 24;
      accessor += 2;
    }
    if (colored) {
      accessors += ",{\"bufferView\":0,\"byteOffset\":" + std::to_string(offset) +
                   ",\"componentType\":5121,\"normalized\":true,\"count\":" + count + ",\"type\":\"VEC4\"}";
      attributes += ",\"COLOR_0\":" + std::to_string(accessor++);
      offset += 4;
    }
    for (const char* name : kAttributeNames) {
      accessors += ",{\"bufferView\":0,\"byteOffset\":" + std::to_string(offset) +
                   ",\"componentType\":5126,\"count\":" + count + ",\"type\":\"SCALAR\"}";
      attributes += ",\"" + std::string(name) + "\":" + std::to_string(accessor++);
      offset += 4;
    }
    accessors += ",{\"bufferView\":1,\"byteOffset\":0,\"componentType\":5125,\"count\":" +
                 std::to_string(totals.triangles * 3) + ",\"type\":\"SCALAR\"}";
    std::string nodes = "{\"mesh\":0,\"name\":\"dla\"}", scene_nodes = "0", meshes, materials, buffer_views, more;
    if (has_leaves) {
      const detail::LeafParts parts =
          detail::leaf_parts(leaves->leaf, {accessor + 1, 2, 1, 1, vertex_bytes + index_bytes});
      nodes += ",{\"name\":\"leaves\",\"children\":[";
      for (std::size_t n = 0; n < leaves->points.size(); ++n) nodes += (n ? "," : "") + std::to_string(n + 2);
      nodes += "]}" + leaf_nodes(*leaves, parts);
      scene_nodes += ",1";
      accessors += "," + parts.accessors;
      meshes = "," + parts.meshes;
      if (!parts.materials.empty()) materials = "," + parts.materials;
      if (!parts.buffer_views.empty()) buffer_views = "," + parts.buffer_views;
      for (const auto& [name, list] : {std::pair{"textures", &parts.textures}, std::pair{"images", &parts.images},
                                       std::pair{"samplers", &parts.samplers}})
        if (!list->empty()) more += ",\"" + std::string(name) + "\":[" + *list + "]";
      if (!parts.extensions_used.empty()) more += ",\"extensionsUsed\":" + names_list(parts.extensions_used);
      if (!parts.extensions_required.empty())
        more += ",\"extensionsRequired\":" + names_list(parts.extensions_required);
    }
    gltf += "\"scenes\":[{\"nodes\":[" + scene_nodes + "]}],\"nodes\":[" + nodes + "],"
            "\"meshes\":[{\"name\":\"dla\",\"primitives\":[{\"attributes\":{" + attributes +
            "},\"indices\":" + std::to_string(accessor) +
            ",\"material\":0,\"mode\":4}]}" + meshes + "],"
            "\"materials\":[{\"name\":\"dla\",\"pbrMetallicRoughness\":{\"baseColorFactor\":" +
            std::string(colored ? "[1,1,1,1]" : "[0.79,0.6,0.36,1]") +
            ",\"metallicFactor\":0,\"roughnessFactor\":0.55}}" + materials + "],"
            "\"buffers\":[{\"byteLength\":" + std::to_string(buffer_bytes) + "}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" + std::to_string(vertex_bytes) +
            ",\"byteStride\":" + std::to_string(stride) + ",\"target\":34962},"
            "{\"buffer\":0,\"byteOffset\":" + std::to_string(vertex_bytes) + ",\"byteLength\":" +
            std::to_string(index_bytes) + ",\"target\":34963}" + buffer_views + "],"
            "\"accessors\":[" + accessors + "]" + more + "}";
  }
  gltf.resize((gltf.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned: JSON pads with spaces
  const std::size_t length = 12 + 8 + gltf.size() + (empty ? 0 : 8 + buffer_bytes);
  detail::require_glb_fits(length, Pieces::content);

  detail::OutputFile out(path);
  out.raw(std::uint32_t{0x46546C67}).raw(std::uint32_t{2}).raw(static_cast<std::uint32_t>(length));
  out.raw(static_cast<std::uint32_t>(gltf.size())).raw(std::uint32_t{0x4E4F534A}) << gltf;
  if (empty) {
    out.commit();
    return totals;
  }
  out.raw(static_cast<std::uint32_t>(buffer_bytes)).raw(std::uint32_t{0x004E4942});
  // The vertices and the indices in one walk of the tubes, each gathered and written at its
  // own place in the binary chunk: a second walk took a quarter of the time.
  const ColorScale scale(cluster, look.attributes, look.options.color_by);
  constexpr std::size_t kGathered = std::size_t{1} << 20;
  std::uint64_t vertices_at = 12 + 8 + gltf.size() + 8, indices_at = vertices_at + vertex_bytes;
  std::string vertices, indices;
  const auto write_out = [&](std::string& bytes, std::uint64_t& at) {
    out.write_at(at, bytes);
    at += bytes.size();
    bytes.clear();
  };
  std::uint32_t base = 0;
  each_tube([&](const TubePiece& piece) {
    const std::size_t vertices_before = vertices.size(), indices_before = indices.size();
    vertices.resize(vertices_before + piece.positions.size() * stride);
    char* at = vertices.data() + vertices_before;
    const auto put = [&at](const void* data, std::size_t size) {
      std::memcpy(at, data, size);
      at += size;
    };
    for (std::size_t v = 0; v < piece.positions.size(); ++v) {
      const auto particle = static_cast<std::size_t>(piece.particles[v]);
      put(piece.positions[v].data(), 12);
      put(piece.normals[v].data(), 12);
      if constexpr (textured) {
        put(piece.tangents[v].data(), 16);
        put(piece.uvs[v].data(), 8);
      }
      if (colored) put(vertex_color(scale, particle).data(), 4);
      put(vertex_attributes(cluster, look, each_tube, particle).data(), 4 * std::size(kAttributeNames));
    }
    indices.resize(indices_before + piece.triangles.size() * 12);
    at = indices.data() + indices_before;
    for (const auto& t : piece.triangles)
      for (const std::uint32_t v : t) {
        const std::uint32_t index = base + v;
        put(&index, 4);
      }
    base += static_cast<std::uint32_t>(piece.positions.size());
    if (vertices.size() >= kGathered) write_out(vertices, vertices_at);
    if (indices.size() >= kGathered) write_out(indices, indices_at);
  });
  write_out(vertices, vertices_at);
  write_out(indices, indices_at);
  if (has_leaves) out.write_at(indices_at, leaves->leaf.binary);
  out.commit();
  return totals;
}

//! Lines of an OBJ file gathered from the tube pieces, to be formatted on a thread of its
//! own: vertices and faces in runs, each run's vertex lines before its face lines, as a
//! piece's are. A large piece (the solid) spans several batches.
struct ObjBatch {
  std::vector<Eigen::Vector3f> positions, normals;
  std::vector<Eigen::Vector2f> uvs;        // textured pieces only
  std::vector<std::int32_t> particles;     // for the colours only
  std::vector<std::array<std::size_t, 3>> faces;  // OBJ's indices, counted from 1
  std::vector<std::array<std::size_t, 2>> run_ends;  // each run's end in positions and faces

  std::size_t lines() const { return positions.size() + faces.size(); }
  void end_run() {
    const std::array<std::size_t, 2> end{positions.size(), faces.size()};
    if (end != (run_ends.empty() ? std::array<std::size_t, 2>{} : run_ends.back())) run_ends.push_back(end);
  }
  void clear() {
    positions.clear(), normals.clear(), uvs.clear(), particles.clear(), faces.clear(), run_ends.clear();
  }
};

//! Lines (a vertex with its normal and texture, or a face) in a batch of an OBJ file: about
//! 2 MB of text, a few batches in memory at a time.
constexpr std::size_t kObjBatchLines = std::size_t{1} << 15;

//! OBJ's faces name a vertex's position, texture coordinates and normal by one index; its v
//! counts up from the image's foot where glTF's counts down from its head, so it holds 1 - v
//! and both files map an image alike. The walk over the pieces gathers their lines in batches,
//! which the machine's threads format at once.
template <class Pieces>
void obj_of(const Cluster& cluster, const Look& look, const Pieces& each_tube, std::string_view what,
            const std::string& path) {
  const bool colored = look.options.color_by != ColorBy::none;
  const ColorScale scale(cluster, look.attributes, look.options.color_by);
  detail::OutputFile out(path);
  out << "# dla3d " << version << " " << what << ": ";
  out.integer(static_cast<long long>(cluster.particles.size()))
      << " particles, radius model " << to_string(look.options.radius.model) << (colored ? ", colour by " : "")
      << (colored ? to_string(look.options.color_by) : "") << "\no dla\n";
  const auto format = [&](detail::Text& text, const ObjBatch& batch) {
    std::size_t v = 0, f = 0;
    for (const auto& [vertex_end, face_end] : batch.run_ends) {
      for (; v < vertex_end; ++v) {
        text << "v ";
        for (int a = 0; a < 3; ++a) text.number(batch.positions[v][a], 7) << (a < 2 ? " " : "");
        if (colored) {
          const std::array<double, 3> rgb = color_at(scale(static_cast<std::size_t>(batch.particles[v])));
          for (int c = 0; c < 3; ++c) text << ' ', text.fixed(rgb[c], 4);
        }
        text << "\nvn ";
        for (int a = 0; a < 3; ++a) text.fixed(batch.normals[v][a], 5) << (a < 2 ? " " : "\n");
        if constexpr (Pieces::textured) {
          text << "vt ";
          text.fixed(batch.uvs[v].x(), 5) << ' ';
          const double flipped = 1.0 - static_cast<double>(batch.uvs[v].y());
          (std::abs(flipped) < 1e9 ? text.fixed(flipped, 5) : text.float_number(static_cast<float>(flipped))) << '\n';
        }
      }
      for (; f < face_end; ++f) {
        text << 'f';
        for (const std::size_t index : batch.faces[f]) {
          // The index once in digits, then as position/texture/normal (position//normal).
          char digits[24];
          const char* const end = std::to_chars(digits, digits + 24, index).ptr;
          const std::string_view name(digits, static_cast<std::size_t>(end - digits));
          text << ' ' << name << (Pieces::textured ? "/" : "//");
          if (Pieces::textured) text << name << '/';
          text << name;
        }
        text << '\n';
      }
    }
  };
  detail::OrderedBatches<ObjBatch, decltype(format)> batches(out, detail::format_threads(), format);
  const auto line_added = [&] {
    if (batches.batch().lines() < kObjBatchLines) return;
    batches.batch().end_run();
    batches.send();
  };
  std::size_t base = 1;  // OBJ counts from 1
  each_tube([&](const TubePiece& piece) {
    for (std::size_t v = 0; v < piece.positions.size(); ++v) {
      ObjBatch& batch = batches.batch();
      batch.positions.push_back(piece.positions[v]);
      batch.normals.push_back(piece.normals[v]);
      if constexpr (Pieces::textured) batch.uvs.push_back(piece.uvs[v]);
      if (colored) batch.particles.push_back(piece.particles[v]);
      line_added();
    }
    for (const auto& t : piece.triangles) {
      batches.batch().faces.push_back({base + t[0], base + t[1], base + t[2]});
      line_added();
    }
    batches.batch().end_run();
    base += piece.positions.size();
  });
  batches.send();
  batches.finish();
  out.commit();
}

//! The solid as one piece of the mesh writers: its vertices with area-weighted normals, each
//! tied to its nearest particle.
class SolidPieces {
 public:
  static constexpr bool textured = false;
  static constexpr detail::GlbContent content = detail::GlbContent::solid;

  SolidPieces(const Solid& solid, const Cluster& cluster, const Look& look) : radii_(look.radii) {
    const SolidMesh& mesh = solid.mesh;
    piece_.positions = mesh.vertices;
    piece_.triangles = mesh.triangles;
    piece_.particles = nearest_particles(cluster, solid, mesh.vertices);
    std::vector<Eigen::Vector3d> normals(mesh.vertices.size(), Eigen::Vector3d::Zero());
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      const Eigen::Vector3d n = (b - a).cross(c - a);  // its length is twice the area
      for (const std::uint32_t v : t) normals[v] += n;
    }
    piece_.normals.reserve(normals.size());
    for (const Eigen::Vector3d& n : normals) {
      const double length = n.norm();
      piece_.normals.push_back(length > 0 ? (n / length).cast<float>().eval() : Eigen::Vector3f::UnitZ().eval());
    }
  }
  template <class Visit>
  void operator()(Visit&& visit) const {
    if (!piece_.triangles.empty()) visit(piece_);
  }
  float radius(std::size_t i) const { return radii_[i]; }

 private:
  TubePiece piece_;
  const std::vector<float>& radii_;
};

}  // namespace

void detail::require_glb_fits(std::uint64_t bytes, GlbContent content) {
  if (bytes <= std::numeric_limits<std::uint32_t>::max()) return;
  const bool solid = content == GlbContent::solid;
  throw InvalidInput(std::string(solid ? "`formats` solid-glb: the solid" : "`formats` glb: the tubes") +
                     " would take " + detail::format_number(std::ceil(static_cast<double>(bytes) / 1e8) / 10.0) +
                     " GB, past a glb's 4.29 GB: " +
                     (solid ? "a larger `solid_voxel` or some `solid_adaptivity` makes it smaller"
                            : "fewer `tube_sides`, a `tube_tolerance` or a `tube_min_branch` makes them smaller"));
}

GlbWritten write_glb(const Cluster& cluster, const Look& look, const std::string& path, const GlbOptions& options) {
  const int levels = options.lods;
  if (levels < 0 || levels > kMaxLods)
    throw InvalidInput("`lod` " + std::to_string(levels) + " is not in 0-" + std::to_string(kMaxLods));
  const LookTubes tubes(cluster, look);
  GlbWritten written;
  if (options.leaf) {
    const PlacedLeaves leaves{*options.leaf, instancing_points(cluster, look.attributes, options.instances)};
    if (glb_of(cluster, look, tubes, path, &leaves).triangles > 0) written.leaves = leaves.points.size();
  } else {
    glb_of(cluster, look, tubes, path);
  }
  if (levels == 0) return written;
  const std::string prefix =
      path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0 ? path.substr(0, path.size() - 4) : path;
  // Each tube's triangles by the size of its branch (capped past the largest threshold): what
  // each threshold keeps, before simplifying.
  constexpr int kMaxMinBranch = 1000;
  std::vector<std::size_t> by_size(kMaxMinBranch + 2, 0);
  std::size_t full = 0;
  tubes([&](const TubePiece& piece) {
    const auto first = static_cast<std::size_t>(piece.particles.front());
    by_size[static_cast<std::size_t>(std::min(look.attributes.descendants[first] + 1, kMaxMinBranch + 1))] +=
        piece.triangles.size();
    full += piece.triangles.size();
  });
  std::vector<std::size_t> kept_from(by_size.size() + 1, 0);  // triangles of branches of m or more
  for (std::size_t m = by_size.size(); m-- > 0;) kept_from[m] = kept_from[m + 1] + by_size[m];
  int min_branch = look.options.tubes.min_branch;
  for (int level = 1; level <= levels; ++level) {
    // Half the triangles a level: twigs go first, down to 1.5 times the level's target; the
    // simplifier takes the rest.
    const double target = static_cast<double>(full) / static_cast<double>(1 << level);
    const auto kept_at = [&](int m) { return static_cast<double>(kept_from[static_cast<std::size_t>(m)]); };
    while (min_branch < kMaxMinBranch && kept_at(min_branch) > 1.5 * target) ++min_branch;
    const double kept = kept_at(min_branch);
    const LodTubes level_tubes(cluster, look, tubes, min_branch, kept > 0 ? std::min(1.0, target / kept) : 1.0);
    written.lod_triangles.push_back(
        glb_of(cluster, look, level_tubes, prefix + "_lod" + std::to_string(level) + ".glb").triangles);
  }
  return written;
}

void write_obj(const Cluster& cluster, const Look& look, const std::string& path) {
  obj_of(cluster, look, LookTubes(cluster, look), "tube mesh", path);
}

void write_solid_glb(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path) {
  glb_of(cluster, look, SolidPieces(solid, cluster, look), path);
}

void write_solid_obj(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path) {
  obj_of(cluster, look, SolidPieces(solid, cluster, look), "solid", path);
}

void write_stl(const TriangleMesh& mesh, const std::string& path) {
  detail::OutputFile out(path);
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL written by dla3d, %zu triangles", mesh.triangles.size());
  out << std::string_view(header, sizeof header);
  const auto u32 = [&](std::uint32_t v) {
    const char b[4] = {char(v & 0xff), char(v >> 8 & 0xff), char(v >> 16 & 0xff), char(v >> 24 & 0xff)};
    out << std::string_view(b, 4);
  };
  const auto f32 = [&](double v) {
    const float f = static_cast<float>(v);
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    u32(bits);
  };
  u32(static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    for (int i = 0; i < 3; ++i) f32(n.allFinite() ? n[i] : 0.0);
    for (const Vec3* v : {&a, &b, &c})
      for (int i = 0; i < 3; ++i) f32((*v)[i]);
    out << std::string_view("\0\0", 2);
  }
  out.commit();
}

}  // namespace dla
