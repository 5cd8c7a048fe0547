#include "dla/io/run_report.h"

#include "dla/core/analysis.h"
#include "dla/io/json.h"
#include "dla/look/strands.h"
#include "dla/version.h"
#include "output_file.h"

#include <cmath>

namespace dla {

namespace {

void vector(detail::OutputFile& out, const Vec3& v) {
  out << '[' << json::number(v.x()) << ", " << json::number(v.y()) << ", " << json::number(v.z()) << ']';
}

void begin(detail::OutputFile& out, const Cluster& cluster, const RunRecord& record) {
  out << "{\n  \"generator\": \"dla3d\",\n  \"version\": \"" << version << "\",\n";
  if (!record.command.empty()) out << "  \"command\": " << json::string(record.command) << ",\n";
  out << "  \"complete\": " << (cluster.complete ? "true" : "false") << ",\n";
  if (!record.stopped_by.empty()) out << "  \"stopped_by\": " << json::string(record.stopped_by) << ",\n";
}

void look_section(detail::OutputFile& out, const LookOptions& look, const PovOptions& pov) {
  out << "  \"look\": {\n    \"radius\": \"" << to_string(look.radius.model) << "\",\n    \"base_radius\": ";
  out.number(look.radius.base_radius) << ",\n    \"tip_radius\": ";
  out.number(look.radius.tip_radius) << ",\n    \"pipe_exponent\": ";
  out.number(look.radius.pipe_exponent) << ",\n    \"color_by\": \"" << to_string(look.color_by)
                                        << "\",\n    \"tube_sides\": ";
  out.integer(look.tubes.sides) << ",\n    \"tube_tolerance\": ";
  out.number(look.tubes.tolerance) << ",\n    \"pov_look\": \"" << to_string(pov.style) << "\"\n  },\n";
}

void counts(detail::OutputFile& out, const Cluster& cluster) {
  out << "  \"counts\": {\n    \"particles\": ";
  out.integer(static_cast<long long>(cluster.particles.size())) << ",\n    \"seeds\": ";
  out.integer(static_cast<long long>(cluster.seed_count)) << ",\n    \"attached\": ";
  out.integer(static_cast<long long>(attached(cluster))) << ",\n    \"strands\": ";
  out.integer(static_cast<long long>(count_strands(cluster))) << "\n  },\n";
}

void measures(detail::OutputFile& out, const Cluster& cluster) {
  out << "  \"measures\": {\n    \"center\": ";
  vector(out, cluster.center);
  out << ",\n    \"bounding_radius\": ";
  out << json::number(bounding_radius(cluster), 9) << ",\n    \"radius_of_gyration\": ";
  out << json::number(radius_of_gyration(cluster), 9) << ",\n    \"fractal_dimension_gyration\": ";
  const auto dimension = [&](const FractalFit& fit) { out << json::number(fit.samples >= 2 ? fit.dimension : NAN, 5); };
  dimension(fractal_dimension_by_gyration(cluster));
  out << ",\n    \"fractal_dimension_mass_radius\": ";
  dimension(fractal_dimension_by_mass_radius(cluster));
  if (cluster.filled > 0.0) out << ",\n    \"filled\": " << json::number(cluster.filled, 6);
  out << "\n  },\n";
}

//! The timings' first entries, left open for the model's own.
void timings(detail::OutputFile& out, const Cluster& cluster, const RunRecord& record) {
  out << "  \"timings\": {\n    \"grow_seconds\": ";
  out.number(record.grow_seconds, 6) << ",\n    \"write_seconds\": ";
  out.number(record.write_seconds, 6) << ",\n    \"particles_per_second\": ";
  out.number(record.grow_seconds > 0 ? static_cast<double>(attached(cluster)) / record.grow_seconds : 0.0, 6);
}

//! The end of a model's sidecar but DLA's (which has walk statistics): the look, counts,
//! measures and timings; then the file goes into place.
void finish_model_report(detail::OutputFile& out, const Cluster& cluster, const LookOptions& look, const PovOptions& pov,
                         const RunRecord& record) {
  look_section(out, look, pov);
  counts(out, cluster);
  measures(out, cluster);
  timings(out, cluster, record);
  out << "\n  }\n}\n";
  out.commit();
}

}  // namespace

void write_run_report(const Cluster& cluster, const DlaOptions& o, const LookOptions& look,
                      const PovOptions& pov, const RunRecord& record, const std::string& path, const MeshConstraint* constraint,
                      const std::string& mesh_file) {
  detail::OutputFile out(path);
  begin(out, cluster, record);
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
  if (o.fill > 0.0) {
    out << ",\n    \"fill\": ";
    out.number(o.fill) << ",\n    \"fill_distance\": ";
    out.number(o.fill_distance);
  }
  if (o.rotate_degrees != 0.0) {
    out << ",\n    \"rotate_axis\": \"" << to_string(o.rotate_axis) << "\",\n    \"rotate_degrees_per_1000\": ";
    out.number(o.rotate_degrees);
  }
  out << ",\n    \"min_step\": ";
  out.number(o.min_step) << ",\n    \"index\": \"" << to_string(o.index) << "\"\n  },\n";
  look_section(out, look, pov);
  if (constraint) {
    const RepairReport& r = constraint->repair_report();
    out << "  \"constraint\": {\n    \"mesh\": ";
    out << json::string(mesh_file);
    out << ",\n    \"side\": \"" << to_string(constraint->options().side) << "\",\n    \"mode\": \""
        << to_string(constraint->options().mode) << "\",\n    \"shell_spacings\": ";
    out.number(constraint->shell() / constraint->spacing()) << ",\n    \"input_triangles\": ";
    out.integer(static_cast<long long>(r.input_triangles)) << ",\n    \"triangles\": ";
    out.integer(static_cast<long long>(constraint->mesh().triangles.size())) << ",\n    \"repair\": ";
    out << json::string(r.summary());
    out << ",\n    \"closed\": " << (r.closed ? "true" : "false") << "\n  },\n";
  }
  counts(out, cluster);
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
  measures(out, cluster);
  timings(out, cluster, record);
  // How the run was spread over threads changes how long it took, never what it grew.
  out << ",\n    \"threads\": ";
  out.integer(o.threads) << ",\n    \"replays\": ";
  out.integer(static_cast<long long>(cluster.replays));
  out << "\n  }\n}\n";
  out.commit();
}

void write_colonization_report(const Cluster& cluster, const ColonizationOptions& o, const AttractorOptions& a,
                               const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                               const std::string& path, const ColonizationInputs& inputs) {
  detail::OutputFile out(path);
  begin(out, cluster, record);
  out << "  \"model\": \"colonization\",\n  \"rng_seed\": ";
  out.integer(static_cast<long long>(o.rng_seed)) << ",\n  \"options\": {\n    \"max_nodes\": ";
  out.integer(static_cast<long long>(o.max_nodes)) << ",\n    \"max_iterations\": ";
  out.integer(static_cast<long long>(o.max_iterations)) << ",\n    \"spacing\": ";
  out.number(o.spacing) << ",\n    \"kill_distance\": ";
  out.number(o.kill_distance) << ",\n    \"influence\": " << json::number(o.influence) << ",\n    \"noise_amplitude\": ";
  out.number(o.noise_amplitude) << ",\n    \"noise_scale\": ";
  out.number(o.noise_scale) << ",\n    \"tropism\": ";
  vector(out, o.tropism);
  out << ",\n    \"dimensions\": ";
  out.integer(o.dimensions) << ",\n    \"attractors\": ";
  out.integer(static_cast<long long>(inputs.attractor_count));
  if (!inputs.attractors_file.empty()) {
    out << ",\n    \"attractors_from\": " << json::string(inputs.attractors_file);
  } else {
    out << ",\n    \"attractors_in\": \"" << to_string(a.region) << "\"";
    if (a.region == AttractorRegion::sphere) {
      out << ",\n    \"attractor_center\": ";
      vector(out, a.center);
      out << ",\n    \"attractor_radius\": ";
      out.number(a.radius);
    } else if (a.region == AttractorRegion::box) {
      out << ",\n    \"attractor_box\": [";
      vector(out, a.box_min);
      out << ", ";
      vector(out, a.box_max);
      out << ']';
    }
  }
  out << ",\n    \"attractor_falloff\": ";
  out.number(a.falloff) << ",\n    \"roots\": [";
  for (std::size_t i = 0; i < cluster.seed_count; ++i) {
    if (i) out << ", ";
    vector(out, cluster.particles[i].position);
  }
  out << ']';
  if (!inputs.vessel_file.empty()) out << ",\n    \"vessel\": " << json::string(inputs.vessel_file);
  if (!inputs.collide_file.empty())
    out << ",\n    \"collide\": " << json::string(inputs.collide_file) << ",\n    \"collision\": \""
        << to_string(inputs.collision) << '"';
  out << "\n  },\n";
  finish_model_report(out, cluster, look, pov, record);
}

void write_eden_report(const Cluster& cluster, const EdenOptions& o, const std::string& mask_file,
                       const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                       const std::string& path) {
  detail::OutputFile out(path);
  begin(out, cluster, record);
  out << "  \"model\": \"eden\",\n  \"rng_seed\": ";
  out.integer(static_cast<long long>(o.rng_seed)) << ",\n  \"options\": {\n    \"sites\": ";
  out.integer(static_cast<long long>(o.sites)) << ",\n    \"lattice\": \"" << to_string(o.lattice)
                                                << "\",\n    \"dimensions\": ";
  out.integer(dimensions_of(o.lattice)) << ",\n    \"mode\": \"" << to_string(o.mode) << '"';
  if (o.mode == EdenMode::drop) {
    if (mask_file.empty()) out << ",\n    \"mask\": \"" << to_string(o.mask) << '"';
    else out << ",\n    \"mask_from\": " << json::string(mask_file);
    out << ",\n    \"mask_sites\": [";
    const std::vector<std::array<int, 3>> sites = eden_mask(o);
    for (std::size_t i = 0; i < sites.size(); ++i) {
      out << (i ? ", [" : "[");
      out.integer(sites[i][0]) << ", ";
      out.integer(sites[i][1]) << ", ";
      out.integer(sites[i][2]) << ']';
    }
    out << "],\n    \"mask_threshold\": ";
    out.integer(o.mask_threshold);
  }
  out << ",\n    \"seed_radius\": ";
  out.number(o.seed_radius) << ",\n    \"spacing\": ";
  out.number(o.spacing) << "\n  },\n";
  finish_model_report(out, cluster, look, pov, record);
}

namespace {

void seeds_entry(detail::OutputFile& out, const std::vector<Vec3>& seeds) {
  out << ",\n    \"seeds\": [";
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (i) out << ", ";
    vector(out, seeds[i]);
  }
  out << ']';
}

void count_entry(detail::OutputFile& out, const char* name, std::uint64_t value) {
  out << ",\n    \"" << name << "\": ";
  out.integer(static_cast<long long>(value));
}

}  // namespace

void write_drop_report(const Cluster& cluster, const DropOptions& o, const DropStats& stats,
                       const MeshConstraint* constraint, const std::string& mesh_file, const LookOptions& look,
                       const PovOptions& pov, const RunRecord& record, const std::string& path) {
  detail::OutputFile out(path);
  begin(out, cluster, record);
  out << "  \"model\": \"drop\",\n  \"rng_seed\": ";
  out.integer(static_cast<long long>(o.rng_seed)) << ",\n  \"options\": {\n    \"particles\": ";
  out.integer(static_cast<long long>(o.particles)) << ",\n    \"dimensions\": ";
  out.integer(o.dimensions) << ",\n    \"spacing\": ";
  out.number(o.spacing) << ",\n    \"stickiness\": ";
  out.number(o.stickiness);
  seeds_entry(out, o.seeds);
  out << ",\n    \"zone\": \"" << to_string(o.zone) << '"';
  if (o.zone != DropZone::mesh) {
    out << ",\n    \"zone_radius\": ";
    if (o.zone_radius > 0.0) {
      out.number(o.zone_radius);
    } else {
      out << "\"growing\",\n    \"zone_margin\": ";
      out.number(o.zone_margin);
    }
  }
  if (o.zone_box) {
    out << ",\n    \"zone_box\": [";
    vector(out, o.zone_box->min);
    out << ", ";
    vector(out, o.zone_box->max);
    out << ']';
  }
  out << ",\n    \"drop\": " << json::string(to_string(o.bias));
  if (constraint)
    out << ",\n    \"mesh\": " << json::string(mesh_file) << ",\n    \"side\": \"" << to_string(constraint->options().side)
        << "\",\n    \"constraint\": \"" << to_string(constraint->options().mode) << '"';
  out << "\n  },\n  \"drops\": {\n    \"drops\": ";
  out.integer(static_cast<long long>(stats.drops));
  count_entry(out, "on_structure", stats.on_structure);
  count_entry(out, "refused", stats.refused);
  count_entry(out, "lost", stats.lost);
  count_entry(out, "mesh_rejected", stats.mesh_rejected);
  count_entry(out, "clipped", stats.clipped);
  out << ",\n    \"zone_full\": " << (stats.zone_full ? "true" : "false") << "\n  },\n";
  finish_model_report(out, cluster, look, pov, record);
}

void write_ballistic_report(const Cluster& cluster, const BallisticOptions& o, const BallisticStats& stats,
                            const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                            const std::string& path) {
  detail::OutputFile out(path);
  begin(out, cluster, record);
  out << "  \"model\": \"ballistic\",\n  \"rng_seed\": ";
  out.integer(static_cast<long long>(o.rng_seed)) << ",\n  \"options\": {\n    \"particles\": ";
  out.integer(static_cast<long long>(o.particles)) << ",\n    \"dimensions\": ";
  out.integer(o.dimensions) << ",\n    \"spacing\": ";
  out.number(o.spacing);
  seeds_entry(out, o.seeds);
  out << ",\n    \"direction\": ";
  if (o.direction.squaredNorm() > 0.0) vector(out, o.direction);
  else out << "\"random\"";
  out << "\n  },\n  \"lines\": {\n    \"launched\": ";
  out.integer(static_cast<long long>(stats.launched));
  count_entry(out, "missed", stats.missed);
  count_entry(out, "far_steps", stats.far_steps);
  count_entry(out, "near_steps", stats.near_steps);
  out << "\n  },\n";
  finish_model_report(out, cluster, look, pov, record);
}

}  // namespace dla
