#include "dla/io/csv_writer.h"

#include "dla/io/scattering_writers.h"
#include "output_file.h"

#include <cstdio>

namespace dla {

namespace {

void write(const Cluster& cluster, const Look* look, const std::string& path) {
  detail::OutputFile out(path);
  const bool struck = look && !look->attributes.channel.empty();
  out << (look ? "id,x,y,z,parent,seed,radius,age,depth,descendants,order,tip" : "id,x,y,z,parent,seed")
      << (struck ? ",current,channel,light\n" : "\n");
  // Ranges of rows formatted at once, appended in order: 4096 rows, about 400 kB.
  write_in_order(out, cluster.particles.size(), 1 << 12, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Particle& p = cluster.particles[i];
      text.integer(static_cast<long long>(i)) << ',';
      text.number(p.position.x()) << ',';
      text.number(p.position.y()) << ',';
      text.number(p.position.z()) << ',';
      text.integer(p.parent) << ',';
      text.integer(p.seed);
      if (look) {
        const Attributes& a = look->attributes;
        text << ',';
        // Floats, as in the PLY: the shortest text that reads back as the same float.
        text.float_number(static_cast<float>(look->radius(cluster, i))) << ',';
        text.float_number(a.age(i)) << ',';
        text.integer(a.depth[i]) << ',';
        text.integer(a.descendants[i]) << ',';
        text.integer(a.strahler(i)) << ',';
        text.integer(a.tip(i) ? 1 : 0);
        if (struck) {
          text << ',';
          text.float_number(a.current(i)) << ',';
          text.integer(a.on_channel(i) ? 1 : 0) << ',';
          text.float_number(a.light(i));
        }
      }
      text << '\n';
    }
  });
  out.commit();
  const std::string links_path = links_csv_path(path);
  if (cluster.links.empty()) {
    std::remove(links_path.c_str());
    return;
  }
  detail::OutputFile links(links_path);
  links << "a,b\n";
  for (const Link& link : cluster.links) {
    links.integer(link.earlier) << ',';
    links.integer(link.later) << '\n';
  }
  links.commit();
}

}  // namespace

void write_csv(const Cluster& cluster, const std::string& path) { write(cluster, nullptr, path); }

void write_csv(const Cluster& cluster, const Look& look, const std::string& path) { write(cluster, &look, path); }

void write_spheres_csv(const Cluster& cluster, const Look& look, const std::string& path) {
  detail::OutputFile out(path);
  out << "x,y,z,r\n";
  write_in_order(out, cluster.particles.size(), 1 << 12, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Vec3& p = cluster.particles[i].position;
      text.number(p.x()) << ',';
      text.number(p.y()) << ',';
      text.number(p.z()) << ',';
      text.number(sphere_radius(cluster, look, i)) << '\n';
    }
  });
  out.commit();
}

}  // namespace dla
