// prepare_run(): each model's run set up from its options (run.h): the meshes read, their
// defaults taken, the seeds, roots or attractors placed, everything checked.

#include "dla/run/run.h"

#include "dla/core/hash.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/text.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

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

namespace {

using detail::with_commas;
using Clock = std::chrono::steady_clock;

//! Refuses, before growing, a run that cannot fit in this machine's memory: a structure takes
//! about 45 bytes a particle while it grows (docs/performance.md).
void check_memory(std::size_t particles) {
  constexpr double bytes_per_particle = 48.0;
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double memory = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double needed = bytes_per_particle * static_cast<double>(particles);
  if (pages > 0 && needed > memory)
    throw InvalidInput("`particles` " + detail::format_count(particles) + " needs about " +
                       detail::format_number(needed / 1e9) + " GB of memory; this machine has " +
                       detail::format_number(memory / 1e9) + " GB");
}

std::string mesh_line(const std::string& name, const MeshConstraint& constraint, double spacing) {
  char line[512];
  std::snprintf(line, sizeof line, "%s: %s triangles; %s; spacing %g", name.c_str(),
                with_commas(static_cast<double>(constraint.repair_report().input_triangles)).c_str(),
                constraint.repair_report().summary().c_str(), spacing);
  return line;
}

//! The files' defaults without a mesh, or with one whose box is `mesh_box`; with `mesh_look`,
//! the look of a root system (DLA in a mesh).
OutputOptions resolve(OutputOptions files, const Box* mesh_box, bool mesh_look, std::optional<Axis> mesh_up = {}) {
  if (files.up) files.pov.up = *files.up;
  else if (mesh_up) files.pov.up = *mesh_up;
  else if (mesh_box) files.pov.up = longest_axis(*mesh_box);
  files.look.radius.model = files.radius.value_or(mesh_look ? RadiusModel::pipe : files.look.radius.model);
  files.look.radius.base_radius = files.base_radius.value_or(mesh_look ? kMeshBaseRadius : files.look.radius.base_radius);
  files.look.radius.tip_radius = files.tip_radius.value_or(mesh_look ? kMeshTipRadius : files.look.radius.tip_radius);
  return files;
}

std::vector<TriangleMesh> read_all(const MeshReader& read, const std::vector<std::string>& paths) {
  std::vector<TriangleMesh> meshes;
  for (const std::string& path : paths) meshes.push_back(read(path, nullptr));
  return meshes;
}

//! A mesh with the meshes that enter it, for a scene that shows where growth starts.
TriangleMesh with_entering(TriangleMesh mesh, const std::vector<TriangleMesh>& entering) {
  for (const TriangleMesh& other : entering) append(mesh, other);
  return mesh;
}

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

//! DLA, in or around a mesh or text if one is given.
class DlaRun : public Run {
 public:
  DlaRun(const DlaRunOptions& o, const MeshReader& read, const Cluster* resumed, std::uint64_t resumed_hash)
      : options_(walk_options(o)), resumed_(resumed) {
    if (!o.particles && o.has_mesh()) options_.particles = o.growth.fill > 0.0 ? kFillParticles : kMeshParticles;
    threads = options_.threads;
    mesh_name_ = o.text ? "the text '" + o.text->text + "'" : o.stl;
    if (o.has_mesh()) {
      set_up_mesh(o, read, resumed_hash);
    } else {
      validate(options_);
      files = resolve(o.files, nullptr, false);
    }
    check_memory(options_.particles);
    total = options_.particles;
    fill = options_.fill;
    constraint = constraint_.get();
    scene_mesh = !scene_mesh_.triangles.empty() ? &scene_mesh_ : constraint_ && o.scene_mesh ? &constraint_->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    if (resumed_)
      return constraint_ ? resume(options_, *constraint_, *resumed_, progress, stop)
                         : resume(options_, *resumed_, progress, stop);
    return constraint_ ? dla::grow(options_, *constraint_, progress, stop) : dla::grow(options_, progress, stop);
  }

  std::size_t done(const Cluster& so_far) const override { return attached(so_far); }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    const double count = static_cast<double>(attached(cluster));
    char filled[160] = "";
    if (options_.fill > 0.0)
      std::snprintf(filled, sizeof filled, "; %.1f%% of the mesh's volume within %g spacings of it%s",
                    100.0 * cluster.filled, options_.fill_distance,
                    cluster.filled >= options_.fill ? "" : ", short of the fill asked (-n ended growth)");
    char line[512];
    std::snprintf(line, sizeof line,
                  "grew %s particles in %.2f s (%s particles/s); bounding radius %.1f, radius of gyration %.1f%s",
                  with_commas(count).c_str(), record.grow_seconds,
                  with_commas(record.grow_seconds > 0 ? count / record.grow_seconds : 0.0).c_str(),
                  bounding_radius(cluster), radius_of_gyration(cluster), filled);
    return line;
  }

  void write_report(const Cluster& cluster, const OutputOptions& out, const RunRecord& record,
                    const std::string& path) const override {
    write_run_report(cluster, options_, out.look, out.pov, record, path, constraint_.get(), mesh_name_);
  }

 private:
  void set_up_mesh(const DlaRunOptions& o, const MeshReader& read, std::uint64_t resumed_hash) {
    TriangleMesh mesh;
    std::vector<Vec3> letter_seeds;
    if (o.text) {
      TextMesh text = text_mesh(*o.text);
      mesh = std::move(text.mesh);
      letter_seeds = std::move(text.glyph_seeds);
      // The text's own hash: the same words in another font are another mesh.
      input_hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
    } else {
      mesh = read(o.stl, &input_hash);
    }
    if (resumed_ && resumed_hash != input_hash)
      throw InvalidInput(mesh_name_ + " has changed since the checkpoint was written: the run cannot go on");
    const Box box = bounding_box(mesh);
    // Text is long and thin: a hundredth of its em leaves strokes some 17 spacings wide.
    if (!o.spacing) options_.spacing = o.text ? o.text->size / 100 : default_spacing(box);
    // Text reads upright with y up; a scan stands on its longest axis.
    files = resolve(o.files, &box, true, o.text ? std::optional<Axis>(Axis::y) : std::nullopt);
    detail::require_in("spacing", options_.spacing, kMinSpacing, kMaxSpacing);
    try {
      constraint_ = std::make_unique<MeshConstraint>(mesh, o.constraint, options_.spacing);
    } catch (const InvalidInput& e) {
      throw InvalidInput(mesh_name_ + ": " + e.what());
    }
    // From the skin inside: thin parts (horns, fingers) get walkers by their surface. To fill
    // the volume, or to grow from seeds lining the skin, from anywhere in the volume: the
    // skin, covered, would stop walkers from the surface long before the inside is full.
    const bool whole_surface = o.seeds.surface && !o.seeds.paint;
    // In a shell, anywhere in it: walkers reach the structure over the surface.
    if (!o.spawn)
      options_.spawn = constraint_->shell() > 0.0                ? SpawnMode::inside
                       : o.constraint.side != Side::inside       ? SpawnMode::sphere
                       : options_.fill > 0.0 || whole_surface    ? SpawnMode::inside
                                                                 : SpawnMode::surface;
    if (o.seeds.on_surface()) {
      const std::vector<TriangleMesh> entering = read_all(read, o.seeds.meshes);
      // The scene shows the meshes that enter with the one they enter, to see where growth starts.
      if (!entering.empty() && o.scene_mesh) scene_mesh_ = with_entering(constraint_->mesh(), entering);
      options_.seeds = named(mesh_name_, [&] { return seeds_on(*constraint_, o.seeds, options_.rng_seed, entering); });
    } else if (o.text && !o.seed_at && !o.seeds.count) {
      // Each letter is a volume of its own: a seed deep in each, or in a shell (whose parts
      // around letters far apart do not meet) or around the text, half a spacing off its front.
      options_.seeds = letter_seeds;
      if (o.constraint.side != Side::inside || constraint_->shell() > 0.0)
        for (Vec3& seed : options_.seeds)
          seed.z() = o.text->depth + (o.constraint.side == Side::inside ? -0.5 : 0.5) * options_.spacing;
    } else if (!o.seed_at) {
      options_.seeds = constraint_->place_seeds(o.seeds.count ? o.seeds.count : 1, options_.rng_seed);
    }
    validate(options_, *constraint_);
    mesh_line = dla::mesh_line(mesh_name_, *constraint_, options_.spacing);
  }

  DlaOptions options_;
  const Cluster* resumed_;
  std::string mesh_name_;
  std::unique_ptr<MeshConstraint> constraint_;
  TriangleMesh scene_mesh_;  // the scene's mesh when it is more than the constraint's
};

//! Space colonization among attractors scattered or read from a file.
class ColonizeRun : public Run {
 public:
  ColonizeRun(const ColonizeRunOptions& o, const MeshReader& read)
      : options_(o.colonization), attractor_options_(o.attractors) {
    files = resolve(o.files, nullptr, false);
    unit = "nodes";
    total = options_.max_nodes;
    grown_with_ = options_;
    if (!o.stl.empty()) {
      vessel_ = with_mesh(read, o.stl, [&](const TriangleMesh& mesh) {
        const ConstraintOptions inside{Side::inside, ConstraintMode::reject};
        return std::make_unique<MeshConstraint>(mesh, inside, options_.spacing);
      });
      grown_with_.vessel = vessel_.get();
    }
    if (!o.collide.empty()) {
      collide_ = with_mesh(read, o.collide, [&](const TriangleMesh& mesh) {
        return std::make_unique<CollisionObject>(mesh, options_.spacing, o.collision);
      });
      grown_with_.collide = collide_.get();
    }
    // Attractors and roots in or on "the mesh": the vessel's, else the collision object's.
    const MeshConstraint* mesh = vessel_ ? vessel_.get() : collide_ ? &collide_->solid() : nullptr;
    if (o.attractors_from.empty()) {
      attractors_ = scatter_attractors(o.attractors, options_.rng_seed, options_.dimensions, mesh);
    } else {
      attractors_ = read_points(o.attractors_from);
      if (o.sample_attractors) attractors_ = sample_attractors(attractors_, o.attractors.count, options_.rng_seed);
      if (attractors_.size() > kMaxAttractors) throw InvalidInput(o.attractors_from + ": more than 1e8 attractors");
      if (options_.dimensions == 2)
        for (const Vec3& a : attractors_)
          if (a.z() != 0.0)
            throw InvalidInput(o.attractors_from + ": `dimensions` 2 grows in z = 0, and an attractor is not");
    }
    if (mesh && (o.seeds.count || o.seeds.on_surface())) {
      const std::vector<TriangleMesh> entering = read_all(read, o.seeds.meshes);
      roots_ = named(mesh == vessel_.get() ? o.stl : o.collide,
                     [&] { return seeds_on(*mesh, o.seeds, options_.rng_seed, entering); });
      if (roots_.size() > options_.max_nodes) throw InvalidInput("more roots than `max_nodes`");
    } else {
      roots_ = colonize_roots(o, attractors_, mesh);
    }
    inputs_ = {o.attractors_from, attractors_.size(), o.stl, o.collide, o.collision};
    // The vessel, else the collision mesh, shows in the scene as glass, as a constraint mesh does.
    constraint = vessel_.get();
    scene_mesh = mesh ? &mesh->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::colonize(grown_with_, std::move(attractors_), roots_, progress, stop);
  }

  std::string summary(const Cluster& tree, const RunRecord& record) const override {
    char line[256];
    std::snprintf(line, sizeof line, "grew %s nodes from %s root%s in %.2f s; bounding radius %.1f",
                  with_commas(static_cast<double>(tree.particles.size())).c_str(),
                  with_commas(static_cast<double>(tree.seed_count)).c_str(), tree.seed_count == 1 ? "" : "s",
                  record.grow_seconds, bounding_radius(tree));
    return line;
  }

  void write_report(const Cluster& tree, const OutputOptions& out, const RunRecord& record,
                    const std::string& path) const override {
    write_colonization_report(tree, options_, attractor_options_, out.look, out.pov, record, path, inputs_);
  }

 private:
  ColonizationOptions options_, grown_with_;
  AttractorOptions attractor_options_;
  std::unique_ptr<MeshConstraint> vessel_;
  std::unique_ptr<CollisionObject> collide_;
  std::vector<Vec3> attractors_, roots_;
  ColonizationInputs inputs_;
};

//! An Eden cluster on a lattice, its mask a preset or drawn in a file.
class EdenRun : public Run {
 public:
  explicit EdenRun(const EdenRunOptions& o) : options_(o.eden), mask_file_(o.mask_file) {
    files = resolve(o.files, nullptr, false);
    unit = "sites";
    total = options_.sites;
    if (!mask_file_.empty()) {
      std::ifstream in(mask_file_, std::ios::binary);
      std::ostringstream text;
      if (!in || !(text << in.rdbuf())) throw IOError("cannot read the mask '" + mask_file_ + "'");
      try {
        options_.mask_offsets = parse_mask(text.str());
        validate(options_);
      } catch (const InvalidInput& e) {
        throw InvalidInput(mask_file_ + ": " + e.what());
      }
    }
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override { return dla::eden(options_, progress, stop); }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char line[256];
    std::snprintf(line, sizeof line, "grew %s sites on a %s lattice in %.2f s%s; bounding radius %.1f",
                  with_commas(static_cast<double>(cluster.particles.size())).c_str(),
                  std::string(to_string(options_.lattice)).c_str(), record.grow_seconds,
                  cluster.complete && cluster.particles.size() < options_.sites ? " (then no site could stick)" : "",
                  bounding_radius(cluster));
    return line;
  }

  void write_report(const Cluster& cluster, const OutputOptions& out, const RunRecord& record,
                    const std::string& path) const override {
    write_eden_report(cluster, options_, mask_file_, out.look, out.pov, record, path);
  }

 private:
  EdenOptions options_;
  std::string mask_file_;
};

//! Random-drop ballistic aggregation, in or around a mesh if one is given.
class DropRun : public Run {
 public:
  DropRun(const DropRunOptions& o, const MeshReader& read) : options_(o.drop), mesh_file_(o.stl) {
    if (o.spacing) options_.spacing = *o.spacing;
    if (o.seed_at) options_.seeds = *o.seed_at;
    if (mesh_file_.empty()) {
      files = resolve(o.files, nullptr, false);
    } else {
      // As for DLA: the spacing and the up axis from the mesh's box, one seed on the growing side.
      const TriangleMesh mesh = read(mesh_file_, nullptr);
      const Box box = bounding_box(mesh);
      if (!o.spacing) options_.spacing = default_spacing(box);
      files = resolve(o.files, &box, false);
      detail::require_in("spacing", options_.spacing, kMinSpacing, kMaxSpacing);
      const std::vector<TriangleMesh> entering = read_all(read, o.seeds.meshes);
      named(mesh_file_, [&] {
        constraint_ = std::make_unique<MeshConstraint>(mesh, o.constraint, options_.spacing);
        if (!o.seed_at) options_.seeds = seeds_on(*constraint_, o.seeds, options_.rng_seed, entering);
        validate(options_, *constraint_);
      });
      if (!entering.empty() && o.scene_mesh) scene_mesh_ = with_entering(constraint_->mesh(), entering);
      mesh_line = dla::mesh_line(mesh_file_, *constraint_, options_.spacing);
    }
    total = options_.seeds.size() + options_.particles;
    constraint = constraint_.get();
    scene_mesh = !scene_mesh_.triangles.empty() ? &scene_mesh_ : constraint_ && o.scene_mesh ? &constraint_->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::drop(options_, constraint_.get(), progress, stop, &stats_);
  }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char line[320];
    std::snprintf(line, sizeof line,
                  "grew %s particles from %s drops in %.2f s%s; %s fell on the structure; bounding radius %.1f",
                  with_commas(static_cast<double>(attached(cluster))).c_str(),
                  with_commas(static_cast<double>(stats_.drops)).c_str(), record.grow_seconds,
                  stats_.zone_full ? " (then the drop zone was full)" : "",
                  with_commas(static_cast<double>(stats_.on_structure)).c_str(), bounding_radius(cluster));
    return line;
  }

  void write_report(const Cluster& cluster, const OutputOptions& out, const RunRecord& record,
                    const std::string& path) const override {
    write_drop_report(cluster, options_, stats_, constraint_.get(), mesh_file_, out.look, out.pov, record, path);
  }

 private:
  DropOptions options_;
  std::string mesh_file_;
  std::unique_ptr<MeshConstraint> constraint_;
  TriangleMesh scene_mesh_;  // the scene's mesh when it is more than the constraint's
  DropStats stats_;
};

//! Ballistic aggregation.
class BallisticRun : public Run {
 public:
  explicit BallisticRun(const BallisticRunOptions& o) : options_(o.ballistic) {
    files = resolve(o.files, nullptr, false);
    total = options_.seeds.size() + options_.particles;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::ballistic(options_, progress, stop, &stats_);
  }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char line[256];
    std::snprintf(line, sizeof line, "grew %s particles from %s lines (%s missed) in %.2f s; bounding radius %.1f",
                  with_commas(static_cast<double>(attached(cluster))).c_str(),
                  with_commas(static_cast<double>(stats_.launched)).c_str(),
                  with_commas(static_cast<double>(stats_.missed)).c_str(), record.grow_seconds,
                  bounding_radius(cluster));
    return line;
  }

  void write_report(const Cluster& cluster, const OutputOptions& out, const RunRecord& record,
                    const std::string& path) const override {
    write_ballistic_report(cluster, options_, stats_, out.look, out.pov, record, path);
  }

 private:
  BallisticOptions options_;
  BallisticStats stats_;
};

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

std::unique_ptr<Run> prepare_run(const RunOptions& options, const MeshReader& read, const Cluster* resumed,
                                 std::uint64_t resumed_hash) {
  validate(options);
  const MeshReader reader =
      read ? read : [](const std::string& path, std::uint64_t* hash) { return read_mesh(path, hash); };
  std::unique_ptr<Run> run = std::visit(
      Overloaded{
          [&](const DlaRunOptions& o) -> std::unique_ptr<Run> {
            return std::make_unique<DlaRun>(o, reader, resumed, resumed_hash);
          },
          [&](const ColonizeRunOptions& o) -> std::unique_ptr<Run> { return std::make_unique<ColonizeRun>(o, reader); },
          [&](const EdenRunOptions& o) -> std::unique_ptr<Run> { return std::make_unique<EdenRun>(o); },
          [&](const DropRunOptions& o) -> std::unique_ptr<Run> { return std::make_unique<DropRun>(o, reader); },
          [&](const BallisticRunOptions& o) -> std::unique_ptr<Run> { return std::make_unique<BallisticRun>(o); },
      },
      options);
  run->model = model_name(options);
  if (resumed && run->model != "grow") throw InvalidInput("only DLA runs go on from a checkpoint");
  return run;
}

Cluster grow_recorded(Run& run, const ProgressFn& progress, const StopFlag* stop, RunRecord& record) {
  const Clock::time_point start = Clock::now();
  Cluster cluster;
  try {
    cluster = run.grow(progress, stop);
  } catch (const PartialGrowth& e) {
    cluster = e.partial();
    record.stopped_by = std::string("error: ") + e.what();
  }
  record.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return cluster;
}

}  // namespace dla
