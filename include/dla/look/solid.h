#pragma once
//! \file solid.h
//! The structure as one watertight solid, for 3D printing and VFX: every branch is the tapered
//! capsule between a particle and its parent, with the look's radius at each end (or each site
//! a sphere or a cube), and the solid is their union, built as a narrow-band signed distance
//! field on a sparse grid (OpenVDB, kept inside libdla) and meshed watertight. See
//! docs/solid.md.

#include "dla/core/cluster.h"
#include "dla/core/option_description.h"
#include "dla/core/options.h"
#include "dla/core/stop.h"
#include "dla/core/words.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

namespace dla {

//! What each particle adds to the solid (`--solid-shape`).
enum class SolidShape {
  branches,  //!< the tapered capsule from the particle to its parent (a seed: its sphere)
  spheres,   //!< a sphere of the particle's radius: the metaball look, with `solid_smooth`
  cubes,     //!< a cube one spacing across: lattice sites (Eden) as voxels
};
inline constexpr WordTable<SolidShape, 3> kSolidShapeWords{
    "solid shape",
    {{{SolidShape::branches, "branches"}, {SolidShape::spheres, "spheres"}, {SolidShape::cubes, "cubes"}}}};
constexpr const auto& words_of(SolidShape) { return kSolidShapeWords; }

//! The largest print size, in millimetres: 10 m, beyond any printer.
inline constexpr double kMaxPrintSize = 1e4;

struct SolidOptions {
  SolidShape shape = SolidShape::branches;
  //! The voxel's edge, in spacings, in [1e-3, 100]; 0 derives it: a third of the thinnest
  //! branch's diameter, so that every branch is at least 3 voxels across.
  double voxel = 0.0;
  //! Blend radius, in spacings, in [0, 100]: every inner corner is rounded to it and branches
  //! closer than twice it are webbed together (a morphological closing): the organic, metaball
  //! look. 0 keeps the sharp union.
  double smooth = 0.0;
  //! How much flat parts of the surface are merged into larger triangles, in [0, 1]: 0 keeps
  //! one or two triangles per voxel of surface.
  double adaptivity = 0.0;
  //! Millimetres, in (0, 1e4]: the structure is scaled so its solid's longest side is this, and
  //! the files are in millimetres. 0 keeps the scene's units (and the files call them mm).
  double print_size = 0.0;
  //! Millimetres, in [0, 100]: with `print_size`, every branch thinner than this is thickened
  //! to it (a common nozzle's 0.8 mm). Without `print_size` there is no unit and nothing is
  //! thickened.
  double min_wall = 0.8;
  //! Join the seeds' trees with bars along a minimum spanning tree of the seeds, at the seeds'
  //! radius, so that several seeds give one piece.
  bool join_seeds = false;
  //! Megabytes the build may take, in [1, 1e9], or 0 for half the memory the machine has free.
  double memory = 0.0;
  //! Threads, 1-256, or 0 for every core; the solid does not depend on them.
  int threads = 0;
};

//! The solid's options, described once (option_description.h); its threads are the run's.
inline const OptionTable<SolidOptions>& solid_option_table() {
  using O = SolidOptions;
  static constexpr std::string_view group = "Solid (stl, 3mf, vdb, solid-glb, solid-obj)";
  static const OptionTable<O> table{
      word("solid_shape", &O::shape, group,
           "what each particle adds: branches (tapered capsules to its parent), spheres (with --solid-smooth: "
           "metaballs) or cubes (lattice sites)"),
      real("solid_voxel", &O::voxel, closed(1e-3, 100), "spacings", group, "the voxel's edge",
           SpecialValue{0, "a third of the thinnest branch's diameter"}),
      real("solid_smooth", &O::smooth, closed(0, 100), "spacings", group,
           "round inner corners to this radius and web branches closer than twice it: the organic look"),
      real("solid_adaptivity", &O::adaptivity, closed(0, 1), "", group, "merge flat parts into larger triangles"),
      real("print_size", &O::print_size, closed(1e-3, kMaxPrintSize), "mm", group,
           "scale the solid so its longest side is this", SpecialValue{0, "the scene's units"}),
      real("min_wall", &O::min_wall, closed(0, 100), "mm", group,
           "with --print-size: thicken every branch thinner than this"),
      flag("solid_join", &O::join_seeds, group, "join the seeds' trees by bars, so several seeds print as one piece"),
      real("solid_memory", &O::memory, closed(1, 1e9), "MB", group, "megabytes the solid may take",
           SpecialValue{0, "half the free memory"}),
  };
  return table;
}

//! Throws InvalidInput, naming the option, for a value out of range.
void validate(const SolidOptions& options);

//! The solid's surface: a closed, oriented triangle mesh (triangles wind counter-clockwise seen
//! from outside), in millimetres with `print_size`, else in scene units.
struct SolidMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

//! What the solid measures to, in the mesh's units.
struct SolidMeasures {
  double volume = 0.0;          //!< enclosed by the mesh
  double area = 0.0;            //!< of the mesh
  std::size_t shells = 0;       //!< connected pieces of the mesh
  double thinnest_wall = 0.0;   //!< the smallest branch (or sphere, cube) diameter after thickening
  std::size_t thickened = 0;    //!< particles whose branch was thickened to `min_wall` or the voxel
  double voxel = 0.0;           //!< the voxel's edge
  double scale = 1.0;           //!< mesh units per scene unit: 1 without `print_size`
  std::size_t active_voxels = 0;//!< the narrow band's voxels
  double estimated_bytes = 0.0;  //!< what the plan expected the build to take (SolidPlan)
  double estimated_seconds = 0.0;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  //!< the mesh's bounding box
};

namespace detail {
struct SolidGrid;  // the OpenVDB level set (libdla/look/solid_grid.h)
struct SolidWork;  // the pieces and where they reach (libdla/look/solid.cpp)
struct SolidNearest;  // the particles' k-d tree, built on first use (libdla/look/solid.cpp)
}  // namespace detail

//! A structure's solid: its mesh, its measures, the grid it was meshed from (for the .vdb
//! writer) and what the grid's units are to the structure's.
struct Solid {
  SolidMesh mesh;
  SolidMeasures measures;
  std::shared_ptr<const detail::SolidGrid> grid;
  //! The structure's point p lies at (p - origin) * measures.scale in the mesh.
  Vec3 origin = Vec3::Zero();
  //! The look-up of nearest_particles, shared by the solid's files and built once for all.
  std::shared_ptr<detail::SolidNearest> nearest;
};

//! What building a structure's solid will take, found before any of it is built: the scale,
//! the voxel, the pieces, and the memory the build is estimated to need.
struct SolidPlan {
  double bytes = 0.0;    //!< the build's estimated peak
  double seconds = 0.0;  //!< the build's and its STL's estimated time
  double voxel = 0.0;  //!< the voxel's edge, in the mesh's units
  std::shared_ptr<const detail::SolidWork> work;
};

//! What a run knows of its structure before growing it: enough to bound its solid's memory from
//! below, and so refuse a solid that cannot fit before the growth, not after it.
struct SolidForecast {
  std::size_t particles = 0;  //!< particles it grows (seeds aside); 0: not known before growth
  //! The least distance, in spacings, between the centre of a particle grown and any other
  //! particle's; 0: the model promises none (space colonization, a clipped branch).
  double separation = 0.0;
  double least_radius = 0.0, most_radius = 0.0;  //!< the look's range of radii, in spacings
};

//! The least memory, in bytes, that the solid of any structure `forecast` describes can take:
//! by the Brunn-Minkowski inequality, its narrow band outside the union of the particles'
//! disjoint balls is at least that of a ball of their volume. 0 where the forecast bounds
//! nothing (no count, no separation, a voxel derived from the print size).
double least_solid_bytes(const SolidForecast& forecast, const SolidOptions& options);

//! Throws InvalidInput, before growth, naming a `solid_voxel` below which no structure of the
//! forecast can fit in `solid_memory`, when the one asked for cannot. A solid that may fit is
//! planned, and refused if need be, once grown (plan_solid).
void refuse_solid_before_growth(const SolidForecast& forecast, const SolidOptions& options);

//! Plans the solid of `cluster` with `radii[i]`, particle i's branch radius in spacings (the
//! look's). Throws InvalidInput for bad options, and, naming a voxel that fits, when the build
//! would take more than `solid_memory`: before anything is allocated by the voxel.
SolidPlan plan_solid(const Cluster& cluster, const std::vector<float>& radii, const SolidOptions& options);

//! Builds a planned solid on its options' threads (the same solid on any number). Throws
//! Interrupted when `stop` is set while it builds. `progress` hears the stages "filling the
//! grid", "smoothing", "meshing", "fitting the surface", "built".
Solid build_solid(const SolidPlan& plan, const StopFlag* stop = nullptr, const StageProgress& progress = {});

inline Solid build_solid(const Cluster& cluster, const std::vector<float>& radii, const SolidOptions& options,
                         const StopFlag* stop = nullptr) {
  return build_solid(plan_solid(cluster, radii, options), stop);
}

//! How much each radius is widened for meshing, in the mesh's units: the mean depth of a
//! facet's chord below a surface of that radius (voxel^2 / 14 radius for a branch, voxel^2 /
//! 8 radius for a sphere), so the mesh's volume is the union's. The grid (`surface` in the
//! .vdb) holds the widened union's distance, and the mesh's vertices lie on its zero.
double chord_depth(double voxel, double radius, bool sphere);

//! For each point of the mesh (in its units), the particle of `cluster`, the structure the solid
//! was built from, nearest to it: what the solid's vertex colours and attributes, and its `age`
//! grid, are taken from. The first call builds the look-up, for every later one on any thread.
std::vector<std::int32_t> nearest_particles(const Cluster& cluster, const Solid& solid,
                                            const std::vector<Eigen::Vector3f>& points);

}  // namespace dla
