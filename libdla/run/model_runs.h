#pragma once
// What the model runs share (one file each: dla_run.cpp, colonize_run.cpp, eden_run.cpp,
// drop_run.cpp, ballistic_run.cpp, breakdown_run.cpp, aggregate_run.cpp) and the function each registers in run.cpp's table.

#include "dla/run/run.h"

#include "dla/core/errors.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dla::detail {

std::unique_ptr<Run> prepare_dla(const DlaRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_colonize(const ColonizeRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_eden(const EdenRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_drop(const DropRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_ballistic(const BallisticRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_breakdown(const BreakdownRunOptions& options, const MeshReader& read, const Resumed& resumed);
std::unique_ptr<Run> prepare_aggregate(const AggregateRunOptions& options, const MeshReader& read, const Resumed& resumed);

//! "NAME: 1,234 triangles; REPAIRS; spacing S": what a run says of its constraint mesh.
std::string mesh_line(const std::string& name, const MeshConstraint& constraint, double spacing);

//! The files' defaults without a mesh, or with one whose box is `mesh_box`; with `mesh_look`,
//! the look of a root system (DLA in a mesh); `mesh_up` an up axis the mesh gives otherwise.
OutputOptions resolve(OutputOptions files, const Box* mesh_box, bool mesh_look, std::optional<Axis> mesh_up = {});

std::vector<TriangleMesh> read_all(const MeshReader& read, const std::vector<std::string>& paths);

//! A mesh with the meshes that enter it, for a scene that shows where growth starts.
TriangleMesh with_entering(TriangleMesh mesh, const std::vector<TriangleMesh>& entering);

//! Seeds or roots placed on a mesh need one, and one way of placing them; `placed_by` is the
//! model's option that places them without a mesh.
void validate_mesh_seeds(const MeshSeeds& seeds, bool mesh, const char* placed_by);

//! Links between neighbours (links.h); lattice links are Eden's alone.
void validate_links(const LinkOptions& links);

//! The links of a structure grown in a constraint mesh: none that leaves its growing side.
std::vector<Link> links_inside(const Cluster& cluster, const LinkOptions& links, int threads,
                               const MeshConstraint* constraint, const StageWatch& watch);

//! What `make` makes, with `name` (the mesh's) before what it refuses.
template <class Make>
auto named(const std::string& name, Make&& make) {
  try {
    return make();
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
}

//! Reads a mesh and makes what needs it, naming the file in what it refuses.
template <class Make>
auto with_mesh(const MeshReader& read, const std::string& path, Make&& make) {
  return named(path, [&] { return make(read(path, nullptr)); });
}

//! Refuses, before growth, a run whose links or tubes would pass this machine's memory, its
//! disk or a glb's 4.29 GB, in one line naming what fits (forecast.cpp); says in
//! `run.forecast_line` when the links will take long.
void refuse_or_foretell(Run& run);

//! Pairs of points looked at (links' neighbours, closed venation's node-source pairs) a second,
//! on a few cores: what a forecast of their time assumes.
inline constexpr double kPairsPerSecond = 1e8;

//! "up to 20 minutes": how long looking at `pairs` may take.
std::string time_for_pairs(double pairs);

// The rows several models' tables share, each written once.

//! `particles` (`-n`), in [0, 2e9].
template <class Options>
DescribedOption<Options> particles_option(std::size_t Options::*member, std::string_view group,
                                          std::string_view help = "particles to attach, seeds not counted") {
  return with_short_name(integer("particles", member, closed(0, 2e9), "", group, help), "n");
}

//! `dimensions`: 3, or 2 for the plane z = 0.
template <class Options>
DescribedOption<Options> dimensions_option(int Options::*member, std::string_view group,
                                           std::string_view help = "3, or 2 for growth in the plane z = 0") {
  return integer("dimensions", member, closed(2, 3), "", group, help);
}

//! `spacing`, in [kMinSpacing, kMaxSpacing] scene units.
template <class Options>
DescribedOption<Options> spacing_option(double Options::*member, std::string_view group, std::string_view help) {
  return real("spacing", member, closed(kMinSpacing, kMaxSpacing), "", group, help);
}

//! `stl` (alias `mesh`): the constraint mesh's file.
template <class Options>
DescribedOption<Options> stl_option(std::string Options::*member) {
  return with_alias(
      file("stl", member, kMeshFileForm, "Mesh constraint", "grow constrained by this mesh: STL, OFF, OBJ or PLY"),
      "mesh");
}

//! `scene_mesh` (off: `no_scene_mesh`): the POV-Ray scene shows the constraint mesh.
template <class Options>
DescribedOption<Options> scene_mesh_option(bool Options::*member) {
  return flag("scene_mesh", member, "Mesh constraint", "show the mesh, as glass, in the POV-Ray scene", "no_scene_mesh");
}

//! `seed_at`: the seeds' points, one a value.
template <class Options, class Member>
DescribedOption<Options> seed_at_option(Member Options::*member, std::string_view group) {
  return point_list("seed_at", member, group, "a seed at x,y,z (repeat for several); default: one at the origin");
}

}  // namespace dla::detail
