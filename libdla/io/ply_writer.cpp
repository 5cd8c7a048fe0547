#include "dla/io/ply_writer.h"

#include "dla/version.h"
#include "output_file.h"

#include <algorithm>

namespace dla {

namespace {

void header(detail::OutputFile& out, PlyEncoding encoding) {
  out << "ply\nformat " << (encoding == PlyEncoding::binary ? "binary_little_endian" : "ascii")
      << " 1.0\ncomment dla3d " << version << '\n';
}

}  // namespace

void write_ply(const Cluster& cluster, const Look& look, const std::string& path, PlyEncoding encoding) {
  const auto& ps = cluster.particles;
  const Attributes& a = look.attributes;
  const bool binary = encoding == PlyEncoding::binary;
  detail::OutputFile out(path);
  header(out, encoding);
  out << "comment radius in scene units, by the " << to_string(look.options.radius.model)
      << " model; order is the Strahler order; tip is 1 for a particle with no child\n";
  // A tree's edges are parent to child; with links, `link` tells them from the links.
  const bool linked = !cluster.links.empty(), struck = !a.channel.empty();
  if (struck)
    out << "comment a discharge: current is the share of its charge that flows through a particle, channel\n"
           "comment is 1 on the main channel to the strike, light is when the leader reaches it (strike 1)\n";
  if (linked) out << "comment an edge's link is 0 for the tree's (parent to child), 1 for a link that joins branches\n";
  out << "element vertex ";
  out.integer(static_cast<long long>(ps.size()));
  out << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radius\nproperty float age\n"
         "property int depth\nproperty int descendants\nproperty uchar order\nproperty uchar tip\n"
         "property int seed\nproperty int parent\n"
      << (struck ? "property float current\nproperty uchar channel\nproperty float light\n" : "");
  out << "element edge ";
  out.integer(static_cast<long long>(ps.size() - cluster.seed_count + cluster.links.size()));
  out << "\nproperty int vertex1\nproperty int vertex2\n" << (linked ? "property uchar link\n" : "") << "end_header\n";
  const auto vertex = [&](detail::Text& text, std::size_t i) {
    const Particle& p = ps[i];
    const auto order = static_cast<std::uint8_t>(a.strahler(i));
    const std::uint8_t tip = a.tip(i) ? 1 : 0;
    const auto radius = static_cast<float>(look.radius(cluster, i));
    if (binary) {
      for (int axis = 0; axis < 3; ++axis) text.raw(static_cast<float>(p.position[axis]));
      text.raw(radius).raw(a.age(i)).raw(a.depth[i]).raw(a.descendants[i]);
      text.raw(order).raw(tip).raw(p.seed).raw(p.parent);
      if (struck) text.raw(a.current(i)).raw(static_cast<std::uint8_t>(a.on_channel(i))).raw(a.light(i));
      return;
    }
    // The floats the properties declare, each as the shortest text that reads back as it.
    for (int axis = 0; axis < 3; ++axis) text.float_number(static_cast<float>(p.position[axis])) << ' ';
    text.float_number(radius) << ' ';
    text.float_number(a.age(i)) << ' ';
    text.integer(a.depth[i]) << ' ';
    text.integer(a.descendants[i]) << ' ';
    text.integer(order) << ' ';
    text.integer(tip) << ' ';
    text.integer(p.seed) << ' ';
    text.integer(p.parent);
    if (struck) {
      text << ' ';
      text.float_number(a.current(i)) << ' ';
      text.integer(a.on_channel(i) ? 1 : 0) << ' ';
      text.float_number(a.light(i));
    }
    text << '\n';
  };
  const auto edge = [&](detail::Text& text, std::int32_t a, std::int32_t b, std::uint8_t link) {
    if (binary) {
      text.raw(a).raw(b);
      if (linked) text.raw(link);
      return;
    }
    text.integer(a) << ' ';
    text.integer(b);
    if (linked) text << ' ' << static_cast<char>('0' + link);
    text << '\n';
  };
  // Ranges of 4,096 particles formatted at once and appended in order.
  const auto each = [&](auto&& write) {
    write_in_order(out, ps.size(), 1 << 12, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) write(text, i);
    });
  };
  each(vertex);
  each([&](detail::Text& text, std::size_t i) {
    if (ps[i].parent >= 0) edge(text, ps[i].parent, static_cast<std::int32_t>(i), 0);
  });
  write_in_order(out, cluster.links.size(), 1 << 12, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) edge(text, cluster.links[k].earlier, cluster.links[k].later, 1);
  });
  out.commit();
}

void write_ply(const Cluster& cluster, const std::string& path, PlyEncoding encoding) {
  write_ply(cluster, make_look(cluster, {}, {nullptr, nullptr, 1, false}), path, encoding);  // no instances
}

void write_instances_ply(const Cluster& cluster, const Attributes& attributes, const InstanceOptions& options,
                         const std::string& path, PlyEncoding encoding) {
  const std::size_t count = count_instances(cluster, attributes, options);
  const bool binary = encoding == PlyEncoding::binary;
  detail::OutputFile out(path);
  header(out, encoding);
  out << "comment instancing points: N is the direction from the parent, pscale the largest scale at which\n"
         "comment unit-radius copies do not overlap, id the particle's index in the structure\n"
         "element vertex ";
  out.integer(static_cast<long long>(count));
  out << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
         "property float nz\nproperty float pscale\nproperty float age\nproperty int id\nend_header\n";
  for_each_instance(cluster, attributes, options, [&](const Instance& instance) {
    const float age = attributes.age(static_cast<std::size_t>(instance.particle));
    if (binary) {
      for (int axis = 0; axis < 3; ++axis) out.raw(static_cast<float>(instance.position[axis]));
      for (int axis = 0; axis < 3; ++axis) out.raw(static_cast<float>(instance.direction[axis]));
      out.raw(static_cast<float>(instance.scale)).raw(age).raw(instance.particle);
      return;
    }
    for (int axis = 0; axis < 3; ++axis) out.float_number(static_cast<float>(instance.position[axis])) << ' ';
    for (int axis = 0; axis < 3; ++axis) out.fixed(instance.direction[axis], 6) << ' ';
    out.float_number(static_cast<float>(instance.scale)) << ' ';
    out.float_number(age) << ' ';
    out.integer(instance.particle) << '\n';
  });
  out.commit();
}

}  // namespace dla
