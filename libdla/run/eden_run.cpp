// The Eden model's run (run.h): its options checked and its mask read; grown, summed up and
// recorded.

#include "model_runs.h"

#include "dla/core/input_file.h"

#include <cstdio>

namespace dla {

namespace {
//! Where `dimensions` has its default, for its description.
struct Plane {
  int dimensions = 2;
};
}  // namespace

const OptionTable<EdenRunOptions>& eden_run_option_table() {
  using O = EdenRunOptions;
  static const OptionTable<O> table = [] {
    constexpr std::string_view group = "Eden";
    OptionTable<O> t{
        with_short_name(nested(OptionTable<EdenOptions>{integer("sites", &EdenOptions::sites, closed(1, 2e9), "",
                                                                group, "sites at most, the seed included")},
                               &O::eden)[0],
                        "n"),
        override_of(detail::dimensions_option(&Plane::dimensions, group,
                                              "2, or 3 for a cubic lattice: the lattice's default there"),
                    &O::dimensions),
        override_of(word("lattice", &EdenOptions::lattice, group,
                         "the lattice (the number: neighbours); default square4, with --dimensions 3 cubic6"),
                    &O::lattice),
    };
    const auto add = [&t](const OptionTable<O>& rows) { t.insert(t.end(), rows.begin(), rows.end()); };
    add(nested(eden_option_table(), &O::eden));
    // A painted mask goes to it as a file; a page may give it only the words (the choices).
    DescribedOption<O> mask = with_paint_role(
        parsed<O>(
            "mask", OptionKind::text, "A|B|C|D|FILE", group,
            "drop: A, B, C or D (the paper's masks: 4, 8, 12 and 24 sites around), or a file drawing one",
            [](O& o, const std::string& words) {
              const bool preset = words.size() == 1 && words.find_first_of("ABCD") == 0;
              if (preset) o.eden.mask = parse_word<EdenMask>(words);
              o.mask_file = preset ? "" : words;  // read, and checked, when the run is prepared
            },
            [](const O& o) { return o.mask_file.empty() ? std::string(to_string(o.eden.mask)) : o.mask_file; }),
        PaintRole::mask);
    mask.about.choices = words_list<EdenMask>();
    add(OptionTable<O>{mask});
    add(nested(
        OptionTable<EdenOptions>{
            integer("mask_threshold", &EdenOptions::mask_threshold, closed(1, 4912), "sites", group,
                    "drop: occupied mask sites a site needs, 1 to the mask's size"),
            detail::spacing_option(&EdenOptions::spacing, group, "distance between neighbouring sites"),
            rng_seed_option(&EdenOptions::rng_seed, group),
        },
        &O::eden));
    add(in_group(nested(links_option_table(true), &O::links), group));
    return t;
  }();
  return table;
}

EdenOptions eden_options(const EdenRunOptions& e) {
  EdenOptions o = e.eden;
  if (e.lattice) o.lattice = *e.lattice;
  else if (e.dimensions) o.lattice = *e.dimensions == 3 ? Lattice::cubic6 : Lattice::square4;
  return o;
}

void validate(const EdenRunOptions& e) {
  require_in_ranges(eden_run_option_table(), e);
  if (e.lattice && e.dimensions && dimensions_of(*e.lattice) != *e.dimensions)
    throw InvalidInput("`lattice` " + std::string(to_string(*e.lattice)) + " is not a lattice in " +
                       std::to_string(*e.dimensions) + "D");
  const EdenOptions eden = eden_options(e);
  validate(e.files, dimensions_of(eden.lattice), false);
  const EdenOptions unset;
  const bool masked = !e.mask_file.empty() || !eden.mask_offsets.empty() || eden.mask != unset.mask ||
                      eden.mask_threshold != unset.mask_threshold;
  if (eden.mode == EdenMode::perimeter && masked) throw InvalidInput("`mask` and `mask_threshold` are for `mode` drop");
  if (e.mask_file.empty()) validate(eden);
  validate(e.links);
}

namespace detail {

namespace {

//! An Eden cluster on a lattice, its mask a preset or drawn in a file.
class EdenRun : public Run {
 public:
  explicit EdenRun(const EdenRunOptions& o) : options_(eden_options(o)) {
    files = resolve(o.files, nullptr, false);
    links = o.links;
    unit = "sites";
    total = options_.sites;
    solid_forecast = {options_.sites, 1.0};  // lattice sites, a spacing apart
    if (!o.mask_file.empty()) {
      const std::string text = read_input_file(o.mask_file, "mask");
      try {
        options_.mask_offsets = parse_mask(text);
        validate(options_);
      } catch (const InvalidInput& e) {
        throw InvalidInput(o.mask_file + ": " + e.what());
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

  //! The lattice the dimensions give.
  void put_resolved(RunOptions& options) const override {
    EdenRunOptions& o = options.get<EdenRunOptions>();
    o.lattice = options_.lattice;
    o.dimensions = dimensions_of(options_.lattice);
  }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    if (options_.mode == EdenMode::drop)
      out.resolved = [this](RecordWriter& w) {
        std::string sites = "[";
        for (const std::array<int, 3>& site : eden_mask(options_))
          sites += (sites.size() > 1 ? ", [" : "[") + std::to_string(site[0]) + ", " + std::to_string(site[1]) + ", " +
                   std::to_string(site[2]) + ']';
        w.raw("mask_sites", sites + "]");
      };
    return out;
  }

 private:
  EdenOptions options_;
};

}  // namespace

std::unique_ptr<Run> prepare_eden(const EdenRunOptions& options, const MeshReader&, const Resumed&) {
  return std::make_unique<EdenRun>(options);
}

}  // namespace detail

}  // namespace dla
