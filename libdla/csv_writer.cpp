#include "dla/csv_writer.h"

#include "output_file.h"

namespace dla {

void write_csv(const Cluster& cluster, const std::string& path) {
  detail::OutputFile out(path);
  out << "id,x,y,z,parent,seed\n";
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const Particle& p = cluster.particles[i];
    out.integer(static_cast<long long>(i)) << ',';
    out.number(p.position.x()) << ',';
    out.number(p.position.y()) << ',';
    out.number(p.position.z()) << ',';
    out.integer(p.parent) << ',';
    out.integer(p.seed) << '\n';
  }
  out.commit();
}

}  // namespace dla
