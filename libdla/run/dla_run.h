#pragma once
// DLA's run (run.h), in a header of its own because the breakdown model's run is DLA's with
// another growth (breakdown_run.cpp): the same meshes, seeds, defaults and files.

#include "model_runs.h"

#include "dla/core/hash.h"
#include "dla/core/memory.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/text.h"

#include <cstdio>

namespace dla::detail {

//! Refuses, before growing, a run that cannot fit in this machine's memory: a structure takes
//! about 45 bytes a particle while it grows (docs/performance.md).
inline void check_memory(std::size_t particles) {
  constexpr double bytes_per_particle = 48.0;
  const double memory = installed_memory();
  const double needed = bytes_per_particle * static_cast<double>(particles);
  if (memory > 0 && needed > memory)
    throw InvalidInput("`particles` " + format_count(particles) + " needs about " + format_number(needed / 1e9) +
                       " GB of memory; this machine has " + format_number(memory / 1e9) + " GB");
}

//! DLA, in or around a mesh or text if one is given.
class DlaRun : public Run {
 public:
  DlaRun(const DlaRunOptions& o, const MeshReader& read, const Resumed& resumed)
      : options_(walk_options(o)), resumed_(resumed.cluster) {
    if (resumed.stats) stats_.walk = *resumed.stats;
    if (!o.particles && o.has_mesh()) options_.particles = o.growth.fill > 0.0 ? kFillParticles : kMeshParticles;
    threads = options_.threads;
    mesh_name_ = o.text ? "the text '" + o.text->text + "'" : o.stl;
    if (o.has_mesh()) {
      set_up_mesh(o, read, resumed.mesh_hash);
    } else {
      validate(options_);
      files = resolve(o.files, nullptr, false);
    }
    check_memory(options_.particles);
    // Walkers stick at contact, a spacing from every particle, unless a branch is clipped short.
    const bool clipped = o.has_mesh() && o.constraint.mode == ConstraintMode::clip;
    solid_forecast = {options_.fill > 0.0 ? 0 : options_.particles, clipped ? 0.0 : 1.0};
    total = options_.particles;
    fill = options_.fill;
    links = o.links;
    constraint = constraint_.get();
    scene_mesh = !scene_mesh_.triangles.empty() ? &scene_mesh_ : constraint_ && o.scene_mesh ? &constraint_->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    if (resumed_)
      return constraint_ ? resume(options_, *constraint_, *resumed_, progress, stop, &stats_)
                         : resume(options_, *resumed_, progress, stop, &stats_);
    return constraint_ ? dla::grow(options_, *constraint_, progress, stop, &stats_)
                       : dla::grow(options_, progress, stop, &stats_);
  }

  std::vector<Link> make_links(const Cluster& cluster, const StageWatch& watch) const override {
    return links_inside(cluster, links, threads, constraint_.get(), watch);
  }

  bool feed_to(ParticleFeed* feed) override {
    stats_.feed = feed;
    return true;
  }

  std::size_t done(const Cluster& so_far) const override { return attached(so_far); }
  double filled() const override { return stats_.filled; }
  const WalkStats* walks() const override { return &stats_.walk; }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    const double count = static_cast<double>(attached(cluster));
    char filled[160] = "";
    if (options_.fill > 0.0)
      std::snprintf(filled, sizeof filled, "; %.1f%% of the mesh's volume within %g spacings of it%s",
                    100.0 * stats_.filled, options_.fill_distance,
                    stats_.filled >= options_.fill ? "" : ", short of the fill asked (-n ended growth)");
    char line[512];
    std::snprintf(line, sizeof line,
                  "grew %s particles in %.2f s (%s particles/s); bounding radius %.1f, radius of gyration %.1f%s",
                  with_commas(count).c_str(), record.grow_seconds,
                  with_commas(record.grow_seconds > 0 ? count / record.grow_seconds : 0.0).c_str(),
                  bounding_radius(cluster), radius_of_gyration(cluster), filled);
    return line;
  }

  void put_resolved(RunOptions& options) const override { resolve_walk(options.get<DlaRunOptions>()); }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.resolved = [this](RecordWriter& w) { w.points("seed_at", options_.seeds); };
    out.statistics = [this](RecordWriter& w) {
      if (constraint_) record_constraint(w);
      const WalkStats& s = stats_.walk;
      w.open("walk")
          .counts({{"walkers", s.walkers}, {"steps", s.steps}, {"near_steps", s.near_steps}, {"contacts", s.contacts},
                   {"returns", s.returns}, {"relaunches", s.relaunches}, {"lost", s.lost}, {"rejected", s.rejected},
                   {"clipped", s.clipped}})
          .close();
    };
    if (options_.fill > 0.0) out.measures = [this](RecordWriter& w) { w.number("filled", stats_.filled, 6); };
    // How the run was spread over threads changes how long it took, never what it grew.
    out.timings = [this](RecordWriter& w) { w.integer("threads", options_.threads).count("replays", stats_.replays); };
    return out;
  }

 protected:
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
    const bool whole_surface = o.seeds.whole_surface();
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
    mesh_line = detail::mesh_line(mesh_name_, *constraint_, options_.spacing);
  }

  //! The count, the spacing and the spawn a mesh gives, in place of the defaults.
  void resolve_walk(DlaRunOptions& o) const {
    o.particles = options_.particles;
    o.spacing = options_.spacing;
    o.spawn = options_.spawn;
  }

  void record_constraint(RecordWriter& out) const {
    const RepairReport& r = constraint_->repair_report();
    out.open("constraint")
        .text("mesh", mesh_name_)
        .text("side", to_string(constraint_->options().side))
        .text("mode", to_string(constraint_->options().mode))
        .number("shell_spacings", constraint_->shell() / constraint_->spacing())
        .count("input_triangles", r.input_triangles)
        .count("triangles", constraint_->mesh().triangles.size())
        .text("repair", r.summary())
        .flag("closed", r.closed)
        .close();
  }

  DlaOptions options_;
  DlaStats stats_;
  const Cluster* resumed_;
  std::string mesh_name_;
  std::unique_ptr<MeshConstraint> constraint_;
  TriangleMesh scene_mesh_;  // the scene's mesh when it is more than the constraint's
};


}  // namespace dla::detail
