#pragma once
// dla3d's command line, parsed and checked without touching a file: main.cpp runs what it says,
// and the CLI fuzzer (tests/fuzz/cli_fuzz.cpp) drives it with arbitrary words.

#include "dla/models/ballistic.h"
#include "dla/models/colonization.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/mesh/constraint.h"
#include "dla/mesh/text.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/core/options.h"
#include "dla/io/ply_writer.h"
#include "dla/io/png_writer.h"
#include "dla/io/pov_writer.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace dla::cli {

//! Defaults with a mesh (--stl) that differ from those without one.
inline constexpr std::size_t kMeshParticles = 30000;
//! With --fill: the particles at most, unless -n says otherwise (growth stops when filled).
inline constexpr std::size_t kFillParticles = 10'000'000;
inline constexpr double kMeshBaseRadius = 3.0, kMeshTipRadius = 0.05;

//! The files a run writes (`--formats`), each as PREFIX.EXT (tips: PREFIX_tips.ply).
struct Formats {
  bool pov = true, csv = true, ply = true, json = true;
  bool glb = false, obj = false, tips = false, svg = false, png = false, html = false;
};

//! What every growth model's files are and look like: the Output and Look options.
struct FileOptions {
  PovOptions pov;
  LookOptions look;
  InstanceOptions instances;
  Formats formats;
  std::string output = "dla";          //!< prefix of the files written
  bool quiet = false;
  PlyEncoding ply_encoding = PlyEncoding::binary;  //!< --ply-format
  PngOptions png;                      //!< --png-scale, --png-bands
};

//! `dla3d [options]`: grow a structure by DLA and write its files.
struct GrowCommand : FileOptions {
  GrowthOptions options;
  std::string mesh_path;               //!< --stl; empty: none
  std::optional<TextOptions> text;     //!< --text: the constraint is this text, extruded
  ConstraintOptions constraint;
  std::size_t seed_count = 0;          //!< --seeds K; 0 when not given or `all`
  bool seed_surface = false;           //!< --seed-surface: the mesh's surface, sampled, is the start
  std::optional<Paint> seed_paint;     //!< --seed-paint: seeds on the painted part only
  std::vector<std::string> seed_mesh_paths;  //!< --seed-mesh: seeds where these meshes meet the mesh
  bool scene_mesh = true;
  std::string checkpoint_path;         //!< empty: no checkpoint
  double checkpoint_every = 60.0;      //!< seconds
  // Options whose default comes from the mesh when they are not given.
  bool spacing_given = false, up_given = false, spawn_given = false, seeds_given = false;
  bool particles_given = false, radius_given = false, base_radius_given = false, tip_radius_given = false;

  bool has_mesh() const { return !mesh_path.empty() || text; }
};

//! `dla3d colonize [options]`: grow a tree by space colonization and write its files.
//! Where `dla3d colonize --roots K` puts its roots (`--roots-in`).
enum class RootRegion {
  sphere,   //!< at random on the sphere around the attractors
  mesh,     //!< inside the mesh, deep and far apart
  surface,  //!< on the mesh's surface, half a spacing inside
};

std::string_view to_string(RootRegion region);
RootRegion parse_root_region(std::string_view word);

struct ColonizeCommand : FileOptions {
  ColonizationOptions options;
  AttractorOptions attractors;
  //! --attractors-from: the attractors from a file, instead of scattered; with
  //! `sample_attractors`, a seeded sample of attractors.count of them.
  std::string attractors_path;
  bool sample_attractors = false;
  std::vector<Vec3> roots;             //!< --root-at; none: see root_count
  //! --roots K: K roots in `roots_in`; with neither, one root at the attractors' lowest
  //! point (-y).
  std::size_t root_count = 0;
  RootRegion roots_in = RootRegion::sphere;
  //! --roots-scale: the sphere of `RootRegion::sphere` is this times the attractors', in
  //! [0.01, 100] (the write-up's third test scatters roots on a larger one).
  double roots_scale = 1.0;
  std::string vessel_path;             //!< --stl: a vessel growth stays inside; empty: none
  std::string collide_path;            //!< --collide: a collision mesh; empty: none
  CollisionMode collision = CollisionMode::push;
};

//! `dla3d eden [options]`: grow an Eden cluster on a lattice and write its files.
struct EdenCommand : FileOptions {
  EdenOptions options;
  std::string mask_path;  //!< --mask FILE: the mask drawn in a file; empty: a preset or none
};

//! `dla3d drop [options]`: grow by random-drop ballistic aggregation and write its files.
struct DropCommand : FileOptions {
  DropOptions options;
  std::string mesh_path;          //!< --stl: a constraint mesh; empty: none
  ConstraintOptions constraint;
  bool scene_mesh = true;
  // Options whose default comes from the mesh when they are not given, as for DLA.
  bool spacing_given = false, seeds_given = false, up_given = false;
};

//! `dla3d ballistic [options]`: grow by ballistic aggregation and write its files.
struct BallisticCommand : FileOptions {
  BallisticOptions options;
};

//! `dla3d frames PREFIX.csv --count K`: the structure a CSV holds as it grew, in K files of
//! each format (PREFIX_0001.glb ...), for tools that cannot reveal growth by its age.
struct FramesCommand : FileOptions {
  std::string csv_path;
  std::size_t count = 30;  //!< frames: frame k of K holds the seeds and k/K of the rest
};

//! What the command line asks for.
struct CommandLine {
  enum class Kind {
    grow,      //!< `grow` holds the options
    colonize,  //!< dla3d colonize: `colonize` holds the options
    eden,      //!< dla3d eden: `eden` holds the options
    drop,      //!< dla3d drop: `drop` holds the options
    ballistic, //!< dla3d ballistic: `ballistic` holds the options
    resume,    //!< --resume FILE, with only -q and --threads beside it
    convert,   //!< dla3d convert IN OUT.stl
    analyze,   //!< dla3d analyze PREFIX.csv
    frames,    //!< dla3d frames PREFIX.csv: `frames` holds the options
    print,     //!< --help or --version: `text` goes to stdout, exit 0
  };
  Kind kind = Kind::grow;
  GrowCommand grow;
  ColonizeCommand colonize;
  EdenCommand eden;
  DropCommand drop;
  BallisticCommand ballistic;
  FramesCommand frames;
  std::string resume_path;
  bool threads_given = false;  //!< with --resume: grow.options.threads replaces the checkpoint's
  std::string convert_in, convert_out;
  std::string analyze_csv;
  std::string text;

  //! The files of the growth run it asks for (grow, colonize, eden, drop, ballistic), else null.
  const FileOptions* growth_files() const {
    switch (kind) {
      case Kind::grow: return &grow;
      case Kind::colonize: return &colonize;
      case Kind::eden: return &eden;
      case Kind::drop: return &drop;
      case Kind::ballistic: return &ballistic;
      default: return nullptr;
    }
  }
};

//! The roots a colonize command grows from: its --root-at points; or --roots K on the sphere
//! around the attractors, or in or on `mesh` (the vessel, else the collision mesh); or one at
//! the attractors' lowest point (-y).
std::vector<Vec3> colonize_roots(const ColonizeCommand& command, const std::vector<Vec3>& attractors,
                                 const MeshConstraint* mesh);

//! Parses dla3d's arguments (without the program name). Throws InvalidInput with a one-line
//! message for a flag or value that cannot work; options that need the mesh to be checked
//! (the spacing's default, seeds) are checked after it is read.
CommandLine parse_command_line(const std::vector<std::string>& args);

}  // namespace dla::cli
