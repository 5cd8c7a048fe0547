// The solid's printing and volume files: binary STL, 3MF (lib3mf) and OpenVDB (solid_writers.h).
// The glb and the OBJ of the solid share the tube meshes' writers (mesh_writers.cpp).

#include "dla/io/solid_writers.h"

#include "dla/core/hash.h"
#include "dla/version.h"
#include "output_file.h"
#include "look/solid_grid.h"

#include <Model/COM/NMR_DLLInterfaces.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <cctype>
#include <cstring>
#include <sstream>

namespace dla {

void write_stl(const Solid& solid, const std::string& path) {
  const SolidMesh& mesh = solid.mesh;
  detail::OutputFile out(path);
  // 80 bytes that must not begin with "solid", which would read as ASCII STL.
  std::string header = std::string("dla3d ") + version + " watertight solid, millimetres";
  header.resize(80, ' ');
  out << header;
  out.raw(static_cast<std::uint32_t>(mesh.triangles.size()));
  char facet[50];
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    Eigen::Vector3f n = (b - a).cross(c - a);
    const float length = n.norm();
    n = length > 0 ? Eigen::Vector3f(n / length) : Eigen::Vector3f::Zero();
    std::memcpy(facet, n.data(), 12);
    std::memcpy(facet + 12, a.data(), 12);
    std::memcpy(facet + 24, b.data(), 12);
    std::memcpy(facet + 36, c.data(), 12);
    facet[48] = facet[49] = 0;
    out << std::string_view(facet, sizeof facet);
  }
  out.commit();
}

namespace {

//! A UUID made from two hashes of a file's content, so the same content gives the same bytes
//! where a format asks for a random one (3MF's production extension, OpenVDB's header). It is
//! marked as version 4, variant 1.
std::string content_uuid(std::uint64_t high, std::uint64_t low) {
  high = (high & ~0xF000ull) | 0x4000ull;                            // the version nibble
  low = (low & ~(0xCull << 60)) | (0x8ull << 60);                     // the variant bits
  static constexpr char kHex[] = "0123456789abcdef";
  std::string uuid;
  for (int i = 15; i >= 0; --i) uuid += kHex[(high >> (4 * i)) & 0xf];
  for (int i = 15; i >= 0; --i) uuid += kHex[(low >> (4 * i)) & 0xf];
  for (const std::size_t dash : {8, 13, 18, 23}) uuid.insert(dash, 1, '-');
  return uuid;
}

//! lib3mf's C interface, its objects released on every path out.
class Lib3mf {
 public:
  ~Lib3mf() {
    for (auto it = owned_.rbegin(); it != owned_.rend(); ++it) NMR::lib3mf_release(*it);
  }
  template <class T>
  T* keep(T* object) {
    owned_.push_back(object);
    return object;
  }
  static void check(HRESULT result, const std::string& path, const char* what) {
    if (result != LIB3MF_OK) throw IOError("cannot write '" + path + "': lib3mf failed to " + what);
  }

 private:
  std::vector<NMR::PLib3MFBase*> owned_;
};

}  // namespace

void write_3mf(const Solid& solid, const std::string& path) {
  const SolidMesh& mesh = solid.mesh;
  Lib3mf lib;
  NMR::PLib3MFModel* model = nullptr;
  Lib3mf::check(NMR::lib3mf_createmodel(&model), path, "make a model");
  lib.keep(model);
  Lib3mf::check(NMR::lib3mf_model_setunit(model, NMR::MODELUNIT_MILLIMETER), path, "set the unit");
  NMR::PLib3MFModelMeshObject* object = nullptr;
  Lib3mf::check(NMR::lib3mf_model_addmeshobject(model, &object), path, "add the mesh");
  lib.keep(object);
  Lib3mf::check(NMR::lib3mf_object_setnameutf8(object, "dla3d solid"), path, "name the mesh");
  std::vector<NMR::MODELMESHVERTEX> vertices(mesh.vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int a = 0; a < 3; ++a) vertices[i].m_fPosition[a] = mesh.vertices[i][a];
  std::vector<NMR::MODELMESHTRIANGLE> triangles(mesh.triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) triangles[i].m_nIndices[k] = mesh.triangles[i][k];
  Lib3mf::check(NMR::lib3mf_meshobject_setgeometry(object, vertices.data(), static_cast<DWORD>(vertices.size()),
                                                   triangles.data(), static_cast<DWORD>(triangles.size())),
                path, "set the geometry");
  NMR::PLib3MFModelBuildItem* item = nullptr;
  Lib3mf::check(NMR::lib3mf_model_addbuilditem(model, object, nullptr, &item), path, "add the build item");
  lib.keep(item);
  // The production extension's UUIDs, from the geometry rather than at random.
  const std::uint64_t geometry = fnv1a(std::string_view(reinterpret_cast<const char*>(vertices.data()),
                                                        vertices.size() * sizeof vertices[0]),
                                       fnv1a(std::string_view(reinterpret_cast<const char*>(triangles.data()),
                                                              triangles.size() * sizeof triangles[0])));
  Lib3mf::check(NMR::lib3mf_object_setuuidutf8(object, content_uuid(geometry, 1).c_str()), path, "set a UUID");
  Lib3mf::check(NMR::lib3mf_builditem_setuuidutf8(item, content_uuid(geometry, 2).c_str()), path, "set a UUID");
  Lib3mf::check(NMR::lib3mf_model_setbuilduuidutf8(model, content_uuid(geometry, 3).c_str()), path, "set a UUID");
  NMR::PLib3MFModelWriter* writer = nullptr;
  Lib3mf::check(NMR::lib3mf_model_querywriter(model, "3mf", &writer), path, "make a writer");
  lib.keep(writer);
  ULONG64 size = 0;
  Lib3mf::check(NMR::lib3mf_writer_getstreamsize(writer, &size), path, "size the file");
  std::string bytes(size, '\0');
  Lib3mf::check(NMR::lib3mf_writer_writetobuffer(writer, reinterpret_cast<BYTE*>(bytes.data()), size), path,
                "write the file");
  detail::OutputFile out(path);
  out << bytes;
  out.commit();
}

namespace {

//! An OpenVDB header names its file by a random UUID (boost's) after its magic number, version
//! numbers and a flag (21 bytes). Made from the rest of the file, the same grids give the same
//! bytes.
void make_uuid_of_content(std::string& bytes) {
  constexpr std::size_t kAt = 21, kLength = 36;
  if (bytes.size() < kAt + kLength) return;
  for (std::size_t i = 0; i < kLength; ++i) {
    const char c = bytes[kAt + i];
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? c != '-' : !std::isxdigit(static_cast<unsigned char>(c))) return;  // not a UUID: leave it
  }
  const std::string_view all(bytes);
  const std::string uuid = content_uuid(fnv1a(all.substr(0, kAt)), fnv1a(all.substr(kAt + kLength)));
  bytes.replace(kAt, kLength, uuid);
}

}  // namespace

void write_vdb(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path) {
  if (!solid.grid) throw IOError("cannot write '" + path + "': the solid has no grid (an empty structure)");
  detail::initialize_openvdb();
  const openvdb::FloatGrid& surface = *solid.grid->surface;
  openvdb::FloatGrid::Ptr density = surface.deepCopy();
  openvdb::tools::sdfToFogVolume(*density);
  density->setName("density");

  // The age of the particle nearest each voxel of the band.
  std::vector<Eigen::Vector3f> at;
  std::vector<openvdb::Coord> where;
  for (auto it = surface.cbeginValueOn(); it; ++it) {
    if (!it.isVoxelValue()) continue;
    const openvdb::Vec3d p = surface.indexToWorld(it.getCoord());
    at.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    where.push_back(it.getCoord());
  }
  const std::vector<std::int32_t> nearest = nearest_particles(cluster, solid, at);
  openvdb::FloatGrid::Ptr age = openvdb::FloatGrid::create(0.0f);
  age->setTransform(surface.transform().copy());
  age->setName("age");
  age->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto access = age->getAccessor();
  for (std::size_t i = 0; i < where.size(); ++i) access.setValue(where[i], look.attributes.age(static_cast<std::size_t>(nearest[i])));

  openvdb::FloatGrid::Ptr surface_copy = surface.deepCopy();
  openvdb::GridPtrVec grids{surface_copy, density, age};
  std::ostringstream stream;
  openvdb::io::Stream(stream).write(grids);
  std::string bytes = std::move(stream).str();
  make_uuid_of_content(bytes);
  detail::OutputFile out(path);
  out << bytes;
  out.commit();
}

}  // namespace dla
