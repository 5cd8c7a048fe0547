// A model is one file and one registration (dla/run/run.h): this file registers a small model,
// `twig`, and nothing else names it. It must then be a command of dla3d's parser with its
// options in `dla3d options`, a function of the Python module (embedded here, so that it sees
// this process's registry), grown and recorded by either, and refused by name with a bad value.

#include "../cli/command_line.h"
#include "test_util.h"

#include "dla/core/random.h"
#include "dla/io/csv_reader.h"
#include "dla/run/run.h"

#include <gtest/gtest.h>
#include <pybind11/embed.h>
#include <pybind11/numpy.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

extern "C" PyObject* PyInit__core();  // the module's entry (python/core/module.cpp), linked in

namespace twig {

//! Which earlier particle a new one joins.
enum class Attach {
  last,  //!< the one before it: a chain, as a random walk
  any,   //!< any, at random: a random recursive tree
};
inline constexpr dla::WordTable<Attach, 2> kAttachWords{"attach", {{{Attach::last, "last"}, {Attach::any, "any"}}}};
constexpr const auto& words_of(Attach) { return kAttachWords; }

//! A twig: particles a spacing from the one they join, in a random direction.
struct TwigRunOptions {
  std::size_t twigs = 50;
  double spacing = 1.0;
  Attach attach = Attach::any;
  bool planar = false;
  std::uint64_t rng_seed = 1;
  dla::OutputOptions files;
};

const dla::OptionTable<TwigRunOptions>& twig_option_table() {
  using O = TwigRunOptions;
  static const dla::OptionTable<O> table{
      dla::integer("twigs", &O::twigs, dla::closed(1, 100000), "particles", "Twig", "particles to add to the seed"),
      dla::real("spacing", &O::spacing, dla::open_closed(0, 1000), "", "Twig", "distance to the particle joined"),
      dla::word("attach", &O::attach, "Twig", "which earlier particle a new one joins"),
      dla::flag("planar", &O::planar, "Twig", "grow in the plane z = 0"),
  };
  return table;
}

void validate(const TwigRunOptions& o) {
  dla::require_in_ranges(twig_option_table(), o);
  dla::validate(o.files, o.planar ? 2 : 3, false);
}

class TwigRun : public dla::Run {
 public:
  explicit TwigRun(const TwigRunOptions& o) : options_(o) {
    files = o.files;
    total = o.twigs + 1;
  }

  dla::Cluster grow(const dla::ProgressFn& progress, const dla::StopFlag* stop) override {
    dla::Cluster twig;
    twig.spacing = options_.spacing;
    twig.dimensions = options_.planar ? 2 : 3;
    twig.seed_count = 1;
    twig.particles.push_back({dla::Vec3::Zero(), -1, 0});
    dla::Rng rng(options_.rng_seed);
    for (std::size_t i = 0; i < options_.twigs; ++i) {
      if ((stop && *stop) || (progress && !progress(twig))) {
        twig.complete = false;
        break;
      }
      const auto joined = static_cast<std::int32_t>(options_.attach == Attach::last
                                                        ? twig.particles.size() - 1
                                                        : rng() % twig.particles.size());
      const dla::Vec3 at = twig.particles[static_cast<std::size_t>(joined)].position +
                           options_.spacing * dla::random_direction(rng, twig.dimensions);
      twig.particles.push_back({at, joined, 0});
    }
    return twig;
  }

  std::string summary(const dla::Cluster& cluster, const dla::RunRecord&) const override {
    return "grew a twig of " + std::to_string(dla::attached(cluster)) + " particles";
  }

  dla::ModelRecord own_record() const override {
    return {model, options_.rng_seed};  // its options the record writes from its table
  }

 private:
  TwigRunOptions options_;
};

std::unique_ptr<dla::Run> prepare(const TwigRunOptions& options, const dla::MeshReader&, const dla::Resumed&) {
  return std::make_unique<TwigRun>(options);
}

// The one registration.
const bool registered = (dla::register_model(dla::make_model<TwigRunOptions>(
                             "twig", "grow a random twig: particles a spacing from the one they join", prepare,
                             twig_option_table())),
                         true);

}  // namespace twig

namespace {

using dla::testing::ScratchDir;
namespace py = pybind11;

//! The message of what parsing `args` refuses, as dla3d prints it; empty if nothing is.
std::string refusal(const std::vector<std::string>& args) {
  try {
    dla::cli::parse_command_line(args);
  } catch (const dla::InvalidInput& e) {
    return dla::spell_options(e.what(), dla::OptionSpelling::cli);
  }
  return "";
}

//! Every particle but the seed a spacing from the earlier one it joined.
void expect_twig(const dla::Cluster& twig, std::size_t particles, double spacing, bool chain) {
  ASSERT_EQ(twig.particles.size(), particles);
  EXPECT_EQ(twig.particles[0].parent, -1);
  for (std::size_t i = 1; i < twig.particles.size(); ++i) {
    const dla::Particle& p = twig.particles[i];
    ASSERT_GE(p.parent, 0);
    ASSERT_LT(static_cast<std::size_t>(p.parent), i);
    if (chain) {
      EXPECT_EQ(static_cast<std::size_t>(p.parent), i - 1);
    }
    EXPECT_NEAR((p.position - twig.particles[static_cast<std::size_t>(p.parent)].position).norm(), spacing, 1e-4);
  }
}

TEST(ModelRegistry, TheModelIsInTheRegistryAndInDla3dOptions) {
  ASSERT_TRUE(twig::registered);
  ASSERT_NE(dla::find_model("twig"), nullptr);
  EXPECT_EQ(dla::models().back().name, "twig");
  const dla::cli::CommandLine line = dla::cli::parse_command_line({"options"});
  const std::string& json = line.text;
  const std::size_t model = json.find("{\"name\": \"twig\"");
  ASSERT_NE(model, std::string::npos) << json;
  const std::string twig = json.substr(model);
  // Its own options, as described, and the files' that every model has.
  EXPECT_NE(twig.find("\"name\": \"--attach\""), std::string::npos);
  EXPECT_NE(twig.find("\"choices\": [\"last\", \"any\"]"), std::string::npos);
  const std::size_t range = twig.find("\"min\": 1, \"max\": ");
  ASSERT_NE(range, std::string::npos) << twig;
  EXPECT_EQ(std::strtod(twig.c_str() + range + 17, nullptr), 100000.0);
  EXPECT_NE(twig.find("\"name\": \"--planar\""), std::string::npos);
  EXPECT_NE(twig.find("\"name\": \"--formats\""), std::string::npos);
  EXPECT_NE(twig.find("\"group\": \"Twig\""), std::string::npos);
}

TEST(ModelRegistry, TheCliParserGrowsItAndTheRecordNamesItsOptions) {
  ScratchDir dir;
  const std::string prefix = dir / "twig";
  const dla::cli::CommandLine line = dla::cli::parse_command_line(
      {"twig", "--twigs", "40", "--attach", "last", "--spacing", "2.5", "-o", prefix, "--formats", "csv,json,ply"});
  ASSERT_EQ(&line.run.model(), dla::find_model("twig"));
  const auto run = dla::prepare_run(line.run);
  dla::RunRecord record;
  const dla::Cluster grown = dla::grow_recorded(*run, {}, nullptr, record);
  dla::write_run(*run, grown, record);
  expect_twig(dla::read_csv(prefix + ".csv"), 41, 2.5, true);
  const std::string json = dla::testing::read_file(prefix + ".json");
  EXPECT_NE(json.find("\"model\": \"twig\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"attach\": \"last\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"twigs\": 40"), std::string::npos) << json;
  EXPECT_FALSE(dla::testing::read_file(prefix + ".ply").empty());
}

TEST(ModelRegistry, TheCliRefusesABadValueByName) {
  EXPECT_EQ(refusal({"twig", "--twigs", "0"}), "--twigs 0 is not in [1, 100000]");
  EXPECT_EQ(refusal({"twig", "--spacing", "0"}), "--spacing 0 is not in (0, 1000]");
  EXPECT_EQ(refusal({"twig", "--attach", "sideways"}), "--attach 'sideways' is not one of last, any");
  EXPECT_EQ(refusal({"twig", "--planar", "--formats", "svg"}), "");  // in the plane, the plane's files
  EXPECT_NE(refusal({"twig", "--formats", "svg"}), "");              // not in 3D
}

TEST(ModelRegistry, PythonGrowsItAsAFunctionAndRefusesABadValueByName) {
  // The module made in this process, so that it reads the registry the test registered in: the
  // package's import finds it among the modules already imported, before the built one.
  py::scoped_interpreter python;
  py::module_::import("sys").attr("modules")["dla3d._core"] = py::reinterpret_steal<py::module_>(PyInit__core());
  py::module_::import("sys").attr("path").attr("insert")(0, DLA_PYTHON_DIR);
  const py::module_ dla3d = py::module_::import("dla3d");
  const py::object result =
      dla3d.attr("twig")(py::arg("twigs") = 30, py::arg("planar") = true, py::arg("attach") = "any");
  const auto positions = result.attr("positions").cast<py::array_t<double>>();
  ASSERT_EQ(positions.shape(0), 31);
  for (py::ssize_t i = 0; i < positions.shape(0); ++i) EXPECT_EQ(positions.at(i, 2), 0.0);  // planar
  const std::string doc = dla3d.attr("twig").attr("__doc__").cast<std::string>();
  EXPECT_NE(doc.find("Grow a random twig"), std::string::npos) << doc;
  try {
    dla3d.attr("twig")(py::arg("twigs") = 0);
    ADD_FAILURE() << "twigs=0 grew";
  } catch (const py::error_already_set& e) {
    EXPECT_TRUE(e.matches(PyExc_ValueError));
    EXPECT_NE(std::string(e.what()).find("twigs=0 is not in [1, 100000]"), std::string::npos) << e.what();
  }
}

}  // namespace
