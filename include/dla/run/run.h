#pragma once
//! \file run.h
//! A run of any growth model, as the CLI, the Python module and C++ users make it: its meshes
//! read, the defaults they give taken, its seeds, roots or attractors placed and every option
//! checked (prepare_run); then grown, recorded and written. See docs/dev/architecture.md.
//!
//! \code
//! dla::DlaRunOptions options;
//! options.stl = "bust.stl";
//! options.seeds.count = 2;                    // dla3d --stl bust.stl --seeds 2
//! const auto run = dla::prepare_run(options);
//! dla::RunRecord record;
//! const dla::Cluster tree = dla::grow_recorded(*run, {}, nullptr, record);
//! dla::write_run(*run, tree, record);         // dla.pov .inc .csv .ply .json
//! \endcode

#include "dla/core/cluster.h"
#include "dla/core/option_description.h"
#include "dla/io/leaf.h"
#include "dla/io/run_report.h"
#include "dla/mesh/constraint.h"
#include "dla/run/models.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

namespace dla {

class ParticleFeed;
struct MeasuredClosest;

//! Reads the mesh a path names, with the hash of its file when `hash` is not null. The default
//! is read_mesh(); the Python module hands over meshes held in memory under a name.
using MeshReader = std::function<TriangleMesh(const std::string& path, std::uint64_t* hash)>;

//! A run set up and ready to grow, of any model.
class Run {
 public:
  virtual ~Run() = default;

  //! Grows the structure (once: a run's seeds and statistics are its own). Throws
  //! PartialGrowth, with what grew, when growth fails part way; the statistics then count
  //! what grew.
  virtual Cluster grow(const ProgressFn& progress, const StopFlag* stop) = 0;
  //! The first line of a summary of the structure grown: counts, time, size.
  virtual std::string summary(const Cluster& cluster, const RunRecord& record) const = 0;
  //! How much of `total` a structure growing has: its particles (DLA: without the seeds).
  virtual std::size_t done(const Cluster& so_far) const { return so_far.particles.size(); }
  //! How full the mesh is, for a DLA run growing to fill one, as it grows; else 0.
  virtual double filled() const { return 0.0; }
  //! The walks that grew the structure so far, which a checkpoint keeps (DLA); else null.
  virtual const WalkStats* walks() const { return nullptr; }
  //! The links beside the tree that `links` asks for, made once growth ends (links.h); throws
  //! Interrupted once `watch.stop` is set.
  virtual std::vector<Link> make_links(const Cluster& cluster, const StageWatch& watch) const {
    return neighbour_links(cluster, links, threads, {}, kLoopSteps, watch);
  }
  //! The model's part of the JSON record of the run: `options`, by its model's table, and
  //! own_record().
  ModelRecord record() const;
  //! The model's own part of the record: what its options resolved to that they cannot say
  //! (the seeds a mesh placed), its statistics as growth left them, its measures and timings.
  virtual ModelRecord own_record() const = 0;
  //! Puts in `options`, the ones this run was prepared from, what it resolved of those they
  //! left to the inputs: the spacing a mesh gives, the default influence. prepare_run() makes
  //! `options` so.
  virtual void put_resolved(RunOptions& options) const { (void)options; }
  //! From the next grow() on, hands each particle to `feed` as it attaches (null: to none), if
  //! the model can; returns whether it will. DLA can.
  virtual bool feed_to(ParticleFeed* feed) {
    (void)feed;
    return false;
  }

  std::string_view model;          //!< its name in the registry (models()): grow, colonize, ...
  //! The options it grows from, with what the inputs resolved in place (put_resolved()): the
  //! record's "options", which grow the same structure again.
  RunOptions options;
  //! The files, with the defaults the mesh gives resolved (the up axis, the radii).
  OutputOptions files;
  std::size_t total = 0;           //!< particles at most, for a progress bar
  const char* unit = "particles";  //!< what they are called in a summary
  int threads = 1;                 //!< for the look's measurements, the links and the writers
  LinkOptions links;               //!< links beside the tree (links.h); none: a tree
  //! "NAME: 1,234 triangles; REPAIRS; spacing S", for a run with a constraint mesh, else empty.
  std::string mesh_line;
  //! What a long stage after growth may take, said before growth; empty when none is long.
  std::string forecast_line;
  //! The mesh the look measures distances to (the boundary radius model), or null.
  const MeshConstraint* constraint = nullptr;
  //! The closest triangles of the constraint's surface to the first particles grown, measured
  //! by grow_recorded on a spare core as they attached; write_run takes them rather than
  //! measuring again. Null: none.
  std::shared_ptr<const MeasuredClosest> measured_while_growing;
  //! The mesh the POV-Ray scene and the web viewer show, or null.
  const TriangleMesh* scene_mesh = nullptr;
  //! The leaf file of `files.leaf`, read and checked once before any mesh, or null.
  std::shared_ptr<const Leaf> leaf;
  //! DLA growing to fill a mesh: the fraction of its volume asked for, else 0.
  double fill = 0.0;
  //! What the model promises of the structure before growing it, for a solid that cannot fit
  //! to be refused before growth (solid.h); the radii are the look's, set by prepare_run.
  SolidForecast solid_forecast;
  //! Whether the model gives each particle its own radius (Cluster::radii), which the `particle`
  //! radius model draws: an aggregate's monomers.
  bool sizes_particles = false;
  //! The hash of the mesh's file (or text), which a checkpoint keeps to know it again.
  std::uint64_t input_hash = 0;
};

//! A checkpointed structure a DLA run goes on from, with the hash of the mesh it grew in.
struct Resumed {
  const Cluster* cluster = nullptr;
  const WalkStats* stats = nullptr;  //!< the walks that grew it; null: none counted
  std::uint64_t mesh_hash = 0;
};

//! A growth model, as the registry holds it: what the CLI, the Python module, the studio, the
//! fuzzers and the property test loop over. A model is one file and one registration: the
//! built-in ones are a line each in libdla/run/run.cpp's table, others register_model() their
//! make_model() (docs/dev/architecture.md#adding-a-model).
struct Model {
  std::string_view name;     //!< the CLI's subcommand and Python's function: grow, colonize, ...
  std::string_view summary;  //!< what it grows, in a line, as `dla3d --help` says
  std::type_index options_type;  //!< the type of its run options, by which RunOptions knows it
  //! Its options as no one changed them.
  std::function<RunOptions()> options;
  //! Sets up a run of `options` (of this model): prepare_run() for this model.
  std::function<std::unique_ptr<Run>(const RunOptions& options, const MeshReader& read, const Resumed& resumed)> prepare;
  //! Throws InvalidInput, in one line naming the option, for options that cannot work.
  std::function<void(const RunOptions& options)> validate;
  //! The files its run writes: its options' `files`.
  OutputOptions& (*files)(RunOptions& options);
  //! Its own options, described (option_description.h), from which it gets its command, its
  //! Python keywords and its record (the files' and the look's are output_option_table()'s).
  OptionTable<RunOptions> option_table;
  //! Options of other models that front ends offer it only to refuse, each with why
  //! (refuse_for()): `fill` for all but DLA.
  std::vector<std::string_view> refuses = {};
  //! Whether its runs go on from a checkpoint (`Resumed`): DLA's.
  bool resumes = false;
};

//! The model `name` that grows from run options of type `Options` with a `files` member (of
//! type OutputOptions), checked by `validate(const Options&)`, found where `Options` is declared,
//! and set up by `prepare`. `table` describes its own options (not the files'), which the CLI
//! and Python give it; it refuses those of other models named in `refuses`.
template <class Options>
Model make_model(std::string_view name, std::string_view summary,
                 std::unique_ptr<Run> (*prepare)(const Options&, const MeshReader&, const Resumed&),
                 const OptionTable<Options>& table, std::vector<std::string_view> refuses = {}) {
  Model model{name,
              summary,
              typeid(Options),
              [] { return RunOptions(Options{}); },
              [prepare](const RunOptions& o, const MeshReader& read, const Resumed& resumed) {
                return prepare(o.get<Options>(), read, resumed);
              },
              [](const RunOptions& o) { validate(o.get<Options>()); },
              [](RunOptions& o) -> OutputOptions& { return o.get<Options>().files; },
              {},
              std::move(refuses),
              false};
  for (const DescribedOption<Options>& row : table)
    model.option_table.push_back({row.about,
                                  [set = row.set](RunOptions& o, const OptionValue& v) { set(o.get<Options>(), v); },
                                  [get = row.get](const RunOptions& o) { return get(o.get<Options>()); }});
  return model;
}

//! Adds `model` to the registry, after the built-in ones: from then on the CLI parser, the
//! Python module and `dla3d options` offer it. Register before any of them reads the
//! registry (at static initialisation, as a test does). Throws std::logic_error for a name or an
//! options type already registered.
void register_model(Model model);

//! Every model: grow (DLA), colonize, eden, drop, ballistic, breakdown, then the ones
//! registered, in the order they were. References stay valid when one is registered.
const std::deque<Model>& models();
//! The model `options` are of.
const Model& model_of(const RunOptions& options);
//! The model called `name`, or null.
const Model* find_model(std::string_view name);

//! Writes `value`, option `about`'s, as a field of the JSON record: a vector or points as
//! arrays of numbers, a list of files as an array of text, unset as null.
void write_option(RecordWriter& out, const OptionDescription& about, const OptionValue& value);

//! Writes each described option's value in `options` as a field of the JSON record: the
//! record's "options". An option that changes only how fast a run goes (threads) belongs in
//! the record's timings, so that the same options give the same record.
template <class Options>
void write_described(RecordWriter& out, const OptionTable<Options>& table, const Options& options) {
  for (const DescribedOption<Options>& row : table)
    if (!row.about.speed_only) write_option(out, row.about, row.get(options));
}

//! Sets up the run `options` ask for: validates them, reads the meshes with `read` (default
//! read_mesh), takes their defaults and places seeds, roots or attractors. `resumed` is the
//! checkpointed structure a DLA run goes on from. Throws InvalidInput, with one line, for
//! options that cannot work with the meshes or this machine, and IOError for a file that
//! cannot be read.
std::unique_ptr<Run> prepare_run(const RunOptions& options, const MeshReader& read = {}, const Resumed& resumed = {});

//! Grows `run` under `progress` and `stop`, then makes the links its options ask for, heard by
//! `links_progress`. Keeps what grew when growth fails part way (with the links among what
//! grew), and records the time taken and, when growth failed part way, "error: " and why in
//! `record.stopped_by`. A stop ends the stage it comes in: growth stopped short (`stop`, or
//! `progress` returning false) makes no links; links stopped leave none. Either way the
//! structure comes back incomplete, with the stage in `record.stopped_in`; what stopped it (a
//! signal, a callback) only the caller knows, and records. With a constraint mesh and a core
//! that growth leaves free, it measures there the particles' closest points of the mesh as
//! they attach (Run::measured_while_growing), which the write then need not: the files are
//! the same.
Cluster grow_recorded(Run& run, const ProgressFn& progress, const StopFlag* stop, RunRecord& record,
                      const StageProgress& links_progress = {});

//! Writes the files `files` asks for, the JSON record among them, of what `run` grew, each
//! writer on a thread of its own (the same bytes as one by one), and records the time taken in
//! `record`, with the solid's measures when a solid format is asked for. The POV-Ray scene's
//! first line is `record.command`. The record is written even when another file fails, and
//! then the failure is thrown: InvalidInput for a solid beyond the memory it may take,
//! Interrupted when `stop` stopped the writing (write_files keeps the files finished).
//! `solid_progress` hears how the solid's build goes.
void write_run(const Run& run, const Cluster& cluster, const OutputOptions& files, RunRecord& record,
               const StopFlag* stop = nullptr, const StageProgress& solid_progress = {});
inline void write_run(const Run& run, const Cluster& cluster, RunRecord& record, const StopFlag* stop = nullptr,
                      const StageProgress& solid_progress = {}) {
  write_run(run, cluster, run.files, record, stop, solid_progress);
}

//! With a mesh: a spacing of about a hundredth of its box's longest side, rounded to two digits.
double default_spacing(const Box& box);
//! With a mesh: the axis of its box's longest side, y on a tie, so that standing figures and
//! vessels come out upright.
Axis longest_axis(const Box& box);

namespace detail {
//! A non-negative amount rounded to a whole number, thousands grouped: "64,687".
std::string with_commas(double value);
}  // namespace detail

}  // namespace dla
