#include "dla/ply_writer.h"

#include "dla/version.h"
#include "output_file.h"

#include <cstring>

namespace dla {

namespace {

//! Appends `value`'s bytes, little-endian (the only byte order dla3d builds for).
template <class T>
void put(detail::OutputFile& out, T value) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary PLY is written little-endian");
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  out << std::string_view(bytes, sizeof value);
}

}  // namespace

void write_ply(const Cluster& cluster, const std::string& path, PlyEncoding encoding) {
  const auto& ps = cluster.particles;
  const bool binary = encoding == PlyEncoding::binary;
  detail::OutputFile out(path);
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment dla3d " << version << '\n';
  out << "element vertex ";
  out.integer(static_cast<long long>(ps.size()));
  out << "\nproperty float x\nproperty float y\nproperty float z\n"
         "property int parent\nproperty int seed\n";
  out << "element edge ";
  out.integer(static_cast<long long>(ps.size() - cluster.seed_count));
  out << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  if (binary) {
    for (const Particle& p : ps) {
      for (int a = 0; a < 3; ++a) put(out, static_cast<float>(p.position[a]));
      put(out, p.parent);
      put(out, p.seed);
    }
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps[i].parent < 0) continue;
      put(out, ps[i].parent);
      put(out, static_cast<std::int32_t>(i));
    }
    out.commit();
    return;
  }
  for (const Particle& p : ps) {
    out.number(p.position.x(), 9) << ' ';
    out.number(p.position.y(), 9) << ' ';
    out.number(p.position.z(), 9) << ' ';
    out.integer(p.parent) << ' ';
    out.integer(p.seed) << '\n';
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps[i].parent < 0) continue;
    out.integer(ps[i].parent) << ' ';
    out.integer(static_cast<long long>(i)) << '\n';
  }
  out.commit();
}

}  // namespace dla
