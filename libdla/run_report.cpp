#include "dla/run_report.h"

#include "dla/analysis.h"
#include "dla/strands.h"
#include "dla/version.h"
#include "output_file.h"

namespace dla {

namespace {

void vector(detail::OutputFile& out, const Vec3& v) {
  out << '[';
  out.number(v.x()) << ", ";
  out.number(v.y()) << ", ";
  out.number(v.z()) << ']';
}

}  // namespace

//! A JSON string: quotes, backslashes and control characters escaped.
void string(detail::OutputFile& out, const std::string& text) {
  out << '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out << escaped;
    } else {
      out << c;
    }
  }
  out << '"';
}

void write_run_report(const Cluster& cluster, const GrowthOptions& o, const PovOptions& pov,
                      const RunTimings& timings, const std::string& path, const MeshConstraint* constraint,
                      const std::string& mesh_file) {
  const std::size_t attached = cluster.particles.size() - cluster.seed_count;
  detail::OutputFile out(path);
  out << "{\n  \"generator\": \"dla3d\",\n  \"version\": \"" << version << "\",\n";
  out << "  \"complete\": " << (cluster.complete ? "true" : "false") << ",\n";
  out << "  \"rng_seed\": ";
  out.integer(static_cast<long long>(o.rng_seed)) << ",\n  \"options\": {\n    \"particles\": ";
  out.integer(static_cast<long long>(o.particles)) << ",\n    \"spacing\": ";
  out.number(o.spacing) << ",\n    \"stickiness\": ";
  out.number(o.stickiness) << ",\n    \"dimensions\": ";
  out.integer(o.dimensions) << ",\n    \"seeds\": [";
  for (std::size_t i = 0; i < o.seeds.size(); ++i) {
    if (i) out << ", ";
    vector(out, o.seeds[i]);
  }
  out << "],\n    \"spawn\": \"" << to_string(o.spawn) << "\",\n    \"spawn_axis\": \""
      << to_string(o.spawn_axis) << "\",\n    \"disk_radius\": ";
  out.number(o.disk_radius) << ",\n    \"spawn_box\": ";
  if (o.spawn_box) {
    out << '[';
    vector(out, o.spawn_box->min);
    out << ", ";
    vector(out, o.spawn_box->max);
    out << ']';
  } else {
    out << "null";
  }
  out << ",\n    \"drift\": ";
  vector(out, o.drift);
  out << ",\n    \"min_step\": ";
  out.number(o.min_step) << ",\n    \"index\": \"" << to_string(o.index)
                         << "\",\n    \"base_radius\": ";
  out.number(pov.base_radius) << ",\n    \"tip_radius\": ";
  out.number(pov.tip_radius) << "\n  },\n";
  if (constraint) {
    const RepairReport& r = constraint->repair_report();
    out << "  \"constraint\": {\n    \"mesh\": ";
    string(out, mesh_file);
    out << ",\n    \"side\": \"" << to_string(constraint->options().side) << "\",\n    \"mode\": \""
        << to_string(constraint->options().mode) << "\",\n    \"input_triangles\": ";
    out.integer(static_cast<long long>(r.input_triangles)) << ",\n    \"triangles\": ";
    out.integer(static_cast<long long>(constraint->mesh().triangles.size())) << ",\n    \"repair\": ";
    string(out, r.summary());
    out << ",\n    \"closed\": " << (r.closed ? "true" : "false") << "\n  },\n";
  }
  out << "  \"counts\": {\n    \"particles\": ";
  out.integer(static_cast<long long>(cluster.particles.size())) << ",\n    \"seeds\": ";
  out.integer(static_cast<long long>(cluster.seed_count)) << ",\n    \"attached\": ";
  out.integer(static_cast<long long>(attached)) << ",\n    \"strands\": ";
  out.integer(static_cast<long long>(count_strands(cluster))) << "\n  },\n";
  const WalkStats& s = cluster.stats;
  out << "  \"walk\": {\n    \"walkers\": ";
  out.integer(static_cast<long long>(s.walkers)) << ",\n    \"steps\": ";
  out.integer(static_cast<long long>(s.steps)) << ",\n    \"near_steps\": ";
  out.integer(static_cast<long long>(s.near_steps)) << ",\n    \"contacts\": ";
  out.integer(static_cast<long long>(s.contacts)) << ",\n    \"returns\": ";
  out.integer(static_cast<long long>(s.returns)) << ",\n    \"relaunches\": ";
  out.integer(static_cast<long long>(s.relaunches)) << ",\n    \"lost\": ";
  out.integer(static_cast<long long>(s.lost)) << ",\n    \"rejected\": ";
  out.integer(static_cast<long long>(s.rejected)) << ",\n    \"clipped\": ";
  out.integer(static_cast<long long>(s.clipped)) << "\n  },\n";
  out << "  \"measures\": {\n    \"center\": ";
  vector(out, cluster.center);
  out << ",\n    \"bounding_radius\": ";
  out.number(bounding_radius(cluster), 9) << ",\n    \"radius_of_gyration\": ";
  out.number(radius_of_gyration(cluster), 9) << ",\n    \"fractal_dimension_gyration\": ";
  const auto dimension = [&](const FractalFit& fit) {
    if (fit.samples >= 2)
      out.number(fit.dimension, 5);
    else
      out << "null";
  };
  dimension(fractal_dimension_by_gyration(cluster));
  out << ",\n    \"fractal_dimension_mass_radius\": ";
  dimension(fractal_dimension_by_mass_radius(cluster));
  out << "\n  },\n  \"timings\": {\n    \"grow_seconds\": ";
  out.number(timings.grow_seconds, 6) << ",\n    \"write_seconds\": ";
  out.number(timings.write_seconds, 6) << ",\n    \"particles_per_second\": ";
  out.number(timings.grow_seconds > 0 ? static_cast<double>(attached) / timings.grow_seconds : 0.0, 6);
  // How the run was spread over threads changes how long it took, never what it grew.
  out << ",\n    \"threads\": ";
  out.integer(o.threads) << ",\n    \"replays\": ";
  out.integer(static_cast<long long>(cluster.replays));
  out << "\n  }\n}\n";
  out.commit();
}

}  // namespace dla
