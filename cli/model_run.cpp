#include "model_run.h"

#include "run_files.h"

#include "dla/core/hash.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/text.h"
#include "dla/models/growth.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace dla::cli {

namespace {

//! Refuses, before growing, a run that cannot fit in this machine's memory: a structure takes
//! about 45 bytes a particle while it grows (docs/performance.md).
void check_memory(std::size_t particles) {
  constexpr double bytes_per_particle = 48.0;
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double memory = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double needed = bytes_per_particle * static_cast<double>(particles);
  if (pages > 0 && needed > memory)
    throw InvalidInput("--particles " + detail::format_count(particles) + " needs about " +
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

//! `dla3d [options]`: DLA, in or around a mesh or text if one is given.
class GrowthRun : public ModelRun {
 public:
  GrowthRun(const GrowCommand& command, const Checkpoint* resumed, const MeshReader& read)
      : options_(command.options), resumed_(resumed) {
    files = command;
    threads = options_.threads;
    mesh_name_ = command.text ? "the text '" + command.text->text + "'" : command.mesh_path;
    if (command.has_mesh()) set_up_mesh(command, read);
    check_memory(options_.particles);
    total = options_.particles;
    fill = options_.fill;
    constraint = constraint_.get();
    scene_mesh = !scene_mesh_.triangles.empty()     ? &scene_mesh_
                 : constraint_ && command.scene_mesh ? &constraint_->mesh()
                                                     : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    if (resumed_)
      return constraint_ ? resume(options_, *constraint_, resumed_->cluster, progress, stop)
                         : resume(options_, resumed_->cluster, progress, stop);
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

  void write_report(const Cluster& cluster, const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                    const std::string& path) const override {
    write_run_report(cluster, options_, look, pov, record, path, constraint_.get(), mesh_name_);
  }

 private:
  void set_up_mesh(const GrowCommand& command, const MeshReader& read) {
    TriangleMesh mesh;
    std::vector<Vec3> letter_seeds;
    if (command.text) {
      TextMesh text = text_mesh(*command.text);
      mesh = std::move(text.mesh);
      letter_seeds = std::move(text.glyph_seeds);
      // The text's own hash: the same words in another font are another mesh.
      input_hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
    } else {
      mesh = read(command.mesh_path, &input_hash);
    }
    if (resumed_ && resumed_->input_hash != input_hash)
      throw InvalidInput(mesh_name_ + " has changed since the checkpoint was written: the run cannot go on");
    const Box box = bounding_box(mesh);
    // Text is long and thin: a hundredth of its em leaves strokes some 17 spacings wide.
    if (!command.spacing_given) options_.spacing = command.text ? command.text->size / 100 : default_spacing(box);
    // Text reads upright with y up; a scan stands on its longest axis.
    if (!command.up_given) files.pov.up = command.text ? Axis::y : longest_axis(box);
    detail::require_in("spacing", options_.spacing, kMinSpacing, kMaxSpacing);
    try {
      constraint_ = std::make_unique<MeshConstraint>(mesh, command.constraint, options_.spacing);
    } catch (const InvalidInput& e) {
      throw InvalidInput(mesh_name_ + ": " + e.what());
    }
    // From the skin inside: thin parts (horns, fingers) get walkers by their surface. To fill
    // the volume, or to grow from seeds lining the skin, from anywhere in the volume: the
    // skin, covered, would stop walkers from the surface long before the inside is full.
    const bool whole_surface = command.seed_surface && !command.seed_paint;
    // In a shell, anywhere in it: walkers reach the structure over the surface.
    if (!command.spawn_given)
      options_.spawn = constraint_->shell() > 0.0                ? SpawnMode::inside
                       : command.constraint.side != Side::inside ? SpawnMode::sphere
                       : options_.fill > 0.0 || whole_surface    ? SpawnMode::inside
                                                                 : SpawnMode::surface;
    if (command.seed_surface || command.seed_paint || !command.seed_mesh_paths.empty()) {
      std::vector<TriangleMesh> entering;
      for (const std::string& path : command.seed_mesh_paths) entering.push_back(read(path, nullptr));
      // The scene shows the meshes that enter with the one they enter, to see where growth starts.
      if (!entering.empty() && command.scene_mesh) {
        scene_mesh_ = constraint_->mesh();
        for (const TriangleMesh& other : entering) append(scene_mesh_, other);
      }
      try {
        const std::vector<Vec3> cover =
            entering.empty()
                ? constraint_->sample_surface(options_.rng_seed, command.seed_paint ? &*command.seed_paint : nullptr)
                : constraint_->sample_intersection(entering, options_.rng_seed);
        options_.seeds = command.seed_count ? farthest_apart(cover, command.seed_count) : cover;
      } catch (const InvalidInput& e) {
        throw InvalidInput(mesh_name_ + ": " + e.what());
      }
    } else if (command.text && !command.seeds_given && !command.seed_count) {
      // Each letter is a volume of its own: a seed deep in each, or in a shell (whose parts
      // around letters far apart do not meet) or around the text, half a spacing off its front.
      options_.seeds = letter_seeds;
      if (command.constraint.side != Side::inside || constraint_->shell() > 0.0)
        for (Vec3& seed : options_.seeds)
          seed.z() = command.text->depth + (command.constraint.side == Side::inside ? -0.5 : 0.5) * options_.spacing;
    } else if (!command.seeds_given) {
      options_.seeds = constraint_->place_seeds(command.seed_count ? command.seed_count : 1, options_.rng_seed);
    }
    validate(options_, *constraint_);
    mesh_line = cli::mesh_line(mesh_name_, *constraint_, options_.spacing);
  }

  GrowthOptions options_;
  const Checkpoint* resumed_;
  std::string mesh_name_;
  std::unique_ptr<MeshConstraint> constraint_;
  TriangleMesh scene_mesh_;  // the scene's mesh when it is more than the constraint's
};

//! `dla3d colonize`: space colonization among attractors scattered or read from a file.
class ColonizeRun : public ModelRun {
 public:
  ColonizeRun(const ColonizeCommand& command, const MeshReader& read)
      : options_(command.options), attractor_options_(command.attractors) {
    files = command;
    unit = "nodes";
    total = options_.max_nodes;
    grown_with_ = options_;
    const auto read_solid = [&](const std::string& path, const auto& make) {
      try {
        return make(read(path, nullptr));
      } catch (const InvalidInput& e) {
        throw InvalidInput(path + ": " + e.what());
      }
    };
    if (!command.vessel_path.empty()) {
      vessel_ = read_solid(command.vessel_path, [&](const TriangleMesh& mesh) {
        const ConstraintOptions inside{Side::inside, ConstraintMode::reject};
        return std::make_unique<MeshConstraint>(mesh, inside, options_.spacing);
      });
      grown_with_.vessel = vessel_.get();
    }
    if (!command.collide_path.empty()) {
      collide_ = read_solid(command.collide_path, [&](const TriangleMesh& mesh) {
        return std::make_unique<CollisionObject>(mesh, options_.spacing, command.collision);
      });
      grown_with_.collide = collide_.get();
    }
    // Attractors and roots in or on "the mesh": the vessel's, else the collision object's.
    const MeshConstraint* mesh = vessel_ ? vessel_.get() : collide_ ? &collide_->solid() : nullptr;
    if (command.attractors_path.empty()) {
      attractors_ = scatter_attractors(command.attractors, options_.rng_seed, options_.dimensions, mesh);
    } else {
      attractors_ = read_points(command.attractors_path);
      if (command.sample_attractors)
        attractors_ = sample_attractors(attractors_, command.attractors.count, options_.rng_seed);
      if (attractors_.size() > kMaxAttractors)
        throw InvalidInput(command.attractors_path + ": more than 1e8 attractors");
      if (options_.dimensions == 2)
        for (const Vec3& a : attractors_)
          if (a.z() != 0.0)
            throw InvalidInput(command.attractors_path + ": --dimensions 2 grows in z = 0, and an attractor is not");
    }
    roots_ = colonize_roots(command, attractors_, mesh);
    inputs_ = {command.attractors_path, attractors_.size(), command.vessel_path, command.collide_path,
               command.collision};
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

  void write_report(const Cluster& tree, const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                    const std::string& path) const override {
    write_colonization_report(tree, options_, attractor_options_, look, pov, record, path, inputs_);
  }

 private:
  ColonizationOptions options_, grown_with_;
  AttractorOptions attractor_options_;
  std::unique_ptr<MeshConstraint> vessel_;
  std::unique_ptr<CollisionObject> collide_;
  std::vector<Vec3> attractors_, roots_;
  ColonizationInputs inputs_;
};

//! `dla3d eden`: an Eden cluster on a lattice, its mask a preset or drawn in a file.
class EdenRun : public ModelRun {
 public:
  explicit EdenRun(const EdenCommand& command) : options_(command.options), mask_path_(command.mask_path) {
    files = command;
    unit = "sites";
    total = options_.sites;
    if (!mask_path_.empty()) {
      std::ifstream in(mask_path_, std::ios::binary);
      std::ostringstream text;
      if (!in || !(text << in.rdbuf())) throw IOError("cannot read the mask '" + mask_path_ + "'");
      try {
        options_.mask_offsets = parse_mask(text.str());
        validate(options_);
      } catch (const InvalidInput& e) {
        throw InvalidInput(mask_path_ + ": " + e.what());
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

  void write_report(const Cluster& cluster, const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                    const std::string& path) const override {
    write_eden_report(cluster, options_, mask_path_, look, pov, record, path);
  }

 private:
  EdenOptions options_;
  std::string mask_path_;
};

//! `dla3d drop`: random-drop ballistic aggregation, in or around a mesh if one is given.
class DropRun : public ModelRun {
 public:
  DropRun(const DropCommand& command, const MeshReader& read) : options_(command.options), mesh_path_(command.mesh_path) {
    files = command;
    if (!mesh_path_.empty()) {
      // As for DLA: the spacing and the up axis from the mesh's box, one seed on the growing side.
      const TriangleMesh mesh = read(mesh_path_, nullptr);
      const Box box = bounding_box(mesh);
      if (!command.spacing_given) options_.spacing = default_spacing(box);
      if (!command.up_given) files.pov.up = longest_axis(box);
      detail::require_in("spacing", options_.spacing, kMinSpacing, kMaxSpacing);
      try {
        constraint_ = std::make_unique<MeshConstraint>(mesh, command.constraint, options_.spacing);
        if (!command.seeds_given) options_.seeds = constraint_->place_seeds(1, options_.rng_seed);
        validate(options_, *constraint_);
      } catch (const InvalidInput& e) {
        throw InvalidInput(mesh_path_ + ": " + e.what());
      }
      mesh_line = cli::mesh_line(mesh_path_, *constraint_, options_.spacing);
    }
    total = options_.seeds.size() + options_.particles;
    constraint = constraint_.get();
    scene_mesh = constraint_ && command.scene_mesh ? &constraint_->mesh() : nullptr;
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

  void write_report(const Cluster& cluster, const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                    const std::string& path) const override {
    write_drop_report(cluster, options_, stats_, constraint_.get(), mesh_path_, look, pov, record, path);
  }

 private:
  DropOptions options_;
  std::string mesh_path_;
  std::unique_ptr<MeshConstraint> constraint_;
  DropStats stats_;
};

//! `dla3d ballistic`: ballistic aggregation.
class BallisticRun : public ModelRun {
 public:
  explicit BallisticRun(const BallisticCommand& command) : options_(command.options) {
    files = command;
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

  void write_report(const Cluster& cluster, const LookOptions& look, const PovOptions& pov, const RunRecord& record,
                    const std::string& path) const override {
    write_ballistic_report(cluster, options_, stats_, look, pov, record, path);
  }

 private:
  BallisticOptions options_;
  BallisticStats stats_;
};

}  // namespace

std::unique_ptr<ModelRun> prepare_run(const CommandLine& line, const Checkpoint* resumed, const MeshReader& read) {
  const MeshReader reader =
      read ? read : [](const std::string& path, std::uint64_t* hash) { return read_mesh(path, hash); };
  using Kind = CommandLine::Kind;
  switch (line.kind) {
    case Kind::grow: return std::make_unique<GrowthRun>(line.grow, resumed, reader);
    case Kind::colonize: return std::make_unique<ColonizeRun>(line.colonize, reader);
    case Kind::eden: return std::make_unique<EdenRun>(line.eden);
    case Kind::drop: return std::make_unique<DropRun>(line.drop, reader);
    case Kind::ballistic: return std::make_unique<BallisticRun>(line.ballistic);
    default: throw InvalidInput("the command line asks for no growth");
  }
}

void write_run(const ModelRun& run, const Cluster& cluster, const FileOptions& files, RunRecord& record) {
  PovOptions pov = files.pov;
  pov.comment = record.command;
  const Clock::time_point start = Clock::now();
  write_files(cluster, files, pov, run.threads, run.constraint, run.scene_mesh);
  record.write_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (files.formats.json) run.write_report(cluster, files.look, pov, record, files.output + ".json");
}

}  // namespace dla::cli
