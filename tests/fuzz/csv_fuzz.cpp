// libFuzzer target for the CSV reader of `dla3d analyze` and the measures it prints: any bytes
// must either be refused with InvalidInput or give a tree (parents before children) whose
// measures compute without a fault. Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "dla/core/analysis.h"
#include "dla/io/csv_reader.h"

#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
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
  return 0;
}
