#include "dla/ply_writer.h"

#include "dla/version.h"
#include "output_file.h"

namespace dla {

void write_ply(const Cluster& cluster, const std::string& path) {
  const auto& ps = cluster.particles;
  detail::OutputFile out(path);
  out << "ply\nformat ascii 1.0\ncomment dla3d " << version << '\n';
  out << "element vertex ";
  out.integer(static_cast<long long>(ps.size()));
  out << "\nproperty float x\nproperty float y\nproperty float z\n"
         "property int parent\nproperty int seed\n";
  out << "element edge ";
  out.integer(static_cast<long long>(ps.size() - cluster.seed_count));
  out << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
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
