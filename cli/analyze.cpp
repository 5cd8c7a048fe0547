#include "commands.h"

#include "dla/core/analysis.h"
#include "dla/io/csv_reader.h"
#include "dla/io/json.h"

#include <cstdio>

namespace dla::cli {

int analyze(const std::string& path) {
  const Cluster cluster = read_csv(path);
  const FractalFit gyration = fractal_dimension_by_gyration(cluster);
  const FractalFit mass = fractal_dimension_by_mass_radius(cluster);
  const auto value = [](const FractalFit& fit) { return json::number(fit.samples >= 2 ? fit.dimension : NAN); };
  std::printf("{\n  \"file\": %s,\n  \"particles\": %zu,\n  \"seeds\": %zu,\n  \"spacing\": %s,\n"
              "  \"dimensions\": %d,\n  \"radius_of_gyration\": %s,\n  \"fractal_dimension_gyration\": %s,\n"
              "  \"fractal_dimension_mass_radius\": %s\n}\n",
              json::string(path).c_str(), cluster.particles.size(), cluster.seed_count,
              json::number(cluster.spacing).c_str(), cluster.dimensions,
              json::number(radius_of_gyration(cluster)).c_str(), value(gyration).c_str(), value(mass).c_str());
  return 0;
}

}  // namespace dla::cli
