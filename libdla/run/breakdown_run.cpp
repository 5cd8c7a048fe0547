// The breakdown model's run (run.h): DLA's run (dla_run.h) for the meshes, seeds, defaults and
// files, with the discharge's growth (breakdown.h), its checks, summary and record.

#include "dla_run.h"

#include "dla/models/breakdown.h"
#include "dla/models/electrode.h"
#include "dla/mesh/mesh_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace dla {

namespace {

//! The options of a DLA run that a breakdown run does not take: its walkers neither drift nor
//! turn, its walk needs the grid index, and it grows to its count or its strike, not to fill a
//! mesh (`fill` the front ends refuse, with why: Model::refuses).
constexpr std::array<std::string_view, 5> kNotForBreakdown{"fill", "fill_distance", "drift", "rotate", "index"};

//! The one target: a second of another kind is refused, whichever came first.
void aim(Target& target, TargetKind kind) {
  if (target.kind != TargetKind::none && target.kind != kind)
    throw InvalidInput("`target_" + std::string(to_string(target.kind)) + "` and `target_" +
                       std::string(to_string(kind)) + "` are two targets: give one");
  target.kind = kind;
}

}  // namespace

const OptionTable<BreakdownRunOptions>& breakdown_run_option_table() {
  using O = BreakdownRunOptions;
  static const OptionTable<O> table = [] {
    // The discharge first: its group heads --help, and its target is the mesh a front end
    // offers a second object for before the seeds' (the Blender add-on).
    OptionTable<O> t = nested(breakdown_option_table(), &O::breakdown);
    using B = BreakdownOptions;
    constexpr std::string_view group = "Discharge";
    const OptionTable<O> targets = nested(
        OptionTable<B>{
            parsed<B>(
                "target_point", OptionKind::vector, "X,Y,Z", group,
                "the other electrode: a small ball at x,y,z; walkers leave it",
                [](B& o, const std::string& words) {
                  if (words.empty()) return;
                  const std::vector<double> p = detail::numbers_in("target_point", words, 3);
                  aim(o.target, TargetKind::point);
                  o.target.point = Vec3(p[0], p[1], p[2]);
                },
                [](const B& o) {
                  return o.target.kind == TargetKind::point ? detail::point_words(o.target.point) : std::string();
                }),
            excluding(parsed<B>(
                "target_plane", OptionKind::text, "AXIS=VALUE", group,
                "the other electrode: the plane AXIS = VALUE (a line in 2D), the ground; walkers leave it",
                [](B& o, const std::string& words) {
                  if (words.empty()) return;
                  const std::size_t mark = words.find_first_of("=,");
                  if (mark == std::string::npos || mark == 0)
                    throw InvalidInput("`target_plane` '" + words + "' is not AXIS=VALUE (as y=-60)");
                  Axis axis;
                  try {
                    axis = parse_word<Axis>(words.substr(0, mark));
                  } catch (const InvalidInput&) {
                    throw InvalidInput("`target_plane` '" + words + "': its axis is not one of " + accepted_words<Axis>());
                  }
                  const double at = detail::numbers_in("target_plane", std::string_view(words).substr(mark + 1), 1)[0];
                  aim(o.target, TargetKind::plane);
                  o.target.axis = axis;
                  o.target.at = at;
                },
                [](const B& o) {
                  return o.target.kind == TargetKind::plane
                             ? std::string(to_string(o.target.axis)) + "=" + detail::exact_number(o.target.at)
                             : std::string();
                }),
                {"target_point"}),
        },
        &O::breakdown);
    t.insert(t.end(), targets.begin(), targets.end());
    t.push_back(excluding(file("target_mesh", &O::target_mesh, kMeshFileForm, group,
                               "the other electrode: a mesh's surface (STL, OBJ, PLY, OFF; repaired as --stl is), a "
                               "lightning rod; 3D only"),
                          {"target_point", "target_plane"}));
    for (const DescribedOption<DlaRunOptions>& row : dla_run_option_table())
      if (std::find(kNotForBreakdown.begin(), kNotForBreakdown.end(), row.about.name) == kNotForBreakdown.end())
        t.push_back({row.about, [set = row.set](O& o, const OptionValue& v) { set(o, v); },
                     [get = row.get](const O& o) { return get(o); }});
    return t;
  }();
  return table;
}

void validate(const BreakdownRunOptions& o) {
  // Before DLA's checks, which would ask a fill for a mesh.
  if (o.growth.fill != 0.0) refuse_for("breakdown", "fill");
  validate(static_cast<const DlaRunOptions&>(o));
  if (!o.target_mesh.empty() && o.breakdown.target.kind != TargetKind::none)
    throw InvalidInput("`target_mesh` and `target_" + std::string(to_string(o.breakdown.target.kind)) +
                       "` are two targets: give one");
  if (!o.target_mesh.empty() && o.growth.dimensions == 2)
    throw InvalidInput("`target_mesh` is for 3D growth; in 2D give `target_point` or `target_plane` (a line)");
  // The seeds against the target wait for the mesh when it places them, and for the target's
  // mesh when it is read.
  BreakdownOptions own = o.breakdown;
  if (o.has_mesh() && !o.seed_at) own.target = {};
  validate(own, walk_options(o));
}

namespace detail {

namespace {

class BreakdownRun : public DlaRun {
 public:
  BreakdownRun(const BreakdownRunOptions& o, const MeshReader& read)
      : DlaRun(o, read, Resumed{}), breakdown_(o.breakdown), target_mesh_name_(o.target_mesh) {
    if (!o.target_mesh.empty()) {
      read_target(read);
      // The scene shows the target beside the insulator, to see where the bolt goes.
      if (o.scene_mesh) {
        scene_mesh_ = with_entering(scene_mesh ? *scene_mesh : TriangleMesh{}, {target_->mesh()});
        scene_mesh = &scene_mesh_;
      }
    }
    validate(breakdown_, options_);
    const Target& target = breakdown_.target;
    if (constraint_ && target.kind == TargetKind::point && !constraint_->on_growth_side(target.point))
      throw InvalidInput("`target_point` is not on the growing side of " + mesh_name_ +
                         ": it lies in the insulator, and no walker can leave it");
    if (constraint_ && target.kind == TargetKind::mesh &&
        std::none_of(target_->mesh().vertices.begin(), target_->mesh().vertices.end(),
                     [&](const Vec3& v) { return constraint_->on_growth_side(v); }))
      throw InvalidInput("`target_mesh` " + target_mesh_name_ + " is not on the growing side of " + mesh_name_ +
                         ": it lies in the insulator, and no walker can leave it");
    if (breakdown_.field != BreakdownField::walkers) foresee_fields(options_.particles);
    // A strike ends growth before the count: no count is promised.
    if (target.kind != TargetKind::none && breakdown_.stop_at_strike) solid_forecast.particles = 0;
  }

  //! The point-charge fields keep six sites a particle at most and their charges: memory in
  //! proportion to the count. The charges field sums each new particle's charge at every open
  //! site, time to the count's square; the conductor field's potentials, about 200 a particle,
  //! each cost a Barnes-Hut sum over a tree that deepens with the count
  //! (docs/performance.md#the-breakdown-model).
  void foresee_fields(std::size_t particles) {
    const bool charges = breakdown_.field == BreakdownField::charges;
    const double bytes_per_particle = charges ? 400.0 : 1000.0;
    const std::string field = "the " + std::string(to_string(breakdown_.field)) + " field";
    const double n = static_cast<double>(particles), memory = installed_memory();
    if (memory > 0.0 && bytes_per_particle * n > memory)
      throw InvalidInput("`particles` " + format_count(particles) + " with " + field + " needs about " +
                         format_number(std::ceil(bytes_per_particle * n / 1e8) / 10.0) + " GB of memory; this machine has " +
                         format_number(std::floor(memory / 1e8) / 10.0) + " GB: at most " +
                         format_count(static_cast<std::size_t>(memory / bytes_per_particle)) + " particles fit");
    // Charges: about 2.5 open sites a particle, each summing every later charge, and six new
    // sites each summing the charges before them: 4 n^2 potentials, about 1e9 a second on one
    // core. Conductor: measured, 3 to 4 s for 10^4 and 90 s for 10^5 on one core.
    const double seconds = charges ? 4.0 * n * n / 1e9 : 1.8e-6 * std::pow(n, 1.55);
    if (seconds > 120.0)
      forecast_line = field + " takes " + time_for_pairs(seconds * kPairsPerSecond) + " on one core for " +
                      format_count(particles) + " particles";
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::breakdown(options_, breakdown_, constraint_.get(), progress, stop, &stats_);
  }

  bool feed_to(ParticleFeed* feed) override {
    stats_.feed = feed;
    return true;
  }

  const WalkStats* walks() const override { return &stats_.walk; }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char strike[96] = "";
    if (cluster.strike >= 0)
      std::snprintf(strike, sizeof strike, "; struck the target at particle %s",
                    with_commas(static_cast<double>(cluster.strike)).c_str());
    else if (breakdown_.target.kind != TargetKind::none)
      std::snprintf(strike, sizeof strike, "; the target was not reached");
    char field[96];
    if (breakdown_.field == BreakdownField::charges)
      std::snprintf(field, sizeof field, "by the charges field, %s sites weighed",
                    with_commas(static_cast<double>(stats_.sites)).c_str());
    else if (breakdown_.field == BreakdownField::conductor)
      std::snprintf(field, sizeof field, "by the conductor field, %s sites weighed, %s solves",
                    with_commas(static_cast<double>(stats_.sites)).c_str(),
                    with_commas(static_cast<double>(stats_.solves)).c_str());
    else
      std::snprintf(field, sizeof field, "%d walkers each (%s walks)", walkers_for(breakdown_),
                    with_commas(static_cast<double>(stats_.walk.walkers)).c_str());
    char line[512];
    std::snprintf(line, sizeof line, "grew %s particles at eta %g in %.2f s, %s; bounding radius %.1f%s",
                  with_commas(static_cast<double>(attached(cluster))).c_str(), breakdown_.eta, record.grow_seconds,
                  field, bounding_radius(cluster), strike);
    return line;
  }

  void put_resolved(RunOptions& options) const override {
    BreakdownRunOptions& o = options.get<BreakdownRunOptions>();
    resolve_walk(o);
    if (breakdown_.field == BreakdownField::walkers) o.breakdown.walkers = walkers_for(breakdown_);
  }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.resolved = [this](RecordWriter& w) { w.points("seed_at", options_.seeds); };
    out.statistics = [this](RecordWriter& w) {
      if (constraint_) record_constraint(w);
      if (target_)
        w.open("target")
            .text("mesh", target_mesh_name_)
            .count("triangles", target_->mesh().triangles.size())
            .text("repair", target_repair_.summary())
            .flag("closed", target_repair_.closed)
            .close();
      const WalkStats& s = stats_.walk;
      w.open("walk")
          .counts({{"walkers", s.walkers}, {"steps", s.steps}, {"near_steps", s.near_steps}, {"contacts", s.contacts},
                   {"returns", s.returns}, {"relaunches", s.relaunches}, {"absorbed", s.absorbed}, {"lost", s.lost},
                   {"rejected", s.rejected}, {"clipped", s.clipped}})
          .close();
      w.open("discharge").count("sites_weighed", stats_.sites);
      if (breakdown_.field == BreakdownField::conductor) w.count("solves", stats_.solves);
      w.integer("strike", stats_.strike)
          .count("channel", stats_.channel)
          .close();
    };
    out.timings = [this](RecordWriter& w) { w.integer("threads", options_.threads); };
    return out;
  }

 private:
  //! The target's mesh, repaired as the constraint's is, becomes the target: walkers leave a
  //! closed one from outside, one that stays open from both faces.
  void read_target(const MeshReader& read) {
    try {
      const TriangleMesh repaired = repair_mesh(read(target_mesh_name_, nullptr), {}, &target_repair_);
      ConstraintOptions side;
      side.side = target_repair_.closed ? Side::outside : Side::both;
      target_ = std::make_unique<MeshConstraint>(repaired, side, options_.spacing);
    } catch (const InvalidInput& e) {
      throw InvalidInput("`target_mesh` " + std::string(e.what()));
    }
    breakdown_.target = {};
    breakdown_.target.kind = TargetKind::mesh;
    breakdown_.target.mesh = target_.get();
  }

  BreakdownOptions breakdown_;
  BreakdownStats stats_;
  std::string target_mesh_name_;
  std::unique_ptr<const MeshConstraint> target_;
  RepairReport target_repair_;  // of the file as read: the constraint's own finds nothing to repair
};

}  // namespace

std::unique_ptr<Run> prepare_breakdown(const BreakdownRunOptions& options, const MeshReader& read, const Resumed&) {
  return std::make_unique<BreakdownRun>(options, read);
}

}  // namespace detail

}  // namespace dla
