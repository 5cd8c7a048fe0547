#include "dla/pov_writer.h"

#include "dla/strands.h"
#include "dla/version.h"
#include "output_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dla {

namespace {

std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

//! Text for a `//` comment: a line break in it (an argument with a newline) would start a line
//! of scene code, so control characters are written as \xNN.
std::string comment_text(const std::string& text) {
  std::string safe;
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
      safe += escaped;
    } else {
      safe += c;
    }
  }
  return safe;
}

//! How scene coordinates come from the structure's: (p - shift) * scale. POV-Ray's epsilons are
//! absolute (about 1e-6) and it drops what lies beyond 1e7, so a structure with a spacing
//! outside [1e-3, 10] is scaled to a spacing of 1 (a power of ten), and one whose centre lies
//! more than 10^4 spacings from the origin is shifted to it. Coordinates are written with
//! `decimals` places: a thousandth of a spacing.
struct SceneFrame {
  Vec3 shift = Vec3::Zero();
  double scale = 1.0;
  int decimals = 3;

  Vec3 operator()(const Vec3& p) const { return (p - shift) * scale; }
  bool identity() const { return scale == 1.0 && shift == Vec3::Zero(); }
};

SceneFrame scene_frame(double spacing, const Vec3& center) {
  SceneFrame frame;
  if (spacing < 1e-3 || spacing > 10.0) frame.scale = std::pow(10.0, -std::round(std::log10(spacing)));
  if (center.cwiseAbs().maxCoeff() > 1e4 * spacing) frame.shift = center;
  frame.decimals = std::clamp(3 - static_cast<int>(std::floor(std::log10(spacing * frame.scale))), 0, 9);
  return frame;
}

void vector(detail::OutputFile& out, const Vec3& v, const SceneFrame& frame) {
  const Vec3 p = frame(v);
  out << '<';
  out.fixed(p.x(), frame.decimals) << ", ";
  out.fixed(p.y(), frame.decimals) << ", ";
  out.fixed(p.z(), frame.decimals) << '>';
}

// Centre and radius of a sphere around every particle centre and mesh vertex (the box's
// centre, not the smallest sphere: close enough for framing).
std::pair<Vec3, double> bounding_sphere(const Cluster& cluster, const TriangleMesh* mesh) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const auto each_point = [&](auto&& visit) {
    for (const Particle& p : cluster.particles) visit(p.position);
    if (mesh)
      for (const Vec3& v : mesh->vertices) visit(v);
  };
  each_point([&](const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  });
  const Vec3 center = 0.5 * (lo + hi);
  double r2 = 0.0;
  each_point([&](const Vec3& p) { r2 = std::max(r2, (p - center).squaredNorm()); });
  return {center, std::sqrt(r2)};
}

void write_mesh(detail::OutputFile& out, const TriangleMesh& mesh, const SceneFrame& frame) {
  out << "#declare DLA_Mesh = mesh2 {\n  vertex_vectors { ";
  out.integer(static_cast<long long>(mesh.vertices.size()));
  for (const Vec3& v : mesh.vertices) {
    out << ",\n    ";
    vector(out, v, frame);
  }
  out << " }\n  face_indices { ";
  out.integer(static_cast<long long>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    out << ",\n    <";
    out.integer(t[0]) << ", ";
    out.integer(t[1]) << ", ";
    out.integer(t[2]) << '>';
  }
  out << " }\n}\n";
}

void write_geometry(const Cluster& cluster, const TriangleMesh* mesh, const SceneFrame& frame,
                    const std::string& path) {
  detail::OutputFile out(path);
  out << "// dla3d " << version << " geometry: ";
  out.integer(static_cast<long long>(cluster.particles.size())) << " particles in ";
  out.integer(static_cast<long long>(count_strands(cluster)))
      << " strands.\n// Declares DLA_Structure" << (mesh ? " and DLA_Mesh" : "")
      << "; uses DLA_R and DLA_BaseRadius from the .pov.\n";
  if (mesh) write_mesh(out, *mesh, frame);
  out << "#declare DLA_Structure = union {\n";
  for (std::size_t s = 0; s < cluster.seed_count; ++s) {
    out << "  sphere { ";
    vector(out, cluster.particles[s].position, frame);
    out << ", DLA_BaseRadius }\n";
  }
  for_each_strand(cluster, [&](const Strand& strand) {
    if (strand.size() < 2) return;  // a lone seed: its sphere is above
    out << "  sphere_sweep { linear_spline, ";
    out.integer(static_cast<long long>(strand.size())) << ",\n";
    const double last = static_cast<double>(strand.size() - 1);
    for (std::size_t i = 0; i < strand.size(); ++i) {
      out << "    ";
      vector(out, cluster.particles[static_cast<std::size_t>(strand[i])].position, frame);
      out << ", DLA_R(";
      out.fixed(1.0 - static_cast<double>(i) / last, 4) << ")\n";
    }
    out << "  }\n";
  });
  out << "}\n";
  out.commit();
}

}  // namespace

void validate(const PovOptions& options) {
  detail::require_in("base radius", options.base_radius, kMinBranchRadius, kMaxBranchRadius);
  detail::require_in("tip radius", options.tip_radius, kMinBranchRadius, kMaxBranchRadius);
}

void validate_pov_prefix(const std::string& prefix) {
  const std::string name = file_name(prefix);
  for (const char c : name)
    if (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw InvalidInput("the file name '" + comment_text(name) +
                         "' has a quote, a backslash or a control character, which POV-Ray's #include cannot name");
}

void write_pov(const Cluster& cluster, const std::string& prefix, const PovOptions& options,
               const TriangleMesh* mesh) {
  validate(options);
  validate_pov_prefix(prefix);
  const std::string include = prefix + ".inc";
  const auto [center, radius] = bounding_sphere(cluster, mesh);
  const SceneFrame frame = scene_frame(cluster.spacing, center);
  write_geometry(cluster, mesh, frame, include);

  const double base = options.base_radius * cluster.spacing * frame.scale;
  detail::OutputFile out(prefix + ".pov");
  if (!options.comment.empty()) out << "// " << comment_text(options.comment) << '\n';
  out << "// dla3d " << version << " scene: ";
  out.integer(static_cast<long long>(cluster.particles.size()))
      << " particles. Render with: povray +W1280 +H960 +A " << comment_text(file_name(prefix)) << ".pov\n";
  out << "#version 3.7;\n"
         "global_settings { assumed_gamma 1.0 }\n\n";
  if (!frame.identity()) {
    // POV-Ray's fixed epsilons: the scene is in other units than the CSV and PLY.
    out << "// Scene units: POV-Ray works best near a unit of 1, so the coordinates here are the\n"
           "// structure's as (p - DLA_Shift) * DLA_Scale. The CSV and PLY hold them as grown.\n"
           "#declare DLA_Scale = ";
    out.number(frame.scale) << ";\n#declare DLA_Shift = <";
    out.number(frame.shift.x()) << ", ";
    out.number(frame.shift.y()) << ", ";
    out.number(frame.shift.z()) << ">;\n\n";
  }
  out << "// The look: change these and render again, no need to grow again.\n"
         "#declare DLA_BaseRadius = ";
  out.number(base, 7) << ";  // radius at each strand's start\n#declare DLA_TipRadius = ";
  out.number(options.tip_radius * cluster.spacing * frame.scale, 7)
      << ";  // radius at each strand's tip\n"
         "#declare DLA_Texture = texture {\n"
         "  pigment { color rgb <0.90, 0.80, 0.62> }\n"
         "  finish { ambient 0.06 diffuse 0.8 specular 0.4 roughness 0.015 }\n"
         "}\n"
         "#declare DLA_Background = rgb <0.04, 0.05, 0.07>;\n";
  if (mesh)
    out << "#declare DLA_ShowMesh = on;  // the constraint mesh, as glass\n"
           "#declare DLA_MeshTexture = texture {\n"
           "  pigment { color rgbt <0.80, 0.90, 1.0, 0.92> }\n"
           "  finish { ambient 0.04 diffuse 0.12 specular 0.6 roughness 0.004 reflection 0.03 }\n"
           "}\n";
  out << "#declare DLA_R = function(F) { DLA_TipRadius + (DLA_BaseRadius - DLA_TipRadius) * F }\n\n"
         "// Framing: a sphere around the structure (and mesh), seen from DLA_View.\n"
         "#declare DLA_Center = ";
  vector(out, center, frame);
  out << ";\n#declare DLA_Radius = ";
  // Seen from the front, a little from the side and above, whichever axis is up.
  const char* view = cluster.dimensions == 2     ? "<0, 0, -1>"
                     : options.up == Axis::z ? "<0.35, 1, 0.45>"
                     : options.up == Axis::x ? "<0.45, 0.35, -1>"
                                             : "<0.35, 0.45, -1>";
  out.number(radius * frame.scale + base, 7) << ";\n#declare DLA_View = " << view
                               << ";  // from the centre towards the camera\n#declare DLA_Sky = "
                               << (options.up == Axis::z ? "z" : options.up == Axis::x ? "x" : "y")
                               << ";  // up in the picture\n"
         "#declare DLA_Angle = 40;  // horizontal field of view, degrees\n"
         "#declare DLA_Aspect = image_width / image_height;\n"
         "#declare DLA_HalfAngle = min(DLA_Angle / 2, degrees(atan(tan(radians(DLA_Angle / 2)) / DLA_Aspect)));\n"
         "#declare DLA_Distance = 1.05 * DLA_Radius / sin(radians(DLA_HalfAngle));\n\n"
         "background { color DLA_Background }\n"
         "camera {\n"
         "  perspective\n"
         "  location DLA_Center + DLA_Distance * vnormalize(DLA_View)\n"
         "  look_at DLA_Center\n"
         "  right x * DLA_Aspect\n"
         "  angle DLA_Angle\n"
         "  sky DLA_Sky\n"
         "}\n"
         "light_source { DLA_Center + 3 * DLA_Distance * <-0.6, 1.0, -0.8> color rgb 1.0 }\n"
         "light_source { DLA_Center + 3 * DLA_Distance * <0.8, 0.3, -0.4> color rgb 0.3 shadowless }\n\n"
         "#include \""
      << file_name(include) << "\"\nobject { DLA_Structure texture { DLA_Texture } }\n";
  if (mesh) out << "#if (DLA_ShowMesh) object { DLA_Mesh texture { DLA_MeshTexture } no_shadow } #end\n";
  out.commit();
}

}  // namespace dla
