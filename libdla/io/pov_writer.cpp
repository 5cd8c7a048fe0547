#include "dla/io/pov_writer.h"

#include "dla/look/instances.h"
#include "dla/look/strands.h"
#include "dla/version.h"
#include "output_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <future>
#include <string>
#include <vector>

namespace dla {

namespace {

//! Particles whose strands (those ending at tips among them) or tips are formatted as one
//! part of the file, on a thread of its own (write_in_order): up to about 300 kB of text,
//! still in cache when it is written.
constexpr std::size_t kChunk = 1 << 12;

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

void vector(detail::Text& out, const Vec3& v, const SceneFrame& frame) {
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

//! Vertex normals, each the area-weighted mean of its triangles': the glass is smooth, not
//! faceted. A vertex whose triangles cancel out gets its first triangle's normal.
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> normals(mesh.vertices.size(), Vec3::Zero()), fallback(mesh.vertices.size(), Vec3::Zero());
  for (const auto& t : mesh.triangles) {
    const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    for (const std::uint32_t v : t) {
      normals[v] += n;
      if (fallback[v].squaredNorm() == 0.0) fallback[v] = n;
    }
  }
  for (std::size_t v = 0; v < normals.size(); ++v) {
    if (normals[v].squaredNorm() == 0.0) normals[v] = fallback[v];
    normals[v] = normals[v].squaredNorm() > 0.0 ? normals[v].normalized() : Vec3::UnitZ();
  }
  return normals;
}

//! PREFIX_mesh.inc: DLA_Mesh, apart from the structure, which comes from PREFIX.inc or, in a
//! growth frame, from PREFIX_growth.inc.
void write_mesh(const TriangleMesh& mesh, const SceneFrame& frame, const std::string& path) {
  detail::OutputFile out(path);
  out << "// dla3d " << version << " constraint mesh: DLA_Mesh, shown by DLA_ShowMesh in the .pov.\n";
  out << "#declare DLA_Mesh = mesh2 {\n  vertex_vectors { ";
  out.integer(static_cast<long long>(mesh.vertices.size()));
  for (const Vec3& v : mesh.vertices) {
    out << ",\n    ";
    vector(out, v, frame);
  }
  out << " }\n  normal_vectors { ";
  out.integer(static_cast<long long>(mesh.vertices.size()));
  for (const Vec3& n : vertex_normals(mesh)) {
    out << ",\n    <";
    out.fixed(n.x(), 5) << ", ";
    out.fixed(n.y(), 5) << ", ";
    out.fixed(n.z(), 5) << '>';
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
  out.commit();
}

//! What the scene's branches are painted by: the look's colour, and for the glow, which is
//! always as bright as some value, the current when the look has none.
ColorBy painted_by(const Look& look, const PovOptions& options) {
  const ColorBy by = look.options.color_by;
  return options.style == PovStyle::glow && by == ColorBy::none ? ColorBy::current : by;
}

//! Whether the scene's DLA_R takes each particle's own radius as a fifth argument, M: with the
//! `particle` radius model (an aggregate's monomers), which has nothing else to go by.
bool own_radii(const Look& look) { return look.options.radius.model == RadiusModel::particle; }

//! Writes the arguments of DLA_R for particle i: its place along its strand, its flow (the
//! subtree's size, or a discharge's current), and its distances to the mesh and to the seeds as fractions of the largest;
//! with own_radii(), its own radius in scene units.
class RadiusArguments {
 public:
  RadiusArguments(const Cluster& cluster, const Look& look, double scale)
      : cluster_(cluster), attributes_(look.attributes), own_(own_radii(look)), scale_(scale) {}

  void operator()(detail::Text& out, std::size_t i) const {
    const Attributes& a = attributes_;
    out << "DLA_R(";
    out.fixed(a.taper(i), 4) << ", ";
    out.integer(a.flow(i)) << ", ";
    out.fixed(a.boundary_reach > 0 ? a.boundary_distance[i] / a.boundary_reach : 0.0, 3) << ", ";
    const double seed = a.seed_distance(cluster_.particles[i].position);
    out.fixed(a.seed_reach > 0 ? seed / a.seed_reach : 0.0, 3);
    if (own_) {
      out << ", ";
      out.number(cluster_.radii[i] * scale_, 7);
    }
    out << ')';
  }

  //! Starts loading particle i's attributes. A strand's particles lie far apart in memory: at
  //! 10^7, loading them one at a time took a quarter of the scene's time.
  void prefetch(std::size_t i) const {
    __builtin_prefetch(&attributes_.strand_place[i]);
    __builtin_prefetch(&attributes_.descendants[i]);
    if (attributes_.boundary_reach > 0) __builtin_prefetch(&attributes_.boundary_distance[i]);
  }

 private:
  const Cluster& cluster_;
  const Attributes& attributes_;
  bool own_;
  double scale_;
};

void write_geometry(const Cluster& cluster, const SceneFrame& frame, const Look& look, const PovOptions& options,
                    const std::string& path) {
  const auto& ps = cluster.particles;
  const RadiusArguments radius(cluster, look, frame.scale);
  const ColorBy by = painted_by(look, options);
  const bool colored = by != ColorBy::none;
  const ColorScale color(cluster, look.attributes, by);
  const auto paint = [&](detail::Text& out, std::size_t i) {
    if (!colored) return;
    out << " texture { DLA_Paint(";
    out.fixed(color(i), 4) << ") }";
  };
  detail::OutputFile out(path);
  out << "// dla3d " << version << " geometry: ";
  out.integer(static_cast<long long>(ps.size())) << " particles in ";
  out.integer(static_cast<long long>(count_strands(cluster)))
      << " strands.\n// Declares DLA_Structure; uses DLA_R" << (options.style == PovStyle::blob ? ", DLA_BlobRadius" : "")
      << (colored ? " and DLA_Paint" : "") << " from the .pov.\n"
      << "// DLA_R(F, P, B, S): F the place along the strand (1 at its start, 0 at its tip), P the particles\n"
         "// in the subtree, B and S the distances to the mesh and to the seeds (1: the largest).\n";
  if (options.style == PovStyle::blob) {
    out << "#declare DLA_Structure = blob {\n  threshold DLA_BlobThreshold\n";
    write_in_order(out, ps.size(), kChunk, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        text << "  sphere { ";
        vector(text, ps[i].position, frame);
        text << ", DLA_BlobRadius(";
        radius(text, i);
        text << "), 1";
        paint(text, i);
        text << " }\n";
      }
    });
    // A link: a cylinder as wide as the thinner end's blob.
    for (const Link& link : cluster.links) {
      const auto a = static_cast<std::size_t>(link.earlier), b = static_cast<std::size_t>(link.later);
      out << "  cylinder { ";
      vector(out, ps[a].position, frame);
      out << ", ";
      vector(out, ps[b].position, frame);
      out << ", min(DLA_BlobRadius(";
      radius(out, a);
      out << "), DLA_BlobRadius(";
      radius(out, b);
      out << ")), 1";
      paint(out, b);
      out << " }\n";
    }
    out << "}\n";
  } else if (options.style == PovStyle::spheres) {
    out << "#declare DLA_Structure = union {\n";
    write_in_order(out, ps.size(), kChunk, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        text << "  sphere { ";
        vector(text, ps[i].position, frame);
        text << ", ";
        radius(text, i);
        paint(text, i);
        text << " }\n";
      }
    });
    out << "}\n";
  } else {
    out << "#declare DLA_Structure = union {\n";
    for (std::size_t s = 0; s < cluster.seed_count; ++s) {
      out << "  sphere { ";
      vector(out, ps[s].position, frame);
      out << ", ";
      radius(out, s);
      paint(out, s);
      out << " }\n";
    }
    const auto continues = [&](std::size_t i) { return look.attributes.continues_strand(i); };
    const auto is_tip = [&](std::size_t i) { return look.attributes.tip(i); };
    const auto write_strand = [&](detail::Text& out, const Strand& strand) {
      if (strand.size() < 2) return;  // a lone seed: its sphere is above
      for (const std::int32_t i : strand) radius.prefetch(static_cast<std::size_t>(i));
      const auto first = static_cast<std::size_t>(strand[0]), next = static_cast<std::size_t>(strand[1]);
      const bool own_start = starts_at_own_seed(strand, continues);
      out << "  sphere_sweep { linear_spline, ";
      out.integer(static_cast<long long>(strand.size())) << ",\n    ";
      vector(out, ps[first].position, frame);
      // A strand leaving a branch point starts inside its parent's branch (as the tubes do).
      if (own_start) {
        out << ", ";
        radius(out, first);
      } else {
        out << ", min(";
        radius(out, first);
        out << ", ";
        radius(out, next);
        out << ')';
      }
      out << '\n';
      for (std::size_t k = 1; k < strand.size(); ++k) {
        out << "    ";
        vector(out, ps[static_cast<std::size_t>(strand[k])].position, frame);
        out << ", ";
        radius(out, static_cast<std::size_t>(strand[k]));
        out << '\n';
      }
      if (colored) {
        out << "   ";
        paint(out, own_start ? first : next);
        out << '\n';
      }
      out << "  }\n";
    };
    // The strands by ranges of their tips, formatted at once and appended in order.
    write_in_order(out, ps.size(), kChunk, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
      for_each_strand_in(cluster, begin, end, is_tip, continues, [&](const Strand& strand) { write_strand(text, strand); });
    });
    // A link: a sphere sweep from one particle to the other, with each one's radius.
    for (const Link& link : cluster.links) {
      const auto a = static_cast<std::size_t>(link.earlier), b = static_cast<std::size_t>(link.later);
      out << "  sphere_sweep { linear_spline, 2, ";
      vector(out, ps[a].position, frame);
      out << ", ";
      radius(out, a);
      out << ", ";
      vector(out, ps[b].position, frame);
      out << ", ";
      radius(out, b);
      paint(out, b);
      out << " }\n";
    }
    out << "}\n";
  }
  out.commit();
}

//! Writes `#declare NAME = array[n] {...}` with value(text, i) for each particle, eight a line.
template <class Value>
void write_array(detail::OutputFile& out, const char* name, std::size_t n, Value&& value) {
  out << "#declare " << name << " = array[";
  out.integer(static_cast<long long>(n)) << "] {";
  write_in_order(out, n, kChunk, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i > 0) text << ',';
      if (i % 8 == 0) text << "\n  ";
      else text << ' ';
      value(text, i);
    }
  });
  out << "\n}\n";
}

//! PREFIX_growth.inc, read instead of PREFIX.inc when DLA_Show < 1: the tree as arrays, and the
//! scene code that builds DLA_Structure from its first DLA_N particles. The strands are the
//! finished structure's, cut at the last particle grown, so they never jump from one branch to
//! another between frames. The radius follows the structure of the moment: the taper runs along
//! the part of each strand grown so far and the pipe model counts the subtrees so far, so a
//! branch only thickens as it grows. The distances to the mesh and the seeds, which do not
//! change, keep the finished structure's scale. At every particle this is PREFIX.inc.
void write_growth(const Cluster& cluster, const SceneFrame& frame, const Look& look, const PovOptions& options,
                  const std::string& path) {
  const auto& ps = cluster.particles;
  const Attributes& a = look.attributes;
  const ColorBy by = painted_by(look, options);
  const bool colored = by != ColorBy::none, boundary = a.boundary_reach > 0;
  const ColorScale color(cluster, a, by);
  detail::OutputFile out(path);
  out << "// dla3d " << version << " growth: the tree, from which DLA_Structure is built as it was when a\n"
         "// fraction DLA_Show of the particles had attached. Read by the .pov when DLA_Show < 1.\n"
         "#declare DLA_GrowthParticles = ";
  out.integer(static_cast<long long>(ps.size())) << ";\n#declare DLA_GrowthSeeds = ";
  out.integer(static_cast<long long>(cluster.seed_count)) << ";\n";
  write_array(out, "DLA_Position", ps.size(), [&](detail::Text& text, std::size_t i) { vector(text, ps[i].position, frame); });
  write_array(out, "DLA_Parent", ps.size(), [&](detail::Text& text, std::size_t i) { text.integer(ps[i].parent); });
  {
    std::vector<std::int32_t> next(ps.size(), -1);
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (a.continues_strand(i)) next[static_cast<std::size_t>(ps[i].parent)] = static_cast<std::int32_t>(i);
    write_array(out, "DLA_Next", ps.size(), [&](detail::Text& text, std::size_t i) { text.integer(next[i]); });
  }
  if (boundary)
    write_array(out, "DLA_Boundary", ps.size(), [&](detail::Text& text, std::size_t i) {
      text.fixed(a.boundary_distance[i] / a.boundary_reach, 3);
    });
  write_array(out, "DLA_SeedDistance", ps.size(), [&](detail::Text& text, std::size_t i) {
    text.fixed(a.seed_reach > 0 ? a.seed_distance(ps[i].position) / a.seed_reach : 0.0, 3);
  });
  if (colored) write_array(out, "DLA_Value", ps.size(), [&](detail::Text& text, std::size_t i) { text.fixed(color(i), 4); });
  const bool own = own_radii(look);
  if (own)
    write_array(out, "DLA_Own", ps.size(), [&](detail::Text& text, std::size_t i) {
      text.number(cluster.radii[i] * frame.scale, 7);
    });
  // The links, each shown once its later particle is.
  const std::vector<Link>& links = cluster.links;
  if (!links.empty()) {
    write_array(out, "DLA_LinkA", links.size(), [&](detail::Text& text, std::size_t k) { text.integer(links[k].earlier); });
    write_array(out, "DLA_LinkB", links.size(), [&](detail::Text& text, std::size_t k) { text.integer(links[k].later); });
  }
  const auto link_loop = [&](const std::string& shape) {
    if (links.empty()) return std::string();
    return "  #for (DLA_K, 0, " + std::to_string(links.size() - 1) + ")\n    #if (DLA_LinkB[DLA_K] < DLA_N)\n      " + shape +
           "\n    #end\n  #end\n";
  };

  const auto radius = [&](const char* i) {
    return std::string("DLA_R(DLA_Place[") + i + "], DLA_Descendants[" + i + "] + 1, " +
           (boundary ? std::string("DLA_Boundary[") + i + "]" : std::string("0")) + ", DLA_SeedDistance[" + i + "]" +
           (own ? std::string(", DLA_Own[") + i + "]" : std::string()) + ")";
  };
  const auto paint = [&](const char* i) {
    return colored ? std::string(" texture { DLA_Paint(DLA_Value[") + i + "]) }" : std::string();
  };
  out << "\n// The first DLA_N particles, on the finished structure's strands (DLA_Next: the child that goes\n"
         "// on with each one's strand, or -1) cut at the last of them: DLA_Step, each one's place on its\n"
         "// strand from its start; DLA_Last, that of its strand's last particle so far; DLA_Place, the\n"
         "// taper's 1 at the strand's start to 0 at that particle; and the particles in each subtree.\n"
         "#declare DLA_N = DLA_GrowthSeeds + floor(min(max(DLA_Show, 0), 1) * (DLA_GrowthParticles - DLA_GrowthSeeds) + 0.5);\n"
         "#declare DLA_Descendants = array[DLA_N];\n"
         "#declare DLA_Step = array[DLA_N];\n"
         "#declare DLA_Last = array[DLA_N];\n"
         "#declare DLA_Place = array[DLA_N];\n"
         "#for (DLA_I, 0, DLA_N - 1)\n"
         "  #declare DLA_P = DLA_Parent[DLA_I];\n"
         "  #declare DLA_Descendants[DLA_I] = 0;\n"
         "  #declare DLA_Step[DLA_I] = 0;\n"
         "  #if (DLA_P >= 0) #declare DLA_Step[DLA_I] = (DLA_Next[DLA_P] = DLA_I ? DLA_Step[DLA_P] + 1 : 1); #end\n"
         "  #declare DLA_Last[DLA_I] = DLA_Step[DLA_I];\n"
         "#end\n"
         "#for (DLA_I, DLA_N - 1, 0, -1)\n"
         "  #declare DLA_P = DLA_Parent[DLA_I];\n"
         "  #if (DLA_P >= 0)\n"
         "    #declare DLA_Descendants[DLA_P] = DLA_Descendants[DLA_P] + DLA_Descendants[DLA_I] + 1;\n"
         "    #if (DLA_Next[DLA_P] = DLA_I) #declare DLA_Last[DLA_P] = DLA_Last[DLA_I]; #end\n"
         "  #end\n"
         "  #declare DLA_Place[DLA_I] = (DLA_Last[DLA_I] > 0 ? 1 - DLA_Step[DLA_I] / DLA_Last[DLA_I] : 1);\n"
         "#end\n\n";
  if (options.style == PovStyle::blob) {
    out << "#declare DLA_Structure = blob {\n"
           "  threshold DLA_BlobThreshold\n"
           "  #for (DLA_I, 0, DLA_N - 1)\n"
           "    sphere { DLA_Position[DLA_I], DLA_BlobRadius(" << radius("DLA_I") << "), 1" << paint("DLA_I") << " }\n"
           "  #end\n"
        << link_loop("cylinder { DLA_Position[DLA_LinkA[DLA_K]], DLA_Position[DLA_LinkB[DLA_K]], min(DLA_BlobRadius(" +
                     radius("DLA_LinkA[DLA_K]") + "), DLA_BlobRadius(" + radius("DLA_LinkB[DLA_K]") + ")), 1" +
                     paint("DLA_LinkB[DLA_K]") + " }")
        << "}\n";
  } else if (options.style == PovStyle::spheres) {
    out << "#declare DLA_Structure = union {\n"
           "  #for (DLA_I, 0, DLA_N - 1)\n"
           "    sphere { DLA_Position[DLA_I], " << radius("DLA_I") << paint("DLA_I") << " }\n"
           "  #end\n"
           "}\n";
  } else {
    out << "// A sphere at each seed, and a sphere_sweep along the part grown of each strand, from its last\n"
           "// particle so far up to its start: a strand leaving a branch point starts there, inside its\n"
           "// parent's branch.\n"
           "#declare DLA_Structure = union {\n"
           "  #for (DLA_I, 0, DLA_GrowthSeeds - 1)\n"
           "    sphere { DLA_Position[DLA_I], " << radius("DLA_I") << paint("DLA_I") << " }\n"
           "  #end\n"
           "  #for (DLA_T, DLA_GrowthSeeds, DLA_N - 1)\n"
           "    #if (DLA_Next[DLA_T] < 0 | DLA_Next[DLA_T] >= DLA_N)\n"
           "      #declare DLA_J = DLA_T;\n"
           "      #declare DLA_Count = 1;\n"
           "      #declare DLA_Up = true;\n"
           "      #while (DLA_Up)\n"
           "        #declare DLA_Up = false;\n"
           "        #declare DLA_P = DLA_Parent[DLA_J];\n"
           "        #if (DLA_P >= 0) #if (DLA_Next[DLA_P] = DLA_J)\n"
           "          #declare DLA_J = DLA_P;\n"
           "          #declare DLA_Count = DLA_Count + 1;\n"
           "          #declare DLA_Up = true;\n"
           "        #end #end\n"
           "      #end\n"
           "      #declare DLA_P = DLA_Parent[DLA_J];\n"
           "      sphere_sweep { linear_spline, DLA_Count + (DLA_P >= 0 ? 1 : 0)\n"
           "        #declare DLA_I = DLA_T;\n"
           "        #while (DLA_I != DLA_J)\n"
           "          , DLA_Position[DLA_I], " << radius("DLA_I") << "\n"
           "          #declare DLA_I = DLA_Parent[DLA_I];\n"
           "        #end\n"
           "        , DLA_Position[DLA_J], " << radius("DLA_J") << "\n"
           "        #if (DLA_P >= 0) , DLA_Position[DLA_P], min(" << radius("DLA_P") << ", " << radius("DLA_J") << ") #end\n"
           "       " << paint("DLA_J") << "\n"
           "      }\n"
           "    #end\n"
           "  #end\n"
        << link_loop("sphere_sweep { linear_spline, 2, DLA_Position[DLA_LinkA[DLA_K]], " + radius("DLA_LinkA[DLA_K]") +
                     ", DLA_Position[DLA_LinkB[DLA_K]], " + radius("DLA_LinkB[DLA_K]") + paint("DLA_LinkB[DLA_K]") + " }")
        << "}\n";
  }
  // The finished structure's tips have their no-overlap scale in PREFIX_tips.inc; the tips of
  // a moment get half a spacing.
  out << "\n// DLA_Tip at the tips of the moment, each with a scale of half a spacing.\n"
         "#if (DLA_ShowTips)\n"
         "  #declare DLA_TipCount = 0;\n"
         "  #for (DLA_T, DLA_GrowthSeeds, DLA_N - 1)\n"
         "    #if (DLA_Descendants[DLA_T] = 0) #declare DLA_TipCount = DLA_TipCount + 1; #end\n"
         "  #end\n"
         "  #if (DLA_TipCount > 0)\n"
         "    #declare DLA_Tips = #if (DLA_TipCount > 1) union #else object #end {\n"
         "      #for (DLA_T, DLA_GrowthSeeds, DLA_N - 1)\n"
         "        #if (DLA_Descendants[DLA_T] = 0)\n"
         "          DLA_Tip(DLA_Position[DLA_T], vnormalize(DLA_Position[DLA_T] - DLA_Position[DLA_Parent[DLA_T]]), ";
  out.number(0.5 * cluster.spacing * frame.scale, 7) << ")\n"
         "        #end\n"
         "      #end\n"
         "    }\n"
         "  #end\n"
         "#end\n";
  out.commit();
}

//! PREFIX_tips.inc: DLA_TipCount, and DLA_Tips, a DLA_Tip call at every instancing point (the
//! tips, or with InstanceSet::all every particle: the thesis' object fill) with the largest
//! scale at which copies do not overlap (instances.h). Each range of particles starts at its
//! first point's gap.
void write_tips(const Cluster& cluster, const SceneFrame& frame, const Look& look, const InstanceOptions& instances,
                const std::string& path) {
  const auto& ps = cluster.particles;
  detail::OutputFile out(path);
  out << "// dla3d " << version << " tips: DLA_Tip at every "
      << (instances.set == InstanceSet::tips ? "tip" : "particle") << ", shown by DLA_ShowTips in the .pov.\n";
  const Attributes& a = look.attributes;
  const InstanceSelection selected(cluster, a, instances);
  std::vector<float> measured;
  const std::vector<float>& gaps = instance_gaps(cluster, a, instances, selected, measured, detail::format_threads());
  std::vector<std::size_t> first_gap{0};
  for (std::size_t begin = 0; begin < ps.size(); begin += kChunk) {
    std::size_t chosen = 0;
    for (std::size_t i = begin; i < std::min(ps.size(), begin + kChunk); ++i) chosen += selected(i);
    first_gap.push_back(first_gap.back() + chosen);
  }
  const std::size_t tip_count = first_gap.back();
  out << "#declare DLA_TipCount = ";
  out.integer(static_cast<long long>(tip_count)) << ";\n";
  if (tip_count > 0) {
    // POV-Ray warns about a union of one object.
    out << "#declare DLA_Tips = " << (tip_count > 1 ? "union" : "object") << " {\n";
    write_in_order(out, ps.size(), kChunk, detail::format_threads(), [&](detail::Text& text, std::size_t begin, std::size_t end) {
      std::size_t k = first_gap[begin / kChunk];
      for (std::size_t i = begin; i < end; ++i) {
        if (!selected(i)) continue;
        const Instance tip = instance_at(cluster, a, i, gaps[k++]);
        text << "  DLA_Tip(";
        vector(text, tip.position, frame);
        text << ", <";
        text.fixed(tip.direction.x(), 5) << ", ";
        text.fixed(tip.direction.y(), 5) << ", ";
        text.fixed(tip.direction.z(), 5) << ">, ";
        text.float_number(static_cast<float>(tip.scale * frame.scale)) << ")\n";
      }
    });
    out << "}\n";
  }
  out.commit();
}

}  // namespace

void validate_pov_prefix(const std::string& prefix) {
  const std::string name = file_name(prefix);
  for (const char c : name)
    if (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw InvalidInput("the file name '" + comment_text(name) +
                         "' has a quote, a backslash or a control character, which POV-Ray's #include cannot name");
}

void write_pov(const Cluster& cluster, const std::string& prefix, const PovOptions& options,
               const TriangleMesh* mesh, const Look* given_look) {
  validate_pov_prefix(prefix);
  const Look look = given_look ? Look{}
                               : make_look(cluster, {}, {nullptr, nullptr, 1, options.tips && picks_every_tip(options.instances)});
  const Look& used = given_look ? *given_look : look;
  const RadiusOptions& radius = used.options.radius;
  const std::string include = prefix + ".inc";
  const auto [center, extent] = bounding_sphere(cluster, mesh);
  const SceneFrame frame = scene_frame(cluster.spacing, center);
  const std::string growth = prefix + "_growth.inc", mesh_include = prefix + "_mesh.inc";
  const std::string tips = prefix + "_tips.inc";
  {
    // The includes, each on a thread of its own: a file that replaces another waits on the
    // disk when it is put in place. Every one is finished before the first failure is thrown.
    std::vector<std::future<void>> parts;
    parts.push_back(std::async(std::launch::async, [&] { write_geometry(cluster, frame, used, options, include); }));
    parts.push_back(std::async(std::launch::async, [&] { write_growth(cluster, frame, used, options, growth); }));
    if (mesh) parts.push_back(std::async(std::launch::async, [&] { write_mesh(*mesh, frame, mesh_include); }));
    if (options.tips)
      parts.push_back(std::async(std::launch::async, [&] { write_tips(cluster, frame, used, options.instances, tips); }));
    detail::finish_all(parts);
  }

  const double unit = cluster.spacing * frame.scale;  // a spacing in scene units
  const ColorBy by = painted_by(used, options);
  const bool colored = by != ColorBy::none, glow = options.style == PovStyle::glow;
  detail::OutputFile out(prefix + ".pov");
  if (!options.comment.empty()) out << "// " << comment_text(options.comment) << '\n';
  out << "// dla3d " << version << " scene: ";
  out.integer(static_cast<long long>(cluster.particles.size()))
      << " particles. Render with: povray +W1280 +H960 +A " << comment_text(file_name(prefix)) << ".pov\n";
  out << "#version 3.7;\n"
         "global_settings { assumed_gamma 1.0 }\n\n"
         "// Growth: the structure as it was when this fraction of its particles had attached. An\n"
         "// animation follows the clock from 0 to 1: povray +KFF60 renders 60 frames of growth.\n"
         "#ifndef (DLA_Show) #declare DLA_Show = (clock_on ? clock : 1); #end\n\n";
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
         "#declare DLA_RadiusModel = \"" << to_string(radius.model)
      << "\";  // taper, pipe, boundary, seed-distance" << (own_radii(used) ? ", uniform or particle" : " or uniform")
      << " (docs/look.md)\n"
         "#declare DLA_BaseRadius = ";
  out.number(radius.base_radius * unit, 7) << ";  // the thickest branch\n#declare DLA_TipRadius = ";
  out.number(radius.tip_radius * unit, 7) << ";  // the finest branch\n#declare DLA_PipeExponent = ";
  out.number(radius.pipe_exponent, 7) << ";  // pipe: 2 keeps the area, about 3 is Murray's law\n";
  if (glow)
    out << "// Glow: the branches give light and take none, DLA_GlowColor * DLA_Glow at their brightest.\n"
           "#declare DLA_GlowColor = rgb <0.70, 0.80, 1.00>;\n"
           "#declare DLA_Glow = 1.6;  // the brightest branch's emission\n"
           "#declare DLA_GlowFloor = 0.12;  // the faintest branch's share of it\n"
           "#declare DLA_Finish = finish { ambient 0 diffuse 0 emission DLA_Glow }\n"
           "#declare DLA_Texture = texture {\n"
           "  pigment { color DLA_GlowColor }\n"
           "  finish { DLA_Finish }\n"
           "}\n"
           "#declare DLA_Background = rgb 0;\n";
  else
    out << "#declare DLA_Finish = finish { ambient 0.06 diffuse 0.8 specular 0.4 roughness 0.015 }\n"
           "#declare DLA_Texture = texture {\n"
           "  pigment { color rgb <0.90, 0.80, 0.62> }\n"
           "  finish { DLA_Finish }\n"
           "}\n"
           "#declare DLA_Background = rgb <0.04, 0.05, 0.07>;\n";
  out << "#declare DLA_ShowTips = off;  // on: show DLA_Tip at every "
      << (options.instances.set == InstanceSet::tips ? "tip" : "particle") << " (a small sphere, or your leaf)"
      << (options.tips ? "" : "; needs tips in dla3d's --formats") << "\n"
         "#declare DLA_TipTexture = DLA_Texture;\n";
  if (options.style == PovStyle::blob)
    out << "#declare DLA_BlobThreshold = 0.5;  // metaballs: lower merges more\n"
           "#declare DLA_BlobRadius = function(R) { 2 * R + ";
  if (options.style == PovStyle::blob) out.number(0.5 * unit, 7) << " }  // a sphere's reach from its branch radius\n";
  if (mesh)
    out << "#declare DLA_ShowMesh = on;  // the constraint mesh, as glass\n"
           "#declare DLA_MeshTexture = texture {\n"
           "  pigment { color rgbt <0.80, 0.90, 1.0, 0.92> }\n"
           "  finish { ambient 0.04 diffuse 0.12 specular 0.6 roughness 0.004 reflection 0.03 }\n"
           "}\n";
  if (colored && glow) {
    out << "// Brightness by " << to_string(by) << ": the value in [0, 1] scales the glow.\n"
           "#macro DLA_Paint(V)\n"
           "  pigment { color DLA_GlowColor * (DLA_GlowFloor + (1 - DLA_GlowFloor) * min(max(V, 0), 1)) }\n"
           "  finish { DLA_Finish }\n"
           "#end\n";
  } else if (colored) {
    out << "// Colour by " << to_string(by) << ": the value in [0, 1] through this map (viridis).\n"
           "#declare DLA_Colors = array[" << std::to_string(kColorStops.size()) << "] {\n";
    for (std::size_t k = 0; k < kColorStops.size(); ++k) {
      out << "  <";
      out.fixed(kColorStops[k][0], 4) << ", ";
      out.fixed(kColorStops[k][1], 4) << ", ";
      out.fixed(kColorStops[k][2], 4) << '>' << (k + 1 < kColorStops.size() ? ",\n" : "\n");
    }
    out << "}\n"
           "#macro DLA_Paint(V)\n"
           "  #local X = min(max(V, 0), 1) * (dimension_size(DLA_Colors, 1) - 1);\n"
           "  #local K = min(floor(X), dimension_size(DLA_Colors, 1) - 2);\n"
           "  pigment { color rgb DLA_Colors[K] + (DLA_Colors[K + 1] - DLA_Colors[K]) * (X - K) }\n"
           "  finish { DLA_Finish }\n"
           "#end\n";
  }
  // With each particle's own radius (own_radii), DLA_R takes it as M, and the particle model is M.
  const bool own = own_radii(used);
  const std::string args = own ? "(F, P, B, S, M)" : "(F, P, B, S)";
  out << "\n// Radius of a branch point: F its place along its strand (1 at the start), P the particles\n"
         "// in its subtree, B and S its distances to the mesh and to the seeds (1: the largest)"
      << (own ? ", M its own radius" : "") << ".\n"
         "#if (strcmp(DLA_RadiusModel, \"taper\") = 0)\n"
         "  #declare DLA_R = function" << args << " { DLA_TipRadius + (DLA_BaseRadius - DLA_TipRadius) * F }\n"
         "#elseif (strcmp(DLA_RadiusModel, \"pipe\") = 0)\n"
         "  #declare DLA_R = function" << args << " { min(DLA_TipRadius * pow(P, 1 / DLA_PipeExponent), "
         "max(DLA_BaseRadius, DLA_TipRadius)) }\n"
         "#elseif (strcmp(DLA_RadiusModel, \"boundary\") = 0)\n"
         "  #declare DLA_R = function" << args << " { DLA_TipRadius + (DLA_BaseRadius - DLA_TipRadius) * B }\n"
         "#elseif (strcmp(DLA_RadiusModel, \"seed-distance\") = 0)\n"
         "  #declare DLA_R = function" << args << " { DLA_TipRadius + (DLA_BaseRadius - DLA_TipRadius) * (1 - S) }\n"
         "#elseif (strcmp(DLA_RadiusModel, \"uniform\") = 0)\n"
         "  #declare DLA_R = function" << args << " { DLA_BaseRadius }\n";
  if (own)
    out << "#elseif (strcmp(DLA_RadiusModel, \"particle\") = 0)\n"
           "  #declare DLA_R = function" << args << " { M }\n";
  out << "#else\n"
         "  #error \"DLA_RadiusModel is not taper, pipe, boundary, seed-distance" << (own ? ", uniform or particle" : " or uniform") << "\"\n"
         "#end\n"
         "// Called at every tip: Position, Direction (unit, from the parent) and Scale (the largest radius\n"
         "// at which copies do not overlap). Replace it with a leaf or a flower scaled by Scale.\n"
         "#macro DLA_Tip(Position, Direction, Scale)\n"
         "  sphere { Position, min(Scale, 1.5 * DLA_TipRadius) }\n"
         "#end\n\n"
         "// Framing: a sphere around the structure (and mesh), seen from DLA_View.\n"
         "#declare DLA_Center = ";
  vector(out, center, frame);
  out << ";\n#declare DLA_Radius = ";
  // Seen from the front, a little from the side and above, whichever axis is up.
  const char* view = cluster.dimensions == 2     ? "<0, 0, -1>"
                     : options.up == Axis::z ? "<0.35, 1, 0.45>"
                     : options.up == Axis::x ? "<0.45, 0.35, -1>"
                                             : "<0.35, 0.45, -1>";
  const double thickest = own ? *std::max_element(cluster.radii.begin(), cluster.radii.end()) * frame.scale
                              : std::max(radius.base_radius, radius.tip_radius) * unit;
  const double reach = options.style == PovStyle::blob ? 2.0 * thickest + 0.5 * unit : thickest;
  out.number(extent * frame.scale + reach, 7) << ";\n#declare DLA_View = " << view
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
         "#if (DLA_Show < 1)\n"
         "  #include \"" << file_name(growth) << "\"  // the structure (and tips) at DLA_Show\n"
         "#else\n"
         "  #include \"" << file_name(include) << "\"\n";
  // POV-Ray skips what #if leaves out: the tips are read only when shown.
  if (options.tips)
    out << "  #if (DLA_ShowTips) #include \"" << file_name(tips) << "\" #end\n";
  else
    out << "  #if (DLA_ShowTips) #error \"DLA_ShowTips needs " << file_name(tips)
        << ": grow again with tips in dla3d's --formats\" #end\n";
  out << "#end\n"
         "object { DLA_Structure texture { DLA_Texture } }\n"
         "#if (DLA_ShowTips) #if (DLA_TipCount > 0) object { DLA_Tips texture { DLA_TipTexture } } #end #end\n";
  if (mesh)
    out << "#if (DLA_ShowMesh)\n  #include \"" << file_name(mesh_include) << "\"\n"
        << "  object { DLA_Mesh texture { DLA_MeshTexture } no_shadow }\n#end\n";
  out.commit();
}

}  // namespace dla
