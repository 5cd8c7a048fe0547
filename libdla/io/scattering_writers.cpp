// MSTM's sphere-position file and DDSCAT's shape file (scattering_writers.h).

#include "dla/io/scattering_writers.h"

#include "dla/core/errors.h"
#include "dla/core/memory.h"
#include "dla/core/options.h"
#include "io/output_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

void write_mstm_positions(const Cluster& cluster, const Look& look, const std::string& path) {
  detail::OutputFile out(path);
  // MSTM 3 reads a line into 128 characters: four shortest round-trip doubles take at most 99.
  detail::write_in_order(out, cluster.particles.size(), 1 << 12, detail::format_threads(),
                         [&](detail::Text& text, std::size_t begin, std::size_t end) {
                           for (std::size_t i = begin; i < end; ++i) {
                             const Vec3& p = cluster.particles[i].position;
                             text.number(sphere_radius(cluster, look, i)) << ' ';
                             text.number(p.x()) << ' ';
                             text.number(p.y()) << ' ';
                             text.number(p.z()) << '\n';
                           }
                         });
  out.commit();
}

DipoleLattice dipole_lattice(const Cluster& cluster, const Look& look, int resolution) {
  const std::size_t n = cluster.particles.size();
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += sphere_radius(cluster, look, i);
  const double mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
  DipoleLattice lattice;
  lattice.spacing = mean / resolution;
  if (!(lattice.spacing > 0.0)) return lattice;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = sphere_radius(cluster, look, i) / lattice.spacing;
    lattice.estimated_dipoles += 4.0 / 3.0 * M_PI * r * r * r;
  }
  return lattice;
}

namespace {

//! A dipole's memory while the shape is made: three 32-bit indices, room for a vector's growth.
constexpr double kDipoleBytes = 32.0;
//! A dipole's line in the file, `JA IX IY IZ 1 1 1`, at the least.
constexpr double kDipoleLineBytes = 16.0;

}  // namespace

void refuse_dipoles(const DipoleLattice& lattice, int resolution, const std::string& path) {
  const double memory = available_memory() / kDipoleBytes, disk = free_disk_bytes(path) / kDipoleLineBytes;
  const double most = std::min({kMaxDipoles, memory, disk});
  if (lattice.estimated_dipoles <= most) return;
  const std::string what = most == kMaxDipoles ? "a shape file may hold"
                           : most == memory    ? "this machine's free memory holds"
                                               : "the disk of " + path + " holds";
  // The count goes as the resolution's cube: the largest resolution whose count is in the cap.
  const auto dipoles_at = [&](int r) { return lattice.estimated_dipoles * std::pow(double(r) / resolution, 3.0); };
  int fits = static_cast<int>(std::floor(resolution * std::cbrt(most / lattice.estimated_dipoles)));
  while (dipoles_at(fits + 1) <= most) ++fits;
  while (fits > 0 && dipoles_at(fits) > most) --fits;
  throw InvalidInput("`formats` ddscat: about " + detail::format_count(static_cast<std::size_t>(lattice.estimated_dipoles)) +
                     " dipoles at `ddscat_resolution` " + std::to_string(resolution) + ", past the " +
                     detail::format_count(static_cast<std::size_t>(most)) + " " + what + ": " +
                     (fits >= 1 ? "a resolution of " + std::to_string(fits) + " fits" : "no resolution fits these spheres"));
}

void write_ddscat_shape(const Cluster& cluster, const Look& look, int resolution, const std::string& path) {
  const DipoleLattice lattice = dipole_lattice(cluster, look, resolution);
  refuse_dipoles(lattice, resolution, path);
  const double d = lattice.spacing;
  if (!(d > 0.0)) throw InvalidInput("`formats` ddscat: the spheres have no size to fill with dipoles");
  // Indices from the lattice point below the spheres' box, in 32 bits: (IZ, IY, IX) of every
  // point in a sphere, sorted, then each once.
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const double r = sphere_radius(cluster, look, i);
    low = low.cwiseMin(cluster.particles[i].position - Vec3::Constant(r));
    high = high.cwiseMax(cluster.particles[i].position + Vec3::Constant(r));
  }
  const Vec3 origin = (low / d).array().floor().matrix();
  if (!((high / d - origin).maxCoeff() < 2e9))
    throw InvalidInput("`formats` ddscat: the spheres span more than 2e9 lattice spacings: lower `ddscat_resolution`");
  using Point = std::array<std::int32_t, 3>;
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(lattice.estimated_dipoles * 1.1) + 16);
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const Vec3 c = cluster.particles[i].position / d - origin;
    const double r = sphere_radius(cluster, look, i) / d, r2 = r * r;
    const auto first = [](double x) { return static_cast<std::int32_t>(std::ceil(x)); };
    const auto last = [](double x) { return static_cast<std::int32_t>(std::floor(x)); };
    for (std::int32_t z = first(c.z() - r); z <= last(c.z() + r); ++z) {
      const double dz = static_cast<double>(z) - c.z();
      for (std::int32_t y = first(c.y() - r); y <= last(c.y() + r); ++y) {
        const double dy = static_cast<double>(y) - c.y(), left = r2 - dz * dz - dy * dy;
        if (left < 0.0) continue;
        const double half = std::sqrt(left);
        for (std::int32_t x = first(c.x() - half); x <= last(c.x() + half); ++x) {
          const double dx = static_cast<double>(x) - c.x();
          if (dx * dx + dy * dy + dz * dz <= r2) points.push_back({z, y, x});
        }
      }
    }
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());

  detail::OutputFile out(path);
  out << " >dla3d: " << std::to_string(cluster.particles.size()) << " spheres on a cubic lattice, d = ";
  out.number(d) << " scene units; dipole JA is at (IX, IY, IZ) d\n";
  out.integer(static_cast<long long>(points.size())) << " = NAT\n";
  out << "1 0 0 = A_1 vector\n0 1 0 = A_2 vector\n1 1 1 = lattice spacings (d_x,d_y,d_z)/d\n"
         "0 0 0 = lattice offset x0(1-3) = (x_TF,y_TF,z_TF)/d for dipole 0 0 0\n"
         "JA IX IY IZ ICOMP(x,y,z)\n";
  const auto ox = static_cast<long long>(origin.x()), oy = static_cast<long long>(origin.y()),
             oz = static_cast<long long>(origin.z());
  detail::write_in_order(out, points.size(), 1 << 14, detail::format_threads(),
                         [&](detail::Text& text, std::size_t begin, std::size_t end) {
                           for (std::size_t j = begin; j < end; ++j) {
                             text.integer(static_cast<long long>(j + 1)) << ' ';
                             text.integer(points[j][2] + ox) << ' ';
                             text.integer(points[j][1] + oy) << ' ';
                             text.integer(points[j][0] + oz) << " 1 1 1\n";
                           }
                         });
  out.commit();
}

}  // namespace dla
