#pragma once
//! \file models.h
//! The options of a run of each growth model: the model's own options, the meshes and files it
//! reads, where it starts, and its files (output.h). They are what `dla3d MODEL [options]` and
//! `dla3d.MODEL(**options)` set, checked by validate() before anything is read, and resolved
//! against the meshes by prepare_run() (run.h). Options a mesh gives a default for are
//! std::optional: unset, the mesh's default holds, or without a mesh the model's own.

#include "dla/mesh/constraint.h"
#include "dla/mesh/paint.h"
#include "dla/mesh/text.h"
#include "dla/models/aggregate.h"
#include "dla/models/ballistic.h"
#include "dla/models/breakdown.h"
#include "dla/models/colonization.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/models/dla.h"
#include "dla/models/links.h"
#include "dla/run/output.h"
#include "dla/core/words.h"

#include <any>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <typeindex>
#include <vector>

namespace dla {

//! Inside a mesh, DLA grows a root system: enough particles to fill a bust at the default
//! spacing, short of the 35,000 or so that cover its skin, where the surface spawn starts them.
inline constexpr std::size_t kMeshParticles = 30000;
//! Growing to fill a mesh: the particles at most, unless `particles` says otherwise.
inline constexpr std::size_t kFillParticles = 10'000'000;
//! Inside a mesh: thick trunks and fine tips, in spacings (docs/look.md).
inline constexpr double kMeshBaseRadius = 3.0, kMeshTipRadius = 0.05;

//! Where seeds go on a mesh, for the models that grow from seeds in or on one.
struct MeshSeeds {
  //! `seeds`: K seeds on the growing side, far apart; 0: one (text: one in each letter), or
  //! with `surface`, `paint` or `meshes`, all of them at the spacing.
  std::size_t count = 0;
  bool surface = false;               //!< `seed_surface`: the whole surface, sampled at the spacing
  std::optional<Paint> paint;         //!< `seed_paint`: the part of the surface painted this colour
  std::vector<std::string> meshes;    //!< `seed_mesh`: where these meshes' surfaces meet the mesh
  //! `seeds` all: at the spacing over what `paint` or `meshes` pick of the surface, or all of it
  bool all = false;

  bool on_surface() const { return surface || all || paint || !meshes.empty(); }
  //! The seeds cover the whole surface, not a part of it.
  bool whole_surface() const { return (surface || all) && !paint && meshes.empty(); }
};
//! Its options, described: `seeds`, `seed_surface`, `seed_paint`, `seed_mesh`; with `roots`, as
//! colonize's roots.
const OptionTable<MeshSeeds>& mesh_seeds_option_table(bool roots = false);

//! `dla3d [options]`, `dla3d.grow()`: DLA, in or around a mesh or text when one is given.
struct DlaRunOptions {
  //! The walk. Its `particles`, `spacing`, `spawn` and `seeds` are the defaults without a
  //! mesh; the optionals below replace them.
  DlaOptions growth;
  std::optional<std::size_t> particles;      //!< default 10,000; with a mesh 30,000; filling 1e7
  std::optional<double> spacing;             //!< with a mesh: its longest side / 100 (text: size / 100)
  std::optional<SpawnMode> spawn;            //!< with a mesh: surface inside, else sphere (docs/dla.md)
  std::optional<std::vector<Vec3>> seed_at;  //!< with a mesh: placed on its growing side
  std::string stl;                           //!< the constraint mesh's file; empty: none
  std::optional<TextOptions> text;           //!< the constraint is this text, extruded
  ConstraintOptions constraint;              //!< side, reject or clip, shell
  MeshSeeds seeds;
  bool scene_mesh = true;                    //!< the POV-Ray scene shows the mesh as glass
  LinkOptions links;                         //!< links between neighbours beside the tree (links.h)
  OutputOptions files;

  bool has_mesh() const { return !stl.empty() || text.has_value(); }
};

//! Its options, described: the walk's (dla_option_table()), the count, the scale and the seeds,
//! the mesh or text and the links. All but `rng_seed`, which the front ends still add.
const OptionTable<DlaRunOptions>& dla_run_option_table();

//! DLA's options with the run's optionals that are set put in place; what a mesh gives for
//! those unset, prepare_run() resolves.
DlaOptions walk_options(const DlaRunOptions& options);

//! Where `dla3d colonize --roots K` puts its roots.
enum class RootRegion {
  sphere,   //!< at random on the sphere around the attractors
  mesh,     //!< inside the mesh, deep and far apart
  surface,  //!< on the mesh's surface, half a spacing inside
};
inline constexpr WordTable<RootRegion, 3> kRootRegionWords{
    "root region",
    {{{RootRegion::sphere, "sphere"}, {RootRegion::mesh, "mesh"}, {RootRegion::surface, "surface"}}}};
constexpr const auto& words_of(RootRegion) { return kRootRegionWords; }

//! `dla3d colonize`, `dla3d.colonize()`: space colonization among attractors.
struct ColonizeRunOptions {
  ColonizationOptions colonization;
  AttractorOptions attractors;
  //! The attractors from a file (CSV rows x,y,z or PLY points) instead of scattered; with
  //! `sample_attractors` (which giving `attractors` sets), a seeded sample of attractors.count
  //! of them.
  std::string attractors_from;
  bool sample_attractors = false;
  std::vector<Vec3> root_at;      //!< roots here; none: see root_count
  //! K roots in `roots_in`; 0, with no `root_at`: one at the attractors' lowest point (-y).
  std::size_t root_count = 0;
  RootRegion roots_in = RootRegion::sphere;
  double roots_scale = 1.0;       //!< the sphere of RootRegion::sphere, times the attractors', [0.01, 100]
  std::string stl;                //!< a vessel growth stays inside; empty: none
  std::string collide;            //!< a collision mesh; empty: none
  CollisionMode collision = CollisionMode::push;
  //! Roots on the mesh (the vessel, else the collision mesh) as DLA's seeds go: K far apart,
  //! the surface, the paint, or where other meshes meet it; instead of `root_at` or `roots`.
  MeshSeeds seeds;
  OutputOptions files;
};

//! Space colonization's run options, described whole but the refusals of `fill` and `shell`:
//! the model's, the attractors', the roots' and the meshes'.
const OptionTable<ColonizeRunOptions>& colonize_option_table();

//! `dla3d eden`, `dla3d.eden()`: an Eden cluster on a lattice.
struct EdenRunOptions {
  EdenOptions eden;       //!< its `lattice` holds unless `lattice` or `dimensions` is set
  std::optional<Lattice> lattice;  //!< in place of eden.lattice
  //! 2 or 3: without `lattice`, its default there (square4, cubic6); with it, its dimensions
  std::optional<int> dimensions;
  std::string mask_file;  //!< the mask drawn in a file; empty: a preset (eden.mask) or none
  LinkOptions links;      //!< links beside the tree: lattice, or between neighbours (links.h)
  OutputOptions files;
};
//! Its options, described whole.
const OptionTable<EdenRunOptions>& eden_run_option_table();
//! The Eden model's options with the run's lattice resolved.
EdenOptions eden_options(const EdenRunOptions& options);

//! `dla3d drop`, `dla3d.drop()`: random-drop ballistic aggregation, in or around a mesh.
struct DropRunOptions {
  DropOptions drop;               //!< its `spacing` and `seeds` are the defaults without a mesh
  std::optional<double> spacing;  //!< with a mesh: its longest side / 100
  std::optional<std::vector<Vec3>> seed_at;  //!< with a mesh: one on its growing side
  std::string stl;                //!< the constraint mesh's file; empty: none
  ConstraintOptions constraint;   //!< side, reject or clip; no shell: drops fall through space
  MeshSeeds seeds;                //!< with a mesh: where the seeds go; default one on the growing side
  bool scene_mesh = true;
  LinkOptions links;              //!< links between neighbours beside the tree (links.h)
  OutputOptions files;
};
//! Its options, described whole but the refusals of `fill` and `shell`.
const OptionTable<DropRunOptions>& drop_run_option_table();

//! `dla3d ballistic`, `dla3d.ballistic()`: ballistic aggregation along straight lines.
struct BallisticRunOptions {
  BallisticOptions ballistic;
  LinkOptions links;  //!< links between neighbours beside the tree (links.h)
  OutputOptions files;
};
//! Its options, described whole.
const OptionTable<BallisticRunOptions>& ballistic_run_option_table();

//! The files of an aggregate as no one changed them: its monomers drawn at their own radii, as
//! spheres in POV-Ray and in the solid, and the sphere list beside the usual files.
inline OutputOptions aggregate_files() {
  OutputOptions files;
  files.output = "aggregate";
  files.formats.spheres = true;
  files.radius = RadiusModel::particle;
  files.pov.style = PovStyle::spheres;
  files.solid.shape = SolidShape::spheres;
  return files;
}

//! `dla3d aggregate`, `dla3d.aggregate()`: cluster-cluster aggregation (aggregate.h), described
//! whole: its command line and Python keywords come from aggregate_option_table().
struct AggregateRunOptions {
  AggregateOptions aggregate;
  OutputOptions files = aggregate_files();
};
//! Its options, described: the aggregate's and the seed.
const OptionTable<AggregateRunOptions>& aggregate_run_option_table();

//! `dla3d breakdown`, `dla3d.breakdown()`: the dielectric breakdown model, grown by DLA's walk
//! with every option of a DLA run (the mesh as an insulator, the seeds as the source, the spawn
//! when there is no target) but `fill`, `drift`, `rotate`, `index` and checkpoints.
struct BreakdownRunOptions : DlaRunOptions {
  BreakdownOptions breakdown;
  //! The target electrode's mesh file (STL, OBJ, PLY, OFF), read and repaired as `stl` is:
  //! `breakdown.target` becomes that mesh. Empty: the target is `breakdown.target`'s.
  std::string target_mesh;
};

//! Its options, described whole: DLA's but those it does not take, the discharge's
//! (breakdown_option_table()) and the target electrode.
const OptionTable<BreakdownRunOptions>& breakdown_run_option_table();

//! The roots a colonize run grows from: its `root_at` points; or `root_count` on the sphere
//! around the attractors, or in or on `mesh` (the vessel, else the collision mesh); or one at
//! the attractors' lowest point (-y).
std::vector<Vec3> colonize_roots(const ColonizeRunOptions& options, const std::vector<Vec3>& attractors,
                                 const MeshConstraint* mesh);

//! Seeds on a mesh as `seeds` asks: K far apart (default 1), or the surface, the paint, or
//! the curves where the `entering` meshes meet it, at the spacing (K of them far apart when K is
//! given). Throws InvalidInput when there is nowhere to put them.
std::vector<Vec3> seeds_on(const MeshConstraint& mesh, const MeshSeeds& seeds, std::uint64_t rng_seed,
                           const std::vector<TriangleMesh>& entering = {});

//! The one-line refusal of a control that means nothing to `model`, and why; for the front ends
//! that offer every model the same controls.
[[noreturn]] void refuse_for(std::string_view model, std::string_view option);

struct Model;
//! The registered model whose run options are of `type` (run.h); throws std::logic_error for a
//! type that no model registered.
const Model& model_for(std::type_index type);

//! A run of any registered model (run.h): that model's run options, and which model it is.
//! Made from any model's options: `dla::RunOptions run = dla::DropRunOptions{};`.
class RunOptions {
 public:
  //! DLA's options as no one changed them: `dla3d` without options.
  RunOptions();
  template <class Options, std::enable_if_t<!std::is_same_v<std::decay_t<Options>, RunOptions>, int> = 0>
  RunOptions(Options options) : model_(&model_for(typeid(Options))), options_(std::move(options)) {}

  const Model& model() const { return *model_; }
  //! The options, if they are of type `Options` (exactly: BreakdownRunOptions are not
  //! DlaRunOptions), else null.
  template <class Options>
  Options* get_if() { return std::any_cast<Options>(&options_); }
  template <class Options>
  const Options* get_if() const { return std::any_cast<Options>(&options_); }
  //! The options, which must be of type `Options`.
  template <class Options>
  Options& get() { return std::any_cast<Options&>(options_); }
  template <class Options>
  const Options& get() const { return std::any_cast<const Options&>(options_); }

 private:
  const Model* model_;
  std::any options_;
};

//! The files a run of any model writes.
const OutputOptions& output_of(const RunOptions& options);

//! Throws InvalidInput, with one line naming the option, for options that cannot work
//! together; what needs the meshes (the spacing's default, seeds in them) is checked when
//! prepare_run() has read them.
void validate(const DlaRunOptions& options);
void validate(const ColonizeRunOptions& options);
void validate(const EdenRunOptions& options);
void validate(const DropRunOptions& options);
void validate(const BallisticRunOptions& options);
void validate(const BreakdownRunOptions& options);
void validate(const AggregateRunOptions& options);
void validate(const RunOptions& options);

}  // namespace dla
