#include "dla/csv_writer.h"

#include "output_file.h"

#include <algorithm>

namespace dla {

namespace {

void write(const Cluster& cluster, const Look* look, const std::string& path) {
  detail::OutputFile out(path);
  out << (look ? "id,x,y,z,parent,seed,radius,age,depth,descendants,order,tip\n" : "id,x,y,z,parent,seed\n");
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const Particle& p = cluster.particles[i];
    out.integer(static_cast<long long>(i)) << ',';
    out.number(p.position.x()) << ',';
    out.number(p.position.y()) << ',';
    out.number(p.position.z()) << ',';
    out.integer(p.parent) << ',';
    out.integer(p.seed);
    if (look) {
      const Attributes& a = look->attributes;
      out << ',';
      out.number(look->radius(cluster, i), 7) << ',';
      out.number(a.age(i), 7) << ',';
      out.integer(a.depth[i]) << ',';
      out.integer(a.descendants[i]) << ',';
      out.integer(a.strahler(i)) << ',';
      out.integer(a.tip(i) ? 1 : 0);
    }
    out << '\n';
  }
  out.commit();
}

}  // namespace

void write_csv(const Cluster& cluster, const std::string& path) { write(cluster, nullptr, path); }

void write_csv(const Cluster& cluster, const Look& look, const std::string& path) { write(cluster, &look, path); }

}  // namespace dla
