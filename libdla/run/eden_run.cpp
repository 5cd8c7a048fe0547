// The Eden model's run (run.h): its options checked and its mask read; grown, summed up and
// recorded.

#include "model_runs.h"

#include "dla/core/input_file.h"

#include <cstdio>

namespace dla {

void validate(const EdenRunOptions& e) {
  validate(e.files, dimensions_of(e.eden.lattice), false);
  const EdenOptions unset;
  const bool masked = !e.mask_file.empty() || !e.eden.mask_offsets.empty() || e.eden.mask != unset.mask ||
                      e.eden.mask_threshold != unset.mask_threshold;
  if (e.eden.mode == EdenMode::perimeter && masked) throw InvalidInput("`mask` and `mask_threshold` are for `mode` drop");
  if (e.mask_file.empty()) validate(e.eden);
  validate(e.links);
}

namespace detail {

namespace {

//! An Eden cluster on a lattice, its mask a preset or drawn in a file.
class EdenRun : public Run {
 public:
  explicit EdenRun(const EdenRunOptions& o) : options_(o.eden), mask_file_(o.mask_file) {
    files = resolve(o.files, nullptr, false);
    links = o.links;
    unit = "sites";
    total = options_.sites;
    solid_forecast = {options_.sites, 1.0};  // lattice sites, a spacing apart
    if (!mask_file_.empty()) {
      const std::string text = read_input_file(mask_file_, "mask");
      try {
        options_.mask_offsets = parse_mask(text);
        validate(options_);
      } catch (const InvalidInput& e) {
        throw InvalidInput(mask_file_ + ": " + e.what());
      }
    }
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override { return dla::eden(options_, progress, stop); }

  std::vector<Link> make_links(const Cluster& cluster, const StageWatch& watch) const override {
    return links.lattice ? lattice_links(cluster, options_.lattice, threads, watch) : Run::make_links(cluster, watch);
  }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char line[256];
    std::snprintf(line, sizeof line, "grew %s sites on a %s lattice in %.2f s%s; bounding radius %.1f",
                  with_commas(static_cast<double>(cluster.particles.size())).c_str(),
                  std::string(to_string(options_.lattice)).c_str(), record.grow_seconds,
                  cluster.complete && cluster.particles.size() < options_.sites ? " (then no site could stick)" : "",
                  bounding_radius(cluster));
    return line;
  }

  ModelRecord record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.options = [this](RecordWriter& w) { record_options(w); };
    return out;
  }

 private:
  void record_options(RecordWriter& out) const {
    const EdenOptions& o = options_;
    out.count("sites", o.sites)
        .text("lattice", to_string(o.lattice))
        .integer("dimensions", dimensions_of(o.lattice))
        .text("mode", to_string(o.mode));
    if (o.mode == EdenMode::drop) {
      if (mask_file_.empty()) out.text("mask", to_string(o.mask));
      else out.text("mask_from", mask_file_);
      std::string sites = "[";
      for (const std::array<int, 3>& site : eden_mask(o))
        sites += (sites.size() > 1 ? ", [" : "[") + std::to_string(site[0]) + ", " + std::to_string(site[1]) + ", " +
                 std::to_string(site[2]) + ']';
      out.raw("mask_sites", sites + "]").integer("mask_threshold", o.mask_threshold);
    }
    out.number("seed_radius", o.seed_radius).number("spacing", o.spacing);
    if (links.any()) out.text("links", to_string(links));
  }

  EdenOptions options_;
  std::string mask_file_;
};

}  // namespace

std::unique_ptr<Run> prepare_eden(const EdenRunOptions& options, const MeshReader&, const Resumed&) {
  return std::make_unique<EdenRun>(options);
}

}  // namespace detail

}  // namespace dla
