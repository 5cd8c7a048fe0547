// The registry of models, and what every model's run shares (run.h): prepare_run() hands the
// options to their model's file (dla_run.cpp, ...), grow_recorded() grows any run.

#include "model_runs.h"

#include "dla/core/particle_feed.h"
#include "dla/core/input_file.h"
#include "dla/look/attributes.h"
#include "dla/mesh/mesh.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace dla {

namespace detail {
std::string with_commas(double value) { return format_count(static_cast<std::uint64_t>(value + 0.5)); }
}  // namespace detail

double default_spacing(const Box& box) {
  const double raw = (box.max - box.min).maxCoeff() / 100.0;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)) - 1.0);
  return std::round(raw / unit) * unit;
}

Axis longest_axis(const Box& box) {
  const Vec3 size = box.max - box.min;
  if (size.z() > size.y() && size.z() > size.x()) return Axis::z;
  if (size.x() > size.y()) return Axis::x;
  return Axis::y;
}

namespace detail {

std::string mesh_line(const std::string& name, const MeshConstraint& constraint, double spacing) {
  char line[512];
  std::snprintf(line, sizeof line, "%s: %s triangles; %s; spacing %g", name.c_str(),
                with_commas(static_cast<double>(constraint.repair_report().input_triangles)).c_str(),
                constraint.repair_report().summary().c_str(), spacing);
  return line;
}

OutputOptions resolve(OutputOptions files, const Box* mesh_box, bool mesh_look, std::optional<Axis> mesh_up) {
  if (files.up) files.pov.up = *files.up;
  else if (mesh_up) files.pov.up = *mesh_up;
  else if (mesh_box) files.pov.up = longest_axis(*mesh_box);
  files.look.radius.model = files.radius.value_or(mesh_look ? RadiusModel::pipe : files.look.radius.model);
  files.look.radius.base_radius = files.base_radius.value_or(mesh_look ? kMeshBaseRadius : files.look.radius.base_radius);
  files.look.radius.tip_radius = files.tip_radius.value_or(mesh_look ? kMeshTipRadius : files.look.radius.tip_radius);
  return files;
}

void validate_links(const LinkOptions& links) {
  if (links.lattice) throw InvalidInput("`links` lattice links the sites of an Eden cluster; give D[,K] spacings");
  validate(links);
}

std::vector<Link> links_inside(const Cluster& cluster, const LinkOptions& links, int threads,
                               const MeshConstraint* constraint, const StageWatch& watch) {
  if (!constraint) return neighbour_links(cluster, links, threads, {}, kLoopSteps, watch);
  return neighbour_links(
      cluster, links, threads,
      [constraint](const Vec3& earlier, const Vec3& later) {
        const BranchCheck check = constraint->check_branch(earlier, later);
        return check.accepted && !check.clipped;
      },
      kLoopSteps, watch);
}

std::vector<TriangleMesh> read_all(const MeshReader& read, const std::vector<std::string>& paths) {
  std::vector<TriangleMesh> meshes;
  for (const std::string& path : paths) meshes.push_back(read(path, nullptr));
  return meshes;
}

TriangleMesh with_entering(TriangleMesh mesh, const std::vector<TriangleMesh>& entering) {
  for (const TriangleMesh& other : entering) append(mesh, other);
  return mesh;
}

}  // namespace detail

namespace {

//! `model`, whose runs go on from a checkpoint.
Model resuming(Model model) {
  model.resumes = true;
  return model;
}

//! The models, the built-in ones first: a line each, in the order `dla3d --help` lists them.
std::deque<Model>& registry() {
  // DLA's `fill` and `shell` mean nothing to the others; front ends refuse them with why.
  static std::deque<Model> all = {
      resuming(make_model<DlaRunOptions>(
          "grow", "grow by off-lattice diffusion-limited aggregation, in or around a mesh or text (docs/dla.md)",
          detail::prepare_dla, dla_run_option_table())),
      make_model<ColonizeRunOptions>(
          "colonize", "grow a tree by space colonization: attractor points pull its nearest nodes (docs/colonization.md)",
          detail::prepare_colonize, colonize_option_table(), {"fill", "shell"}),
      make_model<EdenRunOptions>("eden",
                                 "grow an Eden cluster on a lattice: sites join at random on its edge, or where a "
                                 "mask counts enough of it (docs/eden.md)",
                                 detail::prepare_eden, eden_run_option_table()),
      make_model<DropRunOptions>("drop",
                                 "grow by random-drop ballistic aggregation: particles dropped at random join the "
                                 "closest particle (docs/drop.md)",
                                 detail::prepare_drop, drop_run_option_table(), {"fill", "shell"}),
      make_model<BallisticRunOptions>("ballistic",
                                      "grow by ballistic aggregation: particles fly in straight lines and stick where "
                                      "they first touch (docs/ballistic.md)",
                                      detail::prepare_ballistic, ballistic_run_option_table()),
      make_model<BreakdownRunOptions>(
          "breakdown",
          "grow a discharge by the dielectric breakdown model: growth where the field to the power eta is strong, "
          "towards a target electrode, around insulating meshes: lightning, Lichtenberg figures (docs/breakdown.md)",
          detail::prepare_breakdown, breakdown_run_option_table(), {"fill"}),
      make_model<AggregateRunOptions>(
          "aggregate",
          "grow an aggregate of clusters: soot, dust, colloids; clusters diffuse (dlca, rlca) or fly (ballistic) "
          "until they touch, or join on a chosen fractal law (tuned); spheres for light-scattering codes "
          "(docs/aggregate.md)",
          detail::prepare_aggregate, aggregate_run_option_table()),
  };
  return all;
}

}  // namespace

RunOptions::RunOptions() : RunOptions(DlaRunOptions{}) {}

void register_model(Model model) {
  for (const Model& known : registry())
    if (known.name == model.name || known.options_type == model.options_type)
      throw std::logic_error("the model " + std::string(model.name) + " is registered twice, or its options are " +
                             std::string(known.name) + "'s");
  registry().push_back(std::move(model));
}

const std::deque<Model>& models() { return registry(); }

const Model& model_for(std::type_index type) {
  for (const Model& model : registry())
    if (model.options_type == type) return model;
  throw std::logic_error(std::string("no model grows from options of type ") + type.name());
}

const Model& model_of(const RunOptions& options) { return options.model(); }

namespace {

//! "1,2,3" as the JSON array [1, 2, 3]; "" as null; words that are not all numbers as text.
std::string numbers_json(const std::string& words) {
  if (words.empty()) return "null";
  std::string list = "[";
  for (std::size_t start = 0; start <= words.size();) {
    const std::size_t comma = std::min(words.find(',', start), words.size());
    const std::string item = words.substr(start, comma - start);
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size()) return json::string(words);
    list += (start ? ", " : "") + json::number(value);
    start = comma + 1;
  }
  return list + "]";
}

}  // namespace

void write_option(RecordWriter& out, const OptionDescription& about, const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return void(out.flag(about.name, *b));
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return void(out.integer(about.name, *i));
  if (const double* d = std::get_if<double>(&value)) return void(out.number(about.name, *d));
  if (const std::string* words = std::get_if<std::string>(&value)) {
    if (about.kind == OptionKind::vector) return void(out.raw(about.name, numbers_json(*words)));
    if (words->empty() && about.kind != OptionKind::word) return void(out.raw(about.name, "null"));
    return void(out.text(about.name, *words));
  }
  std::string list = "[";
  for (const std::string& item : std::get<std::vector<std::string>>(value))
    list += (list.size() > 1 ? ", " : "") + (about.kind == OptionKind::points ? numbers_json(item) : json::string(item));
  out.raw(about.name, list + "]");
}

const Model* find_model(std::string_view name) {
  for (const Model& model : models())
    if (model.name == name) return &model;
  return nullptr;
}

namespace {

//! Every file `options` name that their run reads, each refused in one line naming its option
//! when it is a folder, a device or a FIFO (which a reader would wait on or read for ever).
void require_input_files(const RunOptions& options) {
  std::vector<std::pair<const std::string*, const char*>> files;
  const auto mesh_seeds = [&](const MeshSeeds& seeds) {
    for (const std::string& path : seeds.meshes) files.emplace_back(&path, "seed_mesh");
  };
  const DlaRunOptions* dla = options.get_if<DlaRunOptions>();
  if (const auto* o = options.get_if<BreakdownRunOptions>()) {
    dla = o;
    files.emplace_back(&o->target_mesh, "target_mesh");
  }
  if (const auto* o = dla) {
    files.emplace_back(&o->stl, "stl");
    if (o->text) files.emplace_back(&o->text->font, "font");
    mesh_seeds(o->seeds);
  } else if (const auto* o = options.get_if<ColonizeRunOptions>()) {
    files.insert(files.end(), {{&o->stl, "stl"}, {&o->collide, "collide"}, {&o->attractors_from, "attractors_from"}});
    mesh_seeds(o->seeds);
  } else if (const auto* o = options.get_if<EdenRunOptions>()) {
    files.emplace_back(&o->mask_file, "mask");
  } else if (const auto* o = options.get_if<DropRunOptions>()) {
    files.emplace_back(&o->stl, "stl");
    mesh_seeds(o->seeds);
  }
  files.emplace_back(&output_of(options).leaf, "leaf");
  for (const auto& [path, option] : files)
    if (!path->empty()) require_regular_file(*path, option);
}

}  // namespace

ModelRecord Run::record() const {
  ModelRecord out = own_record();
  out.options = [this](RecordWriter& w) { write_described(w, options.model().option_table, options); };
  return out;
}

std::unique_ptr<Run> prepare_run(const RunOptions& options, const MeshReader& read, const Resumed& resumed) {
  validate(options);
  require_input_files(options);
  const Model& model = model_of(options);
  if (resumed.cluster && !model.resumes) throw InvalidInput("only DLA runs go on from a checkpoint");
  const MeshReader reader =
      read ? read : [](const std::string& path, std::uint64_t* hash) { return read_mesh(path, hash); };
  // The leaf before the meshes: a bad one is refused before a long set-up.
  const std::string& leaf_path = output_of(options).leaf;
  std::shared_ptr<const Leaf> leaf = leaf_path.empty() ? nullptr : std::make_shared<const Leaf>(read_leaf(leaf_path));
  std::unique_ptr<Run> run = model.prepare(options, reader, resumed);
  run->model = model.name;
  run->options = options;
  run->put_resolved(run->options);
  run->leaf = std::move(leaf);
  const RadiusOptions& radius = run->files.look.radius;
  if (radius.model == RadiusModel::particle && !run->sizes_particles)
    throw InvalidInput("`radius` particle draws each particle's own radius: only `aggregate` sizes them");
  // A model that sizes its particles forecasts their radii itself.
  if ((run->files.formats.solid() || run->files.formats.ddscat) && radius.model != RadiusModel::particle) {
    run->solid_forecast.least_radius = std::min(radius.tip_radius, radius.base_radius);
    run->solid_forecast.most_radius = std::max(radius.tip_radius, radius.base_radius);
  }
  if (run->files.formats.solid()) refuse_solid_before_growth(run->solid_forecast, run->files.solid);
  detail::refuse_or_foretell(*run);
  // Refused before growing, not when the files are written.
  if (run->files.instances.exclude_paint && run->constraint)
    run->constraint->require_paint(*run->files.instances.exclude_paint, "tips_exclude_paint");
  return run;
}

namespace {

//! While a run with a constraint mesh grows on fewer threads than the machine has cores:
//! measures on a spare core the closest triangle of the mesh's surface to each particle as it
//! attaches, for the look's distances (attributes.h), which then need not wait for the write.
//! Growth never waits for it: it measures what it keeps up with, a first part of the particles.
class SurfaceFollower {
 public:
  explicit SurfaceFollower(Run& run) : run_(run) {
    if (!run.constraint || run.threads >= static_cast<int>(std::thread::hardware_concurrency())) return;
    measured_ = std::make_shared<MeasuredClosest>();
    measured_->surface = &run.constraint->surface();
    feed_ = std::make_unique<ParticleFeed>(kRoom);
    if (!run.feed_to(feed_.get())) return;
    try {
      thread_ = std::thread([this] { follow(); });
    } catch (...) {  // no thread to spare after all: the write measures them all
      run.feed_to(nullptr);
    }
  }
  ~SurfaceFollower() { finish(); }
  SurfaceFollower(const SurfaceFollower&) = delete;
  SurfaceFollower& operator=(const SurfaceFollower&) = delete;

  //! Once growth is over: stops measuring and gives what was measured, or null.
  std::shared_ptr<const MeasuredClosest> finish() {
    if (!thread_.joinable()) return nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true, std::memory_order_relaxed);
    }
    woken_.notify_one();
    thread_.join();
    run_.feed_to(nullptr);
    return measured_;
  }

 private:
  //! How long it rests when it has caught up: about a hundred particles' growth in a mesh,
  //! which is what it may leave to the write.
  static constexpr std::chrono::microseconds kRest{1000};
  //! Particles it may fall behind before the feed closes: 1 MB.
  static constexpr std::size_t kRoom = std::size_t{1} << 15;

  void follow() noexcept {
    try {
      measure();
    } catch (...) {  // out of memory: what was measured stands, and the write measures the rest
    }
  }

  void measure() {
    ParticleFeed& feed = *feed_;
    const SurfaceDistance& surface = *measured_->surface;
    std::vector<std::uint32_t>& triangles = measured_->triangles;
    std::uint64_t& hash = measured_->positions_hash;
    for (std::size_t k = 0;;) {
      for (const std::size_t put = feed.put_count(); k < put && !stop_.load(std::memory_order_relaxed); ++k) {
        const Particle& p = feed.at(k);
        const auto parent = static_cast<std::size_t>(p.parent);
        const std::uint32_t hint = p.parent >= 0 && parent < k ? triangles[parent] : SurfaceDistance::kNoHint;
        triangles.push_back(surface.closest(p.position, hint).triangle);
        hash = MeasuredClosest::hash_with(hash, p.position);
      }
      feed.taken(k);
      std::unique_lock<std::mutex> lock(mutex_);
      if (woken_.wait_for(lock, kRest, [&] { return stop_.load(std::memory_order_relaxed); })) return;
      if (feed.closed() && k == feed.put_count()) return;
    }
  }

  Run& run_;
  std::unique_ptr<ParticleFeed> feed_;
  std::shared_ptr<MeasuredClosest> measured_;
  std::mutex mutex_;
  std::condition_variable woken_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace

Cluster grow_recorded(Run& run, const ProgressFn& progress, const StopFlag* stop, RunRecord& record,
                      const StageProgress& links_progress) {
  const auto start = std::chrono::steady_clock::now();
  Cluster cluster;
  {
    SurfaceFollower follower(run);
    try {
      cluster = run.grow(progress, stop);
    } catch (const PartialGrowth& e) {
      cluster = e.partial();
      record.stopped_by = std::string("error: ") + e.what();
    }
    run.measured_while_growing = follower.finish();
  }
  if (!cluster.complete && record.stopped_by.empty()) {
    record.stopped_in = "growth";  // by a stop, not an error: the links would delay the files
  } else if (run.links.any()) {
    try {
      cluster.links = run.make_links(cluster, {stop, links_progress});
    } catch (const Interrupted&) {
      cluster.complete = false;
      record.stopped_in = "links";
    }
  }
  record.grow_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return cluster;
}

}  // namespace dla
