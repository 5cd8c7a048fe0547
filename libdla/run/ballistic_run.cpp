// The ballistic model's run (run.h): its options checked; grown, summed up and recorded.

#include "model_runs.h"

#include <cstdio>

namespace dla {

const OptionTable<BallisticRunOptions>& ballistic_run_option_table() {
  using O = BallisticOptions;
  static const OptionTable<BallisticRunOptions> table = [] {
    constexpr std::string_view group = "Ballistic";
    OptionTable<BallisticRunOptions> t = nested(
        OptionTable<O>{
            detail::particles_option(&O::particles, group),
            detail::dimensions_option(&O::dimensions, group),
            detail::spacing_option(&O::spacing, group,
                                   "distance between a particle and its parent; also the contact distance"),
            detail::seed_at_option(&O::seeds, group),
            rng_seed_option(&O::rng_seed, group),
            vector3("direction", &O::direction, group,
                    "deposition: every particle flies along x,y,z; 0,0,0: each from a random direction"),
        },
        &BallisticRunOptions::ballistic);
    const OptionTable<BallisticRunOptions> links =
        in_group(nested(links_option_table(), &BallisticRunOptions::links), group);
    t.insert(t.end(), links.begin(), links.end());
    return t;
  }();
  return table;
}

void validate(const BallisticRunOptions& b) {
  require_in_ranges(ballistic_run_option_table(), b);
  validate(b.ballistic);
  validate(b.files, b.ballistic.dimensions, false);
  detail::validate_links(b.links);
}

namespace detail {

namespace {

//! Ballistic aggregation.
class BallisticRun : public Run {
 public:
  explicit BallisticRun(const BallisticRunOptions& o) : options_(o.ballistic) {
    files = resolve(o.files, nullptr, false);
    links = o.links;
    total = options_.seeds.size() + options_.particles;
    solid_forecast = {options_.particles, 1.0};  // stuck at contact, a spacing from every particle
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

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.statistics = [this](RecordWriter& w) {
      w.open("lines")
          .counts({{"launched", stats_.launched}, {"missed", stats_.missed}, {"far_steps", stats_.far_steps},
                   {"near_steps", stats_.near_steps}})
          .close();
    };
    return out;
  }

 private:
  BallisticOptions options_;
  BallisticStats stats_;
};

}  // namespace

std::unique_ptr<Run> prepare_ballistic(const BallisticRunOptions& options, const MeshReader&, const Resumed&) {
  return std::make_unique<BallisticRun>(options);
}

}  // namespace detail

}  // namespace dla
