#include "commands.h"
#include "progress.h"

#include "dla/core/analysis.h"
#include "dla/core/input_file.h"
#include "dla/io/csv_reader.h"
#include "dla/io/json.h"
#include "dla/models/aggregate.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace dla::cli {

namespace {

//! `number`, or null for no fit.
std::string fitted(double value, bool fit) { return json::number(fit ? value : NAN); }

//! The structure read from `text`, the file at `path` (its links, which no measure reads, not).
int analyze_structure(const std::string& path, const std::string& text) {
  const Cluster cluster = parse_csv(text, path);
  const FractalFit gyration = fractal_dimension_by_gyration(cluster);
  const FractalFit mass = fractal_dimension_by_mass_radius(cluster);
  std::printf("{\n  \"file\": %s,\n  \"particles\": %zu,\n  \"seeds\": %zu,\n  \"spacing\": %s,\n"
              "  \"dimensions\": %d,\n  \"radius_of_gyration\": %s,\n  \"fractal_dimension_gyration\": %s,\n"
              "  \"fractal_dimension_mass_radius\": %s\n}\n",
              json::string(path).c_str(), cluster.particles.size(), cluster.seed_count,
              json::number(cluster.spacing).c_str(), cluster.dimensions,
              json::number(radius_of_gyration(cluster)).c_str(), fitted(gyration.dimension, gyration.samples >= 2).c_str(),
              fitted(mass.dimension, mass.samples >= 2).c_str());
  return 0;
}

//! One aggregate's measures: its monomers, mean radius a, R_g of the centres, and D_f by pair
//! correlation with the k_f that puts its R_g on that law.
struct AggregateMeasure {
  std::size_t monomers = 0;
  double a = 0.0, gyration = 0.0;
  FractalFit pairs;
  double prefactor() const { return static_cast<double>(monomers) / std::pow(gyration / a, pairs.dimension); }
};

AggregateMeasure measure(const SphereList& spheres, bool terminal) {
  AggregateMeasure m;
  m.monomers = spheres.centres.size();
  for (const double r : spheres.radii) m.a += r;
  m.a /= static_cast<double>(m.monomers);
  m.gyration = radius_of_gyration(spheres.centres);
  // The pair correlation takes about 4,000 N distances: 40 s at 10^6 monomers, with a bar.
  std::optional<ProgressBar> bar;
  m.pairs = fractal_dimension_by_pair_correlation(spheres.centres, m.a, m.gyration,
                                                  [&](std::size_t done, std::size_t references) {
                                                    if (!bar) bar.emplace(references, terminal);
                                                    bar->update(done);
                                                  });
  if (bar) bar->clear();
  return m;
}

//! The sphere lists at `paths`, the first of which holds `first`.
int analyze_spheres(const std::vector<std::string>& paths, const std::string& first) {
  std::vector<AggregateMeasure> measures;
  for (const std::string& path : paths) {
    const std::string text = &path == &paths.front() ? first : read_input_file(path, "");
    if (!is_sphere_list(text))
      throw InvalidInput(path + ": is not a sphere list (no 'x,y,z,r' header): analyze reads one structure CSV, "
                                "or sphere lists");
    measures.push_back(measure(parse_sphere_list(text, path), isatty(STDERR_FILENO)));
  }
  // The ensemble's law by gyration: N against R_g / a over the aggregates, when their sizes
  // span a factor of 2 at least; and the mean of their pair-correlation fits.
  std::vector<std::pair<double, double>> sizes_and_radii;
  std::size_t least = measures.front().monomers, most = least;
  double pair_dimension = 0.0, pair_prefactor = 0.0, fitted_by_pairs = 0.0;
  for (const AggregateMeasure& m : measures) {
    sizes_and_radii.emplace_back(static_cast<double>(m.monomers), m.gyration / m.a);
    least = std::min(least, m.monomers);
    most = std::max(most, m.monomers);
    if (m.pairs.samples < 2) continue;
    fitted_by_pairs += 1.0;
    pair_dimension += m.pairs.dimension;
    pair_prefactor += m.prefactor();
  }
  const FractalLaw law = most >= 2 * least ? fit_fractal_law(sizes_and_radii) : FractalLaw{};
  const bool by_gyration = law.dimension > 0.0;  // no fit of fewer than two sizes with an extent
  std::printf("{\n  \"aggregates\": [\n");
  for (std::size_t i = 0; i < measures.size(); ++i) {
    const AggregateMeasure& m = measures[i];
    const bool fit = m.pairs.samples >= 2;
    std::printf("    {\"file\": %s, \"monomers\": %zu, \"mean_radius\": %s, \"radius_of_gyration\": %s, "
                "\"radius_of_gyration_over_a\": %s, \"fractal_dimension_pair_correlation\": %s, "
                "\"prefactor_pair_correlation\": %s}%s\n",
                json::string(paths[i]).c_str(), m.monomers, json::number(m.a).c_str(), json::number(m.gyration).c_str(),
                json::number(m.gyration / m.a).c_str(), fitted(m.pairs.dimension, fit).c_str(),
                fitted(m.prefactor(), fit).c_str(), i + 1 < measures.size() ? "," : "");
  }
  std::printf("  ],\n  \"fractal_dimension_gyration\": %s,\n  \"prefactor_gyration\": %s,\n"
              "  \"fractal_dimension_pair_correlation\": %s,\n  \"prefactor_pair_correlation\": %s\n}\n",
              fitted(law.dimension, by_gyration).c_str(), fitted(law.prefactor, by_gyration).c_str(),
              fitted(pair_dimension / fitted_by_pairs, fitted_by_pairs > 0.0).c_str(),
              fitted(pair_prefactor / fitted_by_pairs, fitted_by_pairs > 0.0).c_str());
  return 0;
}

}  // namespace

int analyze(const std::vector<std::string>& paths) {
  const std::string first = read_input_file(paths.front(), "");
  if (is_sphere_list(first)) return analyze_spheres(paths, first);
  if (paths.size() > 1)
    throw InvalidInput(paths.front() + ": analyze measures one structure CSV at a time (sphere lists, many)");
  return analyze_structure(paths.front(), first);
}

}  // namespace dla::cli
