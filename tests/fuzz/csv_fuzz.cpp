// libFuzzer target for the CSV reader of `dla3d analyze` and the measures it prints: any bytes
// must either be refused with InvalidInput or give a tree (parents before children) whose
// measures compute without a fault. The same bytes as a PREFIX_links.csv of a small tree give
// links between two of its particles, earlier first, or InvalidInput. As a sphere list, they give
// finite spheres of positive radius whose pair correlation computes, or InvalidInput. Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "dla/core/analysis.h"
#include "dla/io/csv_reader.h"
#include "special_files.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dla::fuzz::read_special_files(".csv", [](const std::string& path) { dla::read_csv(path); });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    dla::Cluster tree;
    for (int i = 0; i < 8; ++i) tree.particles.push_back({dla::Vec3(i, 0, 0), i - 1, 0});
    dla::parse_links_csv(bytes, "fuzz", tree);
    for (const dla::Link& link : tree.links)
      if (!(0 <= link.earlier && link.earlier < link.later && link.later < 8)) std::abort();
    dla::cycle_count(tree);
  } catch (const dla::InvalidInput&) {
  }
  try {
    const dla::Cluster cluster = dla::parse_csv(bytes, "fuzz");
    for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
      const dla::Particle& p = cluster.particles[i];
      if (p.parent >= static_cast<std::int64_t>(i) || !p.position.allFinite()) std::abort();
    }
    if (!(cluster.spacing > 0.0)) std::abort();
    dla::fractal_dimension_by_gyration(cluster);
    dla::fractal_dimension_by_mass_radius(cluster);
    dla::radius_of_gyration(cluster);
  } catch (const dla::InvalidInput&) {
  }
  try {
    const dla::SphereList spheres = dla::parse_sphere_list(bytes, "fuzz");
    if (spheres.centres.empty() || spheres.radii.size() != spheres.centres.size()) std::abort();
    for (std::size_t i = 0; i < spheres.centres.size(); ++i)
      if (!spheres.centres[i].allFinite() || !(spheres.radii[i] > 0.0) || !std::isfinite(spheres.radii[i])) std::abort();
    const dla::FractalFit fit = dla::fractal_dimension_by_pair_correlation(spheres.centres, spheres.radii[0], 100.0);
    if (fit.samples >= 2 && std::isnan(fit.dimension)) std::abort();
  } catch (const dla::InvalidInput&) {
  }
  return 0;
}
