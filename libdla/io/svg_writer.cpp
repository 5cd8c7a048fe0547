#include "dla/io/svg_writer.h"

#include "dla/version.h"
#include "output_file.h"

#include <cmath>
#include <cstdio>

namespace dla {

namespace {

//! A linear colour as SVG's sRGB `#rrggbb`.
std::string srgb_hex(const std::array<double, 3>& linear) {
  char text[8];
  int channels[3];
  for (int c = 0; c < 3; ++c) {
    const double v = std::clamp(linear[static_cast<std::size_t>(c)], 0.0, 1.0);
    const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    channels[c] = static_cast<int>(encoded * 255.0 + 0.5);
  }
  std::snprintf(text, sizeof text, "#%02x%02x%02x", channels[0], channels[1], channels[2]);
  return text;
}

}  // namespace

void write_svg(const Cluster& cluster, const Look& look, const std::string& path) {
  if (cluster.dimensions != 2)
    throw InvalidInput("svg draws 2D growth (`dimensions` 2); a 3D structure goes to glb, obj or pov");
  const auto& ps = cluster.particles;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double widest = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    lo = lo.cwiseMin(ps[i].position.head<2>());
    hi = hi.cwiseMax(ps[i].position.head<2>());
    widest = std::max(widest, look.radius(cluster, i));
  }
  const double margin = widest + 0.02 * (hi - lo).maxCoeff();
  lo -= Eigen::Vector2d::Constant(margin);
  hi += Eigen::Vector2d::Constant(margin);
  // A thousandth of a spacing, as in the POV-Ray scene.
  const int decimals = std::clamp(3 - static_cast<int>(std::floor(std::log10(cluster.spacing))), 0, 9);
  const bool colored = look.options.color_by != ColorBy::none;
  const ColorScale scale(cluster, look.attributes, look.options.color_by);

  detail::OutputFile out(path);
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- dla3d " << version << ": ";
  out.integer(static_cast<long long>(ps.size()))
      << " particles, radius model " << to_string(look.options.radius.model) << " -->\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"";
  // y is flipped (SVG's points down), so the box's top is -hi.y.
  out.fixed(lo.x(), decimals) << ' ';
  out.fixed(-hi.y(), decimals) << ' ';
  out.fixed(hi.x() - lo.x(), decimals) << ' ';
  out.fixed(hi.y() - lo.y(), decimals) << "\" width=\"";
  const double aspect = (hi.y() - lo.y()) / (hi.x() - lo.x());
  out.integer(1000) << "\" height=\"";
  out.integer(std::lround(1000 * aspect)) << "\">\n<rect x=\"";
  out.fixed(lo.x(), decimals) << "\" y=\"";
  out.fixed(-hi.y(), decimals) << "\" width=\"";
  out.fixed(hi.x() - lo.x(), decimals) << "\" height=\"";
  out.fixed(hi.y() - lo.y(), decimals) << "\" fill=\"white\"/>\n<g stroke=\"black\" stroke-linecap=\"round\">\n";
  // A branch from a to b, as wide as `radius`, in particle i's colour.
  const auto line = [&](const Vec3& a, const Vec3& b, double radius, std::size_t i) {
    out << "<line x1=\"";
    out.fixed(a.x(), decimals) << "\" y1=\"";
    out.fixed(-a.y(), decimals) << "\" x2=\"";
    out.fixed(b.x(), decimals) << "\" y2=\"";
    out.fixed(-b.y(), decimals) << "\" stroke-width=\"";
    out.fixed(2.0 * radius, decimals) << '"';
    if (colored) out << " stroke=\"" << srgb_hex(color_at(scale(i))) << '"';
    out << "/>\n";
  };
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps[i].parent >= 0) line(ps[static_cast<std::size_t>(ps[i].parent)].position, ps[i].position, look.radius(cluster, i), i);
  // A link is as wide as the thinner of its ends, and takes its later particle's colour.
  for (const Link& link : cluster.links) {
    const auto a = static_cast<std::size_t>(link.earlier), b = static_cast<std::size_t>(link.later);
    line(ps[a].position, ps[b].position, std::min(look.radius(cluster, a), look.radius(cluster, b)), b);
  }
  out << "</g>\n</svg>\n";
  out.commit();
}

}  // namespace dla
