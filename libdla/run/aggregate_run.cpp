// The aggregate's run (run.h): its options checked and the memory it needs foretold; grown,
// summed up and recorded with its fractal law. Described whole (aggregate_option_table()), so
// the CLI's command and Python's keywords are made from the description.

#include "model_runs.h"

#include "dla/core/memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dla {

const OptionTable<AggregateRunOptions>& aggregate_run_option_table() {
  static const OptionTable<AggregateRunOptions> table = [] {
    OptionTable<AggregateRunOptions> rows = nested(aggregate_option_table(), &AggregateRunOptions::aggregate);
    rows.push_back(nested(OptionTable<AggregateOptions>{rng_seed_option(&AggregateOptions::rng_seed, "Aggregate")},
                          &AggregateRunOptions::aggregate)[0]);
    return rows;
  }();
  return table;
}

namespace {

//! Bytes a monomer takes while the aggregate grows, with room to spare: its place twice, radius,
//! cluster, grid links and cells, contact and join, and the cluster it starts as. Measured: 210
//! at 10^4, 350 at 10^5 (peak resident memory less that of 10 monomers).
constexpr double kBytesPerMonomer = 400.0;

}  // namespace

void validate(const AggregateRunOptions& a) {
  require_in_ranges(aggregate_run_option_table(), a);
  validate(a.aggregate);
  validate(a.files, 3, false);
  const double monomers = static_cast<double>(a.aggregate.monomers), memory = available_memory();
  if (kBytesPerMonomer * monomers > 0.8 * memory)
    throw InvalidInput("`monomers` " + detail::with_commas(monomers) + " would take about " +
                       detail::format_number(std::round(kBytesPerMonomer * monomers / 1e8) / 10.0) +
                       " GB while growing; this machine has " + detail::format_number(std::round(memory / 1e8) / 10.0) +
                       " GB free: at most " + detail::with_commas(std::floor(0.8 * memory / kBytesPerMonomer)) +
                       " monomers fit");
}

namespace detail {

namespace {

class AggregateRun : public Run {
 public:
  explicit AggregateRun(const AggregateRunOptions& o) : options_(o.aggregate) {
    files = resolve(o.files, nullptr, false);
    total = options_.monomers;
    unit = "monomers";
    sizes_particles = true;
    // Monomers never come closer than (1 - overlap)(r_i + r_j); their radii, in spacings of 2a,
    // lie within the spread's cut.
    const double widest = options_.sizes == MonomerSizes::lognormal ? std::pow(options_.spread, 4.0)
                          : options_.sizes == MonomerSizes::normal  ? 2.0 + 4.0 * options_.spread
                                                                    : 1.0;
    const double narrowest = options_.sizes == MonomerSizes::lognormal ? std::pow(options_.spread, -4.0)
                             : options_.sizes == MonomerSizes::normal  ? 0.1
                                                                       : 1.0;
    const bool own = files.look.radius.model == RadiusModel::particle;
    solid_forecast = {options_.monomers, (1.0 - options_.overlap) * narrowest,
                      own ? 0.5 * narrowest : std::min(files.look.radius.tip_radius, files.look.radius.base_radius),
                      own ? 0.5 * widest : std::max(files.look.radius.tip_radius, files.look.radius.base_radius)};
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    Cluster grown = dla::aggregate(options_, progress, stop, &stats_);
    grown_ = grown.particles.size();
    gyration_ = radius_of_gyration(grown);
    return grown;
  }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    const FractalLaw fit = fit_joins(stats_);
    char line[320];
    std::snprintf(line, sizeof line, "aggregated %s monomers (%s) in %.2f s; R_g %.3g a",
                  with_commas(static_cast<double>(cluster.particles.size())).c_str(),
                  std::string(to_string(options_.mode)).c_str(), record.grow_seconds,
                  radius_of_gyration(cluster) / options_.monomer_radius);
    std::string summary = line;
    if (fit.dimension > 0.0) {  // clusters of 16 or more to fit
      std::snprintf(line, sizeof line, "; its clusters' law: D_f %.3g, k_f %.3g", fit.dimension, fit.prefactor);
      summary += line;
    }
    return summary;
  }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.timings = [this](RecordWriter& w) { w.integer("threads", options_.threads); };
    out.statistics = [this](RecordWriter& w) {
      w.open("aggregation")
          .counts({{"moves", stats_.moves}, {"contacts", stats_.contacts}, {"tries", stats_.tries},
                   {"joins", stats_.joins.size()}});
      if (stats_.box > 0.0) w.number("box", stats_.box);
      w.close();
    };
    out.measures = [this](RecordWriter& w) {
      // The aggregate's law: R_g of its monomers' centres in units of a, and D_f and k_f fitted
      // to the clusters its joins made (those of 16 monomers or more).
      const FractalLaw fit = fit_joins(stats_);
      w.open("aggregate")
          .count("monomers", grown_)
          .number("radius_of_gyration", gyration_)
          .number("radius_of_gyration_over_a", gyration_ / options_.monomer_radius)
          .number("fractal_dimension", fit.dimension)
          .number("prefactor", fit.prefactor)
          .close();
    };
    return out;
  }

 private:
  AggregateOptions options_;
  AggregateStats stats_;
  // What the record measures of the aggregate, kept when it is grown (record() has no cluster).
  std::size_t grown_ = 0;
  double gyration_ = 0.0;
};

}  // namespace

std::unique_ptr<Run> prepare_aggregate(const AggregateRunOptions& options, const MeshReader&, const Resumed&) {
  return std::make_unique<AggregateRun>(options);
}

}  // namespace detail

}  // namespace dla
