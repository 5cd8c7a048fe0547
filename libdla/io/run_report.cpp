#include "dla/io/run_report.h"

#include "dla/core/analysis.h"
#include "dla/look/strands.h"
#include "dla/version.h"
#include "output_file.h"

#include <cmath>

namespace dla {

void write_run_report(const Cluster& cluster, const ModelRecord& model, const LookOptions& look,
                      const PovOptions& pov, const RunRecord& record, const std::string& path) {
  RecordWriter out;
  out.text("generator", "dla3d").text("version", version);
  if (!record.command.empty()) out.text("command", record.command);
  out.flag("complete", cluster.complete);
  if (!record.stopped_by.empty()) out.text("stopped_by", record.stopped_by);
  if (!record.stopped_in.empty()) out.text("stopped_in", record.stopped_in);
  out.text("model", model.model).count("rng_seed", model.rng_seed);
  out.open("options");
  if (model.options) model.options(out);
  out.close();
  if (model.resolved) {
    out.open("resolved");
    model.resolved(out);
    out.close();
  }

  out.open("look")
      .text("radius", to_string(look.radius.model))
      .number("base_radius", look.radius.base_radius)
      .number("tip_radius", look.radius.tip_radius)
      .number("pipe_exponent", look.radius.pipe_exponent)
      .text("color_by", to_string(look.color_by))
      .integer("tube_sides", look.tubes.sides)
      .number("tube_tolerance", look.tubes.tolerance)
      .text("pov_look", to_string(pov.style))
      .close();

  out.open("counts")
      .count("particles", cluster.particles.size())
      .count("seeds", cluster.seed_count)
      .count("attached", attached(cluster))
      .count("strands", count_strands(cluster))
      .count("links", cluster.links.size())
      .count("cycles", cycle_count(cluster))
      .close();
  if (model.statistics) model.statistics(out);

  // A fit of fewer than two samples has no slope.
  const auto dimension = [](const FractalFit& fit) { return fit.samples >= 2 ? fit.dimension : NAN; };
  out.open("measures")
      .point("center", cluster.center)
      .number("bounding_radius", bounding_radius(cluster), 9)
      .number("radius_of_gyration", radius_of_gyration(cluster), 9)
      .number("fractal_dimension_gyration", dimension(fractal_dimension_by_gyration(cluster)), 5)
      .number("fractal_dimension_mass_radius", dimension(fractal_dimension_by_mass_radius(cluster)), 5);
  if (model.measures) model.measures(out);
  out.close();

  if (!record.lod_triangles.empty()) {
    std::string counts;
    for (const std::size_t n : record.lod_triangles) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
    out.raw("lod_triangles", "[" + counts + "]");
  }
  if (record.leaves) out.number("leaves", static_cast<double>(*record.leaves));

  if (record.solid) {
    const SolidMeasures& m = *record.solid;
    out.open("solid")
        .text("units", record.printed ? "mm" : "scene")
        .number("volume", m.volume, 9)
        .number("volume_cm3", record.printed ? m.volume / 1000.0 : NAN, 6)
        .number("area", m.area, 9)
        .count("shells", m.shells)
        .number("thinnest_wall", m.thinnest_wall, 6)
        .count("thickened", m.thickened)
        .number("voxel", m.voxel, 9)
        .number("scale", m.scale, 9)
        .count("active_voxels", m.active_voxels)
        .number("estimated_bytes", m.estimated_bytes, 3)
        .number("estimated_seconds", m.estimated_seconds, 3)
        .raw("size", "[" + json::number(m.size.x(), 7) + ", " + json::number(m.size.y(), 7) + ", " +
                         json::number(m.size.z(), 7) + "]")
        .close();
  }

  const double rate = record.grow_seconds > 0 ? static_cast<double>(attached(cluster)) / record.grow_seconds : 0.0;
  out.open("timings")
      .number("grow_seconds", record.grow_seconds, 6)
      .number("write_seconds", record.write_seconds, 6)
      .number("particles_per_second", rate, 6);
  if (model.timings) model.timings(out);
  out.close();

  detail::OutputFile file(path);
  file << out.finish();
  file.commit();
}

std::string describe(const SolidMeasures& m, bool printed) {
  const auto number = [](double value, int digits) { return json::number(value, digits); };
  std::string line = "solid: " + (printed ? number(m.volume / 1000.0, 4) + " cm3" : number(m.volume, 4) + " volume") +
                     ", area " + number(m.area, 4) + (printed ? " mm2" : "") + ", " + std::to_string(m.shells) +
                     (m.shells == 1 ? " shell" : " shells") + ", thinnest wall " + number(m.thinnest_wall, 3) +
                     (printed ? " mm" : "");
  if (m.thickened) line += ", " + detail::format_count(m.thickened) + " branches thickened";
  line += ", voxel " + number(m.voxel, 3) + (printed ? " mm" : "");
  if (m.shells > 1) line += "; several seeds grow apart: `solid_join` joins their trees";
  return line;
}

}  // namespace dla
