// The CLI's property test: random command lines drawn from every option of `dla3d --help`, each
// value valid, at an edge or invalid, run with a small particle count and a time bound. Whatever
// the user types:
//   - dla3d exits within the bound (no hang) and by exit(), never by a signal (no crash; under
//     the sanitizers, a report ends the run with a multi-line stderr, which fails below);
//   - exit 0 leaves the files --formats asks for and no other, each read back whole: the CSV
//     and the PLY trees (with the JSON, of its counts, and the CSV's branches at most a
//     spacing), the JSON whole, the STL, OBJ and 3MF closed meshes (the 3MF read by lib3mf),
//     the glb passed by the glTF-Validator where it is installed, the POV-Ray scene rendered
//     by POV-Ray (which the setup installs: its absence fails the run by name);
//   - exit 2 (bad input) prints one line and writes no file;
//   - exit 1 (growth or I/O failed) ends with one error line, and any files are marked
//     incomplete.
// Every model the library registers (dla/run/run.h) has a share of the command lines: a
// quarter are `dla3d colonize` ones, an eighth `dla3d eden` ones and a sixteenth each `dla3d
// drop`, `dla3d ballistic`, `dla3d breakdown`, `dla3d aggregate` and `dla3d frames` ones, each drawn from its
// own table and the Output and Look options.
// DLA_PROPERTY_RUNS sets the number of command lines (default 150, about a minute;
// CliProperty.Long, in the full tier, runs 1,000) and DLA_PROPERTY_SEED the generator's seed.
// Every option and model added to dla3d must join the tables below: the test fails on an
// option of --help, or a model, it does not know.

#include "cli_util.h"
#include "clients.h"
#include "mesh_util.h"
#include "solid_check.h"
#include "test_util.h"

#include "dla/io/mesh_writers.h"
#include "dla/io/checkpoint.h"
#include "dla/io/csv_reader.h"
#include "dla/io/csv_writer.h"
#include "dla/models/dla.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/shapes.h"
#include "dla/run/presets.h"
#include "dla/run/run.h"

#include "tree_check.h"

#include <Model/COM/NMR_DLLInterfaces.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

//! Every option of --help with values to draw from: valid ones first, then edges and faults.
//! A flag with no values is a switch.
//! The draws an option's description gives: each choice and one word that is none; inside the
//! range, at each end and just past it, and its special value.
std::vector<std::string> described_draws(const OptionDescription& about) {
  std::vector<std::string> draws;
  for (std::string_view choice : about.choices) draws.emplace_back(choice);
  if (about.kind == OptionKind::word) draws.push_back("none-of-these");
  if (about.range) {
    const Range& r = *about.range;
    const bool whole = about.kind == OptionKind::integer;
    // A step past an end that "%g" still tells from the end itself.
    const auto past = [&](double end, double sign) {
      return whole ? end + sign : end + sign * std::max(std::abs(end) * 1e-3, 1e-3);
    };
    for (double value : {r.min, r.max, whole ? std::round((r.min + r.max) / 2) : (r.min + r.max) / 2,
                         past(r.min, -1), past(r.max, 1)})
      draws.push_back(detail::format_number(value));
    if (about.special) draws.push_back(detail::format_number(about.special->value));
  }
  // A text form: a value of its shape, one of another shape, and none.
  std::string sample;
  for (std::size_t n = 0, numbers = std::count(about.form.begin(), about.form.end(), ',') + 1;
       (about.kind == OptionKind::vector || about.kind == OptionKind::points) && n < numbers; ++n)
    sample += (n ? "," : "") + std::to_string(n) + ".25";
  if (about.kind == OptionKind::colour) sample = "ff8000,0.5";
  if (!sample.empty()) draws.push_back(sample);
  if (about.kind == OptionKind::file) draws.push_back("missing.file");
  if (!about.form.empty()) draws.insert(draws.end(), {"x", "''"});
  return draws;
}

//! `table` with the draws of each described option added to its own.
std::map<std::string, std::vector<std::string>> with_described(std::map<std::string, std::vector<std::string>> table,
                                                               const std::vector<OptionDescription>& described) {
  for (const OptionDescription& about : described) {
    std::vector<std::string>& values = table[cli_flag(about.name)];
    for (std::string& draw : described_draws(about)) values.push_back(std::move(draw));
    if (about.kind == OptionKind::flag && !about.negation.empty()) table[cli_flag(about.negation)];
  }
  return table;
}

//! `table` with `--preset` drawn from each preset of `model`, `list` and a name it has not.
std::map<std::string, std::vector<std::string>> with_presets(std::map<std::string, std::vector<std::string>> table,
                                                             std::string_view model) {
  std::vector<std::string>& values = table["--preset"];
  for (const Preset* preset : presets_of(model)) values.emplace_back(preset->name);
  values.insert(values.end(), {"list", "nope", "''"});
  return table;
}

template <class Options>
std::vector<OptionDescription> descriptions(const OptionTable<Options>& table) {
  std::vector<OptionDescription> described;
  for (const DescribedOption<Options>& option : table) described.push_back(option.about);
  return described;
}

const std::map<std::string, std::vector<std::string>>& option_table() {
  static const std::map<std::string, std::vector<std::string>> table = with_presets(with_described(with_described({
      {"--particles", {"0", "1", "40", "150", "-1", "abc", "1e3", "99999999999999999999", "''"}},
      {"--spacing", {"1", "0.5", "1e-6", "1e6", "1e-25", "1e25", "1e-100", "1e100", "0", "-1", "inf", "nan", "1e-300", "1e300",
                     "4.9e-324", "x"}},
      {"--stickiness", {"1", "0.3", "1e-4", "0", "1.5", "nan", "1e-300", "-0"}},
      {"--dimensions", {"2", "3", "1", "4", "-3", "x"}},
      {"--seed-at", {"0,0,0", "6,0,0", "-6,0,0", "1e-7,0,0", "0,0,1", "1e12,0,0", "nan,0,0", "1,2", "a,b,c", "''"}},
      {"--rng-seed", {"0", "1", "7", "18446744073709551615", "-1", "x"}},
      {"--min-step", {"0.5", "1", "0.01", "0", "2", "1e-300", "nan"}},
      {"--index", {"grid", "kdtree", "brute", "octree"}},
      {"--links", {"2", "1.5,3", "4,8", "1", "0", "-1", "2,0", "2,65", "101", "lattice", "x", "2,"}},
      {"--threads", {"1", "2", "3", "0", "300", "-1"}},
      {"--stl", {"box.off", "ball.stl", "paint.ply", "missing.stl", "noise.stl", "out.csv", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--mesh", {"ball.stl", "box.off", "paint.ply", "missing.stl", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--side", {"inside", "outside", "both", "surface", "sideways"}},
      {"--shell", {"3", "1", "2.5", "1000", "0.5", "0", "nan", "x"}},
      {"--constraint", {"reject", "clip", "bend"}},
      {"--seeds", {"1", "2", "3", "all", "0", "-1", "1000", "x"}},
      {"--seed-paint", {"red", "ff0000", "'#ff0000,0.5'", "red,0", "blue", "pink", "red,1", "red,x", "''"}},
      {"--seed-mesh", {"rod.stl", "box.off", "ball.stl", "missing.stl", "noise.stl", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--text", {"DLA", "'A B'", "O", "'L\\nI'", "''", "' '"}},
      {"--font", {"/usr/share/fonts/truetype/dejavu/DejaVuSerif-Bold.ttf", "missing.ttf", "noise.stl", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--scene-mesh", {}},
      {"--no-scene-mesh", {}},
      {"--spawn", {"sphere", "disk", "box", "inside", "radial", "surface", "cube"}},
      {"--spawn-axis", {"x", "y", "z", "w"}},
      {"--disk-radius", {"0.25", "1", "1000", "0", "1e300", "nan"}},
      {"--box", {"-40,-40,-40,40,40,40", "-3,-3,-3,3,3,3", "1,1,1,0,0,0", "0,0,0,1", "-1e300,0,0,1,1,1"}},
      {"--drift", {"0,0,0", "0,-0.3,0", "0.2,0,0", "0,0.9,0", "0,0,2", "nan,0,0", "0,0,0.5"}},
      {"--rotate", {"z,30", "y,-90", "x,36000", "z,0", "z,36001", "w,10", "z", "z,nan", "y,1e300"}},
      {"--fill", {"0.3", "0.05", "1", "0", "1.5", "-0.1", "nan"}},
      {"--seed-surface", {}},
      {"--fill-distance", {"3", "0.5", "1000", "0.1", "2000", "inf"}},
      {"--output", {"out", "'with space'", "'we\"ird'", "'back\\slash'", "sub/out", "''", "dir/"}},
      {"--ply-format", {"binary", "ascii", "text"}},
      {"--binary", {}},
      {"--formats", {"pov,csv,ply,json", "glb,obj,tips,json", "csv,svg,json", "png,csv,json", "html,json", "json", "''",
                     "spheres,csv,json", "mstm,ddscat,json",
                     "pov,jpg", "glb,,obj", "stl,json", "3mf,vdb,json", "solid-glb,solid-obj,csv,json", "stl,3mf"}},
      {"--solid-shape", {"branches", "spheres", "cubes", "blobs"}},
      {"--solid-voxel", {"0", "0.2", "0.05", "0.001", "100", "-1", "nan"}},
      {"--solid-smooth", {"0", "0.4", "1", "100", "-1", "nan"}},
      {"--solid-adaptivity", {"0", "0.5", "1", "2", "-0.1", "nan"}},
      {"--print-size", {"0", "60", "0.001", "10000", "10001", "-1", "nan"}},
      {"--min-wall", {"0.8", "0", "2", "100", "101", "-1", "nan"}},
      {"--solid-join", {}},
      {"--solid-memory", {"0", "200", "1", "0.5", "1e10", "nan"}},
      {"--png-scale", {"2", "0.5", "64", "1e-6", "0", "65", "nan", "-1"}},
      {"--png-bands", {"8", "1", "1000000", "0", "-1", "x"}},
      {"--radius", {"taper", "pipe", "boundary", "seed-distance", "uniform", "wavy"}},
      {"--base-radius", {"0.5", "0.001", "1000", "0", "-1", "1e300"}},
      {"--tip-radius", {"0.25", "0.001", "1000", "0", "-1", "nan"}},
      {"--pipe-exponent", {"2", "3", "1", "10", "0.5", "nan"}},
      {"--color-by", {"age", "depth", "seed", "distance", "current", "none", "hue"}},
      {"--look", {"branches", "blob", "glow", "cloud"}},
      {"--tube-sides", {"8", "3", "64", "2", "65", "-1"}},
      {"--tube-tolerance", {"0", "0.5", "10", "-1", "11", "nan"}},
      {"--tube-min-branch", {"1", "16", "1000", "0", "1001", "x"}},
      {"--uv-scale", {"0", "2.5", "1e-9", "-1", "1e10", "nan"}},
      {"--lod", {"0", "2", "8", "-1", "9", "x"}},
      // Up to 3: the shape file of a few thousand particles at 50 would take gigabytes.
      {"--ddscat-resolution", {"1", "3", "0", "51", "x"}},
      {"--leaf", {"leaf.glb", "leaf.glb", "nested/leaf.glb", "noise.stl", "missing.glb", "''", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.glb"}},
      {"--instances", {"tips", "all", "some"}},
      {"--tips-within", {"2", "0", "1e300", "-1", "nan"}},
      {"--tips-every", {"1", "3", "1000000", "0", "1000001", "x"}},
      {"--tips-exclude-paint", {"red", "ff0000,0.2", "blue", "mauve", "red,1"}},
      {"--up", {"x", "y", "z", "w"}},
      {"--quiet", {}},
      {"--stream", {"live.bin", "live.bin", "nofolder/live.bin", "dir", "''"}},
      {"--checkpoint", {"run.ck", "nofolder/run.ck"}},
      {"--checkpoint-every", {"0", "0.5", "60", "-1", "nan", "inf"}},
      {"--resume", {"saved.ck", "missing.ck", "out.csv", "noise.stl", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.ck"}},
      {"--help", {}},
      {"--version", {}},
  }, descriptions(dla_run_option_table())), descriptions(output_option_table())), "grow");
  return table;
}

//! `dla3d colonize`'s own options, drawn as the table's; its Output and Look options are the
//! table's.
//! `table` with the mesh controls drop and colonize share with DLA: seeds (roots) on the mesh,
//! and DLA's --fill and --shell, which they refuse.
std::map<std::string, std::vector<std::string>> with_mesh_seeds(std::map<std::string, std::vector<std::string>> table) {
  table.insert({{"--seeds", {"2", "all", "1", "0", "-1", "x"}},
                {"--seed-surface", {}},
                {"--seed-paint", {"red", "ff0000", "pink", "''"}},
                {"--seed-mesh", {"rod.stl", "box.off", "missing.stl", "noise.stl"}},
                {"--fill", {"0.5", "x"}},
                {"--shell", {"3", "0"}}});
  return table;
}

const std::map<std::string, std::vector<std::string>>& colonize_table() {
  static const std::map<std::string, std::vector<std::string>> table = with_presets(with_described(with_mesh_seeds({
      {"--max-nodes", {"30", "200", "1", "0", "-5", "3e9", "x"}},
      {"--max-iterations", {"50", "1000", "1", "0", "-1"}},
      {"--spacing", {"1", "0.5", "1e-6", "1e6", "1e-25", "1e25", "0", "-1", "nan", "1e-300", "1e100"}},
      {"--kill-distance", {"2", "1.5", "1", "0.5", "1e7", "nan"}},
      {"--influence", {"8", "3", "inf", "1", "-1", "nan"}},
      {"--venation", {"open", "closed", "closed", "shut"}},
      {"--noise", {"0.3,4", "1,1", "0,8", "11,1", "1,0", "1", "nan,1"}},
      {"--tropism", {"0,0.3,0", "0,-1,0", "0,0,0", "11,0,0", "nan,0,0", "1,2"}},
      {"--dimensions", {"3", "2", "1", "x"}},
      {"--rng-seed", {"1", "7", "18446744073709551615", "-1"}},
      {"--attractors", {"300", "2000", "1", "0", "-3", "200000000", "x"}},
      {"--attractors-in", {"sphere", "box", "mesh", "surface", "cone"}},
      {"--attractors-from", {"points.csv", "points.ply", "out.csv", "ball.stl", "noise.stl", "missing.csv", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--attractor-center", {"0,0,0", "10,0,0", "0,0,5", "1e300,0,0", "nan,0,0"}},
      {"--attractor-radius", {"20", "5", "1e-3", "0", "-1", "1e300", "inf"}},
      {"--attractor-box", {"-20,-20,-20,20,20,20", "0,0,0,10,10,0", "1,1,1,0,0,0", "0,0,0,1"}},
      {"--attractor-falloff", {"1", "0", "100", "-1", "nan"}},
      {"--attractor-paint", {"red", "ff0000,0.5", "blue", "pink", "red,1", "''"}},
      {"--root-at", {"0,-20,0", "5,5,0", "0,0,0", "1e300,0,0", "a,b,c"}},
      {"--roots", {"3", "1", "20", "0", "-2"}},
      {"--roots-in", {"sphere", "mesh", "surface", "cube"}},
      {"--roots-scale", {"1.5", "1", "0.01", "100", "0", "-1", "nan", "1e300"}},
      {"--stl", {"ball.stl", "box.off", "paint.ply", "missing.stl", "noise.stl"}},
      {"--collide", {"ball.stl", "box.off", "missing.stl", "noise.stl", "out.csv", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--collision", {"push", "stick", "bounce"}},
  }), descriptions(colonize_option_table())), "colonize");
  return table;
}

//! `dla3d eden`'s own options, drawn as the table's; its Output and Look options are the
//! table's.
const std::map<std::string, std::vector<std::string>>& eden_table() {
  static const std::map<std::string, std::vector<std::string>> table = with_described({
      {"--sites", {"40", "300", "1", "0", "-5", "3e9", "x"}},
      {"--dimensions", {"2", "3", "1", "x"}},
      {"--lattice", {"square4", "hex", "square8", "cubic6", "cubic18", "cubic26", "square5"}},
      {"--mode", {"drop", "perimeter", "random"}},
      {"--mask", {"B", "mask.txt", "A", "C", "D", "missing.txt", "noise.stl", "E", "''", "folder.stl", "pipe.stl", "zero.stl", "empty.stl", "cut.stl"}},
      {"--mask-threshold", {"1", "2", "3", "0", "-1", "200", "x"}},
      {"--seed-radius", {"2", "0", "100", "-1", "101", "nan", "inf"}},
      {"--spacing", {"1", "0.5", "1e-6", "1e6", "1e-25", "1e25", "0", "-1", "nan", "1e-300", "1e100"}},
      {"--rng-seed", {"1", "7", "18446744073709551615", "-1"}},
      {"--links", {"lattice", "lattice", "1.5,2", "0", "x"}},
  }, descriptions(eden_option_table()));
  return table;
}

//! The options `dla3d drop` and `dla3d ballistic` share with DLA, with `extra` (their own).
std::map<std::string, std::vector<std::string>> seeded_table(std::map<std::string, std::vector<std::string>> extra) {
  extra.insert({
      {"--particles", {"40", "300", "0", "-5", "3e9", "x"}},
      {"--dimensions", {"2", "3", "1", "x"}},
      {"--spacing", {"1", "0.5", "1e-6", "1e6", "1e-25", "1e25", "0", "-1", "nan", "1e-300"}},
      {"--seed-at", {"0,0,0", "3,0,0", "0,0,5", "1e12,0,0", "nan,0,0", "x"}},
      {"--rng-seed", {"1", "7", "18446744073709551615", "-1"}},
      {"--links", {"2", "3,2", "1", "0", "lattice", "x"}},
  });
  return extra;
}

//! `dla3d drop`'s own options, drawn as the table's; its Output and Look options are the
//! table's.
const std::map<std::string, std::vector<std::string>>& drop_table() {
  static const std::map<std::string, std::vector<std::string>> table = with_presets(with_described(with_mesh_seeds(seeded_table({
      {"--stickiness", {"0.5", "1", "1e-4", "0", "2", "nan"}},
      {"--zone", {"box", "ball", "mesh", "cone"}},
      {"--zone-radius", {"30", "3", "1e6", "0.5", "-1", "1e300", "nan"}},
      {"--zone-margin", {"4", "0.5", "1e6", "0.1", "-1", "inf"}},
      {"--zone-box", {"-20,-20,-20,20,20,20", "-5,-5,0,5,5,0", "1,1,1,0,0,0", "1,2", "nan,0,0,1,1,1"}},
      {"--drop", {"circle", "same:5", "offset:10,3", "uniform", "same:0", "offset:5", "offset:5,0", "same:1e10", "rain"}},
      {"--stl", {"ball.stl", "box.off", "paint.ply", "missing.stl", "noise.stl"}},
      {"--side", {"inside", "outside", "both", "up"}},
      {"--constraint", {"clip", "reject", "bounce"}},
      {"--scene-mesh", {}},
      {"--no-scene-mesh", {}},
  })), descriptions(drop_option_table())), "drop");
  return table;
}

//! `dla3d ballistic`'s own options, drawn as the table's; its Output and Look options are the
//! table's.
const std::map<std::string, std::vector<std::string>>& ballistic_table() {
  static const std::map<std::string, std::vector<std::string>> table = seeded_table({
      {"--direction", {"0,-1,0", "1,1,0", "0,0,-1", "0,0,0", "1e-300,0,0", "inf,0,0", "x"}},
  });
  return table;
}

//! `dla3d breakdown`'s options: DLA's walk, mesh and spawn options, drawn from DLA's values, and
//! the Discharge group's own; its Output and Look options are the table's.
const std::map<std::string, std::vector<std::string>>& breakdown_table() {
  static const std::map<std::string, std::vector<std::string>> table = [] {
    std::map<std::string, std::vector<std::string>> t = {
        {"--eta", {"2", "0.5", "3", "0", "10", "1", "-1", "10.5", "nan", "x"}},
        {"--field", {"conductor", "charges", "walkers", "conductor", "both", ""}},
        {"--walkers", {"4", "0", "1", "4096", "-1", "4097", "x"}},
        {"--target-point", {"0,-15,0", "20,0,0", "0,0,0", "0.5,0,0", "0,0,4", "nan,0,0", "1e300,0,0", "x"}},
        {"--target-plane", {"y=-15", "x,12", "z=-8", "y=0", "w=3", "y=nan", "y", "=4"}},
        {"--target-mesh", {"rod.stl", "ball.stl", "box.off", "noise.stl", "missing.stl", "folder.stl", "empty.stl", "cut.stl"}},
        {"--stop-at-strike", {}},
        {"--no-stop-at-strike", {}},
        {"--particles", {"40", "150", "0", "-5", "x"}},
    };
    for (const char* shared : {"--spacing", "--stickiness", "--dimensions", "--seed-at", "--rng-seed", "--min-step",
                               "--links", "--threads", "--stl", "--mesh", "--text", "--font", "--side", "--shell",
                               "--constraint", "--seeds", "--seed-surface", "--seed-paint", "--seed-mesh", "--scene-mesh",
                               "--no-scene-mesh", "--fill", "--spawn", "--spawn-axis", "--disk-radius", "--box"})
      t.emplace(shared, option_table().at(shared));
    return with_presets(with_described(t, descriptions(breakdown_option_table())), "breakdown");
  }();
  return table;
}

//! `dla3d aggregate`'s options, all described; the monomers' count is drawn by hand, as the
//! description's largest (10^8) would take hours, not a fault.
const std::map<std::string, std::vector<std::string>>& aggregate_table() {
  static const std::map<std::string, std::vector<std::string>> table = [] {
    std::map<std::string, std::vector<std::string>> t = with_described({}, descriptions(aggregate_run_option_table()));
    t["--monomers"] = {"40", "150", "1", "2", "0", "100000001", "-5", "2.5", "x"};
    return t;
  }();
  return table;
}

//! `dla3d frames`' own option, drawn as the table's; its Output and Look options are the
//! table's.
const std::map<std::string, std::vector<std::string>>& frames_table() {
  static const std::map<std::string, std::vector<std::string>> table = {
      {"--count", {"3", "1", "0", "100001", "-2", "x", "2.5"}},
      {"--links", {"2", "3,2", "0", "lattice", "x"}},
  };
  return table;
}

//! The long option names `dla3d [colonize] --help` lists.
std::set<std::string> options_of_help(const ScratchDir& dir, const std::string& subcommand = "") {
  const std::string command = "cd '" + dir.path().string() + "' && '" DLA3D_PATH "' " + subcommand + " --help > help.txt";
  EXPECT_EQ(std::system(command.c_str()), 0);
  const std::string help = read_file(dir / "help.txt");
  std::filesystem::remove(dir / "help.txt");
  std::set<std::string> names;
  const std::regex option("(^|[ ,!])(--[a-z][a-z0-9-]*)");
  for (auto it = std::sregex_iterator(help.begin(), help.end(), option); it != std::sregex_iterator(); ++it)
    names.insert((*it)[2]);
  return names;
}

//! Inputs the command lines name: meshes (one painted), a file of noise, point files, a leaf, a
//! checkpoint to resume.
void make_inputs(const ScratchDir& dir) {
  write_stl(make_sphere(Vec3::Zero(), 12.0, 10, 20), dir / "ball.stl");
  std::filesystem::copy_file(TEST_DATA_DIR "/open_box.off", dir / "box.off");
  TriangleMesh painted = make_sphere(Vec3::Zero(), 12.0, 10, 20);
  for (const Vec3& v : painted.vertices) painted.colors.push_back(v.z() > 6.0 ? Vec3(1, 0, 0) : Vec3(1, 1, 1));
  std::ofstream(dir / "paint.ply") << testing::painted_ply(painted);
  write_stl(make_open_can(Vec3(0, 0, 6), 2.0, 10.0, 12), dir / "rod.stl");
  std::string noise;
  for (int i = 0; i < 500; ++i) noise += static_cast<char>((i * 7919 + 13) % 251);
  std::ofstream(dir / "noise.stl", std::ios::binary) << noise;
  std::filesystem::copy_file(DLA_EXAMPLES_DIR "/leaf.glb", dir / "leaf.glb");
  std::ofstream(dir / "out.csv") << "id,x,y,z,parent,seed\n0,0,0,0,-1,0\n";
  std::ofstream(dir / "points.csv") << "1,2,3\n-4,5,0\n6,-7,8\n0,-9,0\n3,3,3\n";
  std::ofstream(dir / "mask.txt") << "; the 3x3 block\nxxx\nxox\nxxx\n";
  // Special files, for every file option: a folder, a FIFO (which a reader would wait on), a
  // device that never ends, an empty file.
  std::filesystem::create_directory(dir / "folder.stl");
  EXPECT_EQ(mkfifo((dir / "pipe.stl").c_str(), 0644), 0);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
  std::ofstream(dir / "empty.stl").flush();
  // Truncated files: each format's first part, saying more than follows.
  const auto cut = [&](const std::filesystem::path& whole, const char* name) {
    const std::string bytes = read_file(whole);
    std::ofstream(dir / name, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  };
  cut(dir / "ball.stl", "cut.stl");
  cut(dir / "leaf.glb", "cut.glb");
  std::ofstream(dir / "points.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nend_header\n1 2 0\n-4 5 0\n0 -9 0\n";
  DlaOptions o;
  o.particles = 60;
  Cluster part = grow(o);
  write_csv(part, dir / "grown.csv");  // for dla3d frames
  part.complete = false;
  write_checkpoint({{"-n", "120", "-q", "-o", "resumed"}, 0, part, {}}, dir / "saved.ck");
  cut(dir / "saved.ck", "cut.ck");
}

//! What make_inputs puts in the folder of a run.
const std::set<std::string>& input_names() {
  static const std::set<std::string> names = {"ball.stl",   "box.off",   "noise.stl", "out.csv",   "points.csv",
                                              "paint.ply",  "points.ply", "saved.ck", "mask.txt",  "rod.stl",
                                              "dir",        "grown.csv", "leaf.glb",  "folder.stl", "pipe.stl",
                                              "zero.stl",   "empty.stl", "cut.stl",   "cut.glb",   "cut.ck"};
  return names;
}

bool balanced(const std::string& text, char open, char close) {
  long depth = 0;
  for (const char c : text) {
    depth += (c == open) - (c == close);
    if (depth < 0) return false;
  }
  return depth == 0;
}

//! The number after `"key": ` in a JSON text, after `after` if given, or -1.
double json_value(const std::string& json, const std::string& key, const std::string& after = "") {
  const std::size_t at = json.find("\"" + key + "\": ", after.empty() ? 0 : json.find(after));
  return at == std::string::npos ? -1.0 : std::atof(json.c_str() + at + key.size() + 4);
}

//! The value of the last `flag` in a command line of the table's words, or `otherwise`.
std::string last_value(const std::string& command, const std::string& flag, const std::string& otherwise) {
  const std::size_t at = command.rfind(flag + " ");
  if (at == std::string::npos) return otherwise;
  const std::size_t from = at + flag.size() + 1;
  return command.substr(from, command.find(' ', from) - from);
}

//! The value of `flag` as the run took it: the command's last, else its --preset's (a preset of
//! `model`), else `otherwise`.
std::string value_as_run(const std::string& command, std::string_view model, const std::string& flag,
                         const std::string& otherwise) {
  const std::string none = "\x01";
  if (const std::string given = last_value(command, flag, none); given != none) return given;
  const std::string preset = last_value(command, "--preset", "");
  for (const Preset* p : presets_of(model))
    if (p->name == preset)
      for (const PresetOption& option : p->options)
        if (cli_flag(option.name) == flag) return std::string(option.value);
  return otherwise;
}

//! The header of a PLY file, and the size of its body.
std::pair<std::string, std::size_t> ply_parts(const std::string& ply) {
  const std::size_t header_end = ply.find("end_header\n");
  if (header_end == std::string::npos) return {"", 0};
  return {ply.substr(0, header_end + 11), ply.size() - header_end - 11};
}

//! What is wrong with the .glb `name` in `dir`: its header, and the glTF-Validator's report
//! when it is installed; "" if nothing.
std::string glb_fault(const ScratchDir& dir, const std::string& name) {
  const std::string glb = read_file(dir / name);
  std::uint32_t head[3] = {0, 0, 0};
  if (glb.size() >= 12) std::memcpy(head, glb.data(), 12);
  if (head[0] != 0x46546C67 || head[1] != 2 || head[2] != glb.size()) return name + "'s header is not glTF 2's";
  if (testing::gltf_validator().empty()) return "";
  const std::string report = testing::validate_glb(dir / name);
  return report.empty() ? "" : name + " fails the glTF-Validator: " + report;
}

//! The triangles of the OBJ `name` in `dir`, each piece's positions welded where they are
//! equal (a tube's seam repeats its first column of vertices for the texture), not across
//! pieces, which may touch; `fault` says what is wrong with the file, if anything.
SolidMesh read_obj(const ScratchDir& dir, const std::string& name, std::string& fault) {
  const std::string obj = read_file(dir / name);
  SolidMesh mesh;
  if (obj.rfind("# dla3d ", 0) != 0 || obj.empty() || obj.back() != '\n') {
    fault = name + " is not whole";
    return mesh;
  }
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v") {
      std::array<float, 3> p;
      if (!(words >> p[0] >> p[1] >> p[2]) || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        fault = name + ": a vertex that is not 3 finite numbers: " + line;
        return mesh;
      }
      positions.push_back(p);
    } else if (kind == "f") {
      std::array<std::uint32_t, 3> face;
      std::string corner;
      for (std::size_t k = 0; k < 3; ++k) {
        const long v = words >> corner ? std::atol(corner.c_str()) : 0;  // v, v/vt or v/vt/vn
        if (v < 1 || static_cast<std::size_t>(v) > positions.size()) {
          fault = name + ": a face names a vertex it has not given: " + line;
          return mesh;
        }
        face[k] = static_cast<std::uint32_t>(v - 1);
      }
      if (words >> corner) {
        fault = name + ": a face that is not a triangle: " + line;
        return mesh;
      }
      faces.push_back(face);
    }
  }
  // The pieces: vertices joined by faces.
  std::vector<std::uint32_t> piece(positions.size());
  for (std::uint32_t v = 0; v < piece.size(); ++v) piece[v] = v;
  const auto find = [&](std::uint32_t v) {
    while (piece[v] != v) v = piece[v] = piece[piece[v]];
    return v;
  };
  for (const auto& f : faces)
    for (int k = 1; k < 3; ++k) piece[find(f[k])] = find(f[0]);
  std::map<std::pair<std::uint32_t, std::array<float, 3>>, std::uint32_t> welded;
  std::vector<std::uint32_t> index(positions.size());
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    const auto [at, added] = welded.emplace(std::make_pair(find(v), positions[v]), static_cast<std::uint32_t>(mesh.vertices.size()));
    if (added) mesh.vertices.emplace_back(positions[v][0], positions[v][1], positions[v][2]);
    index[v] = at->second;
  }
  for (const auto& f : faces) mesh.triangles.push_back({index[f[0]], index[f[1]], index[f[2]]});
  return mesh;
}

//! What is wrong with the OBJ `name` in `dir`: "" if it is whole and every tube (or the solid)
//! in it is closed. Tubes may be none (every branch shorter than --tube-min-branch).
std::string obj_fault(const ScratchDir& dir, const std::string& name, bool may_be_empty) {
  std::string fault;
  const SolidMesh mesh = read_obj(dir, name, fault);
  if (!fault.empty()) return fault;
  if (mesh.triangles.empty()) return may_be_empty ? "" : name + " has no triangles";
  const std::string faults = edge_faults(mesh);
  return faults.empty() ? "" : name + " is not closed: " + faults;
}

//! The meshes of the 3MF `path`, read by lib3mf, as one mesh; `fault` says why if it cannot.
SolidMesh read_3mf(const std::string& path, std::string& fault) {
  SolidMesh mesh;
  NMR::PLib3MFModel* model = nullptr;
  NMR::PLib3MFModelReader* reader = nullptr;
  NMR::PLib3MFModelResourceIterator* objects = nullptr;
  const auto release = [&] {
    for (NMR::PLib3MFBase* owned : {static_cast<NMR::PLib3MFBase*>(objects), static_cast<NMR::PLib3MFBase*>(reader),
                                    static_cast<NMR::PLib3MFBase*>(model)})
      if (owned) NMR::lib3mf_release(owned);
  };
  if (NMR::lib3mf_createmodel(&model) != LIB3MF_OK || NMR::lib3mf_model_queryreader(model, "3mf", &reader) != LIB3MF_OK ||
      NMR::lib3mf_reader_readfromfileutf8(reader, path.c_str()) != LIB3MF_OK ||
      NMR::lib3mf_model_getmeshobjects(model, &objects) != LIB3MF_OK) {
    fault = path + " is not a 3MF that lib3mf reads";
    release();
    return mesh;
  }
  BOOL more = false;
  while (NMR::lib3mf_resourceiterator_movenext(objects, &more) == LIB3MF_OK && more) {
    NMR::PLib3MFModelResource* object = nullptr;
    DWORD vertices = 0, triangles = 0;
    NMR::lib3mf_resourceiterator_getcurrent(objects, &object);
    NMR::lib3mf_meshobject_getvertexcount(object, &vertices);
    NMR::lib3mf_meshobject_gettrianglecount(object, &triangles);
    std::vector<NMR::MODELMESHVERTEX> v(vertices);
    std::vector<NMR::MODELMESHTRIANGLE> t(triangles);
    if (vertices) NMR::lib3mf_meshobject_getvertices(object, v.data(), vertices, nullptr);
    if (triangles) NMR::lib3mf_meshobject_gettriangleindices(object, t.data(), triangles, nullptr);
    NMR::lib3mf_release(object);
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const NMR::MODELMESHVERTEX& p : v) mesh.vertices.emplace_back(p.m_fPosition[0], p.m_fPosition[1], p.m_fPosition[2]);
    for (const NMR::MODELMESHTRIANGLE& f : t)
      mesh.triangles.push_back({base + f.m_nIndices[0], base + f.m_nIndices[1], base + f.m_nIndices[2]});
  }
  release();
  return mesh;
}

//! The PLY `name` in `dir` read back whole, ASCII or binary: its particles (positions as
//! floats, parents and seeds) with its tree edges as their parents, and its links; `fault`
//! says what is wrong, if anything.
Cluster read_ply_tree(const ScratchDir& dir, const std::string& name, std::string& fault) {
  const std::string ply = read_file(dir / name);
  const auto [header, body] = ply_parts(ply);
  Cluster tree;
  const std::size_t at_vertex = header.find("element vertex "), at_edge = header.find("element edge ");
  if (header.empty() || at_vertex == std::string::npos || at_edge == std::string::npos) {
    fault = name + " has no header";
    return tree;
  }
  const auto vertices = static_cast<std::size_t>(std::atoll(header.c_str() + at_vertex + 15));
  const auto edges = static_cast<std::size_t>(std::atoll(header.c_str() + at_edge + 13));
  const bool linked = header.find("property uchar link") != std::string::npos;
  const bool binary = header.find("format binary_little_endian") != std::string::npos;
  // A struck discharge's vertices end with its current (float), channel (uchar) and light (float).
  const std::size_t stride = header.find("property float current\nproperty uchar channel\nproperty float light\n") !=
                                     std::string::npos
                                 ? 47
                                 : 38;
  if (binary && body != stride * vertices + (linked ? 9 : 8) * edges) {
    fault = name + "'s body is not its header's size";
    return tree;
  }
  std::vector<float> floats;  // x, y, z, radius, age of each vertex
  std::vector<std::int32_t> seeds, parents;
  std::vector<std::array<std::int32_t, 3>> edge_list;  // vertex1, vertex2, link
  if (binary) {
    const char* data = ply.data() + header.size();
    for (std::size_t v = 0; v < vertices; ++v, data += stride) {
      float five[5];
      std::memcpy(five, data, 20);
      floats.insert(floats.end(), five, five + 5);
      std::int32_t seed = 0, parent = 0;
      std::memcpy(&seed, data + 30, 4);
      std::memcpy(&parent, data + 34, 4);
      seeds.push_back(seed);
      parents.push_back(parent);
    }
    for (std::size_t e = 0; e < edges; ++e, data += linked ? 9 : 8) {
      std::array<std::int32_t, 3> edge{0, 0, 0};
      std::memcpy(edge.data(), data, 8);
      if (linked) edge[2] = static_cast<unsigned char>(data[8]);
      edge_list.push_back(edge);
    }
  } else {
    std::istringstream lines(ply.substr(header.size()));
    std::string line;
    for (std::size_t v = 0; v < vertices; ++v) {
      double x[5], depth, descendants, order, tip, seed, parent;
      if (!std::getline(lines, line) || !(std::istringstream(line) >> x[0] >> x[1] >> x[2] >> x[3] >> x[4] >> depth >>
                                          descendants >> order >> tip >> seed >> parent)) {
        fault = name + ": vertex " + std::to_string(v) + " is not 11 numbers";
        return tree;
      }
      for (const double value : x) floats.push_back(static_cast<float>(value));
      seeds.push_back(static_cast<std::int32_t>(seed));
      parents.push_back(static_cast<std::int32_t>(parent));
    }
    for (std::size_t e = 0; e < edges; ++e) {
      std::array<std::int32_t, 3> edge{0, 0, 0};
      std::istringstream row(std::getline(lines, line) ? line : "");
      if (!(row >> edge[0] >> edge[1]) || (linked && !(row >> edge[2]))) {
        fault = name + ": edge " + std::to_string(e) + " is not " + (linked ? "3" : "2") + " numbers";
        return tree;
      }
      edge_list.push_back(edge);
    }
    if (std::getline(lines, line)) {
      fault = name + " goes on past its header's counts";
      return tree;
    }
  }
  for (const float value : floats)
    if (!std::isfinite(value)) {
      fault = name + " holds a float that is not finite";
      return tree;
    }
  for (std::size_t v = 0; v < vertices; ++v) {
    tree.particles.push_back({Vec3(floats[5 * v], floats[5 * v + 1], floats[5 * v + 2]), parents[v], seeds[v]});
    tree.seed_count += parents[v] < 0;
  }
  // Each tree edge joins a particle's parent to it, once; the rest are links.
  std::size_t tree_edges = 0;
  for (const auto& [from, to, link] : edge_list) {
    if (from < 0 || to < 0 || static_cast<std::size_t>(from) >= vertices || static_cast<std::size_t>(to) >= vertices) {
      fault = name + ": an edge names a vertex it does not have";
      return tree;
    }
    if (link) {
      tree.links.push_back({std::min(from, to), std::max(from, to)});
    } else if (parents[static_cast<std::size_t>(to)] != from) {
      fault = name + ": the edge " + std::to_string(from) + "-" + std::to_string(to) + " is not a parent's";
      return tree;
    } else {
      ++tree_edges;
    }
  }
  if (tree_edges != vertices - tree.seed_count) fault = name + " has " + std::to_string(tree_edges) + " tree edges for " +
                                                        std::to_string(vertices - tree.seed_count) + " attached particles";
  return tree;
}

//! The files a run that exited 0 ought to leave under `prefix`: `formats` (a --formats value),
//! the glb's `lods` levels, the links' CSV beside the CSV when there are `links`, and the
//! scene's mesh when the scene shows one.
std::set<std::string> expected_files(const std::string& prefix, const std::string& formats, int lods, bool links,
                                     bool scene_mesh) {
  OutputOptions files;
  files.output = prefix;
  files.formats = parse_formats(formats);
  files.lods = lods;
  const std::vector<std::string> names = file_names(files);
  std::set<std::string> expected(names.begin(), names.end());
  if (files.formats.pov && files.formats.tips) expected.insert(prefix + "_tips.inc");
  if (files.formats.csv && links) expected.insert(prefix + "_links.csv");
  if (files.formats.pov && scene_mesh) expected.insert(prefix + "_mesh.inc");
  return expected;
}

//! What is wrong with a --stream file of a run that ended (cli/stream.h), or "": whole frames,
//! each starting where the last ended (or at 0, as a resumed run does), the last one done.
std::string stream_fault(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  std::uint64_t sent = 0, done = 0, total = 0;
  for (std::size_t at = 0; at < bytes.size();) {
    if (bytes.size() - at < 32 || bytes.compare(at, 4, "DLAs") != 0) return "a frame's header is cut or wrong";
    std::uint32_t count = 0;
    std::uint64_t first = 0;
    std::memcpy(&count, bytes.data() + at + 4, 4);
    std::memcpy(&first, bytes.data() + at + 8, 8);
    std::memcpy(&done, bytes.data() + at + 16, 8);
    std::memcpy(&total, bytes.data() + at + 24, 8);
    if (first != sent && first != 0) return "a frame starts at " + std::to_string(first) + ", not " + std::to_string(sent);
    if (bytes.size() - at - 32 < 16ull * count) return "a frame's particles are cut";
    sent = first + count;
    at += 32 + 16ull * count;
  }
  if (sent == 0) return "no particle was streamed";
  if (done > total) return "done is past the total";
  return "";
}

//! Checks the files of a run that exited 0 under `prefix` in `dir`, writing `formats` (a
//! --formats value) with `lods` levels of the glb: exactly those files, each read back whole,
//! and, with the JSON, against its counts; returns what is wrong.
std::string check_files(const ScratchDir& dir, const std::string& prefix, const std::string& formats, int lods) {
  const auto wants = [&](const char* format) { return ("," + formats + ",").find(std::string(",") + format + ",") != std::string::npos; };
  // The counts: the JSON's, else the CSV's, else the PLY's.
  std::size_t particles = 0, edges = 0, links = 0;
  double spacing = 0.0, noise = 0.0, reach = 1.0;
  bool collided = false, counted = false;
  const std::string json = read_file(dir / (prefix + ".json"));
  if (!wants("json") && !json.empty()) return prefix + ".json was not asked for";
  if (wants("json")) {
    if (json.empty() || json.front() != '{' || json.substr(json.size() - 2) != "}\n" || !balanced(json, '{', '}') ||
        !balanced(json, '[', ']'))
      return prefix + ".json is not whole";
    if (json.find("nan") != std::string::npos || json.find("inf,") != std::string::npos)
      return prefix + ".json holds a number JSON cannot";
    if (json.find("\"complete\": true") == std::string::npos) return "exit 0 but the JSON says incomplete";
    particles = static_cast<std::size_t>(json_value(json, "particles", "\"counts\""));
    edges = static_cast<std::size_t>(json_value(json, "attached", "\"counts\""));
    links = static_cast<std::size_t>(json_value(json, "links", "\"counts\""));
    spacing = json_value(json, "spacing");
    // Space colonization's noise moves each node by up to its amplitude in each coordinate,
    // and a collision mesh moves it as far as its surface.
    // "noise": "A,K" (or "A"): up to A.
    const std::size_t noise_at = json.find("\"noise\": \"");
    noise = noise_at == std::string::npos ? 0.0 : std::max(0.0, std::atof(json.c_str() + noise_at + 10));
    collided = json.find("\"collide\": \"") != std::string::npos;
    // An Eden site hangs from the nearest occupied site of its mask, up to 8 sites away along
    // each axis.
    if (json.find("\"model\": \"eden\"") != std::string::npos) reach = 8 * std::sqrt(3.0);
    // A monomer of an aggregate touches its parent at the sum of their radii, which spread as
    // far as the options draw them: the tree's shape alone.
    if (json.find("\"model\": \"aggregate\"") != std::string::npos) reach = std::numeric_limits<double>::infinity();
    counted = true;
  }

  if (wants("spheres")) {
    // The sphere list: x,y,z,r, a row a particle, every radius positive.
    std::istringstream spheres(read_file(dir / (prefix + "_spheres.csv")));
    std::string line;
    if (!std::getline(spheres, line) || line != "x,y,z,r") return prefix + "_spheres.csv has no header";
    std::size_t rows = 0;
    for (; std::getline(spheres, line); ++rows) {
      double x, y, z, r;
      char c[3];
      std::istringstream row(line);
      if (!(row >> x >> c[0] >> y >> c[1] >> z >> c[2] >> r) || !(r > 0.0) || !std::isfinite(x + y + z + r))
        return prefix + "_spheres.csv row " + line + " is not a sphere";
    }
    if (counted && rows != particles) return prefix + "_spheres.csv has another count than the JSON";
  }

  if (wants("mstm")) {
    // MSTM's positions: radius x y z, a line a particle, every radius positive.
    std::istringstream positions(read_file(dir / (prefix + "_mstm.pos")));
    std::size_t rows = 0;
    for (std::string line; std::getline(positions, line); ++rows) {
      double r, x, y, z;
      std::istringstream row(line);
      if (!(row >> r >> x >> y >> z) || !(r > 0.0) || !std::isfinite(x + y + z + r))
        return prefix + "_mstm.pos line " + line + " is not a sphere";
    }
    if (counted && rows != particles) return prefix + "_mstm.pos has another count than the JSON";
  }

  if (wants("ddscat")) {
    // DDSCAT's shape: NAT on its second line, then six lines of header and NAT dipoles
    // numbered in order.
    std::istringstream shape(read_file(dir / (prefix + "_ddscat.dat")));
    std::string line;
    std::size_t nat = 0;
    std::getline(shape, line);
    if (!(shape >> nat)) return prefix + "_ddscat.dat has no NAT";
    for (int i = 0; i < 6; ++i) std::getline(shape, line);
    if (line != "JA IX IY IZ ICOMP(x,y,z)") return prefix + "_ddscat.dat has no header";
    std::size_t rows = 0;
    for (long ja, ix, iy, iz, c1, c2, c3; shape >> ja >> ix >> iy >> iz >> c1 >> c2 >> c3;)
      if (static_cast<std::size_t>(ja) != ++rows) return prefix + "_ddscat.dat's dipoles are not numbered in order";
    if (!shape.eof() || rows != nat) return prefix + "_ddscat.dat does not hold its NAT dipoles";
  }

  if (wants("csv")) {
    std::istringstream csv(read_file(dir / (prefix + ".csv")));
    std::string line;
    // A discharge that struck its target has its attributes beside every model's columns
    // (docs/breakdown.md#attributes).
    const std::string header = "id,x,y,z,parent,seed,radius,age,depth,descendants,order,tip";
    if (!std::getline(csv, line) || (line != header && line != header + ",current,channel,light"))
      return prefix + ".csv has no header";
    dla::Cluster grown;
    grown.spacing = spacing;
    grown.dimensions = 3;  // 2D growth's plane is the writers' business here
    while (std::getline(csv, line)) {
      double id, x, y, z, parent, seed, radius;
      char c[6];
      std::istringstream row(line);
      if (!(row >> id >> c[0] >> x >> c[1] >> y >> c[2] >> z >> c[3] >> parent >> c[4] >> seed >> c[5] >> radius))
        return prefix + ".csv row " + line + " does not begin with 7 numbers";
      if (id != static_cast<double>(grown.particles.size())) return prefix + ".csv ids are not in order";
      if (!(radius > 0.0)) return prefix + ".csv has a radius that is not positive";
      if (parent < 0) ++grown.seed_count;
      grown.particles.push_back({Vec3(x, y, z), static_cast<std::int32_t>(parent), static_cast<std::int32_t>(seed)});
    }
    // Branches clipped at a mesh are shorter; a collision mesh moves a node as far as its
    // surface. Without the JSON's spacing, the tree's shape alone.
    const double longest = collided || !counted ? std::numeric_limits<double>::infinity() : reach + std::sqrt(3.0) * noise;
    if (!counted || !(grown.spacing > 0.0)) grown.spacing = 1.0;
    const std::string fault = dla::testing::tree_fault(grown, {0.0, longest, false});
    if (!fault.empty()) return prefix + ".csv is not a tree: " + fault;
    // The links: as many as the JSON counts, each two particles, none a tree edge or twice.
    const std::string links_csv = read_file(dir / (prefix + "_links.csv"));
    if (counted && grown.particles.size() != particles) return prefix + ".csv has another count than the JSON";
    if (!counted) {
      particles = grown.particles.size();
      edges = particles - grown.seed_count;
      links = links_csv.empty() ? 0 : static_cast<std::size_t>(std::count(links_csv.begin(), links_csv.end(), '\n')) - 1;
      counted = true;
    }
    if (links == 0 && !links_csv.empty()) return prefix + "_links.csv is there without links";
    if (links > 0) {
      try {
        dla::parse_links_csv(links_csv, prefix + "_links.csv", grown);
      } catch (const std::exception& e) {
        return e.what();
      }
      if (grown.links.size() != links) return prefix + "_links.csv has another count than the JSON";
      std::set<std::pair<std::int32_t, std::int32_t>> seen;
      for (const dla::Link& link : grown.links)
        if (grown.particles[static_cast<std::size_t>(link.later)].parent == link.earlier ||
            !seen.insert({link.earlier, link.later}).second)
          return prefix + "_links.csv repeats a tree edge or a link";
    }
  }

  if (wants("ply")) {
    std::string fault;
    Cluster tree = read_ply_tree(dir, prefix + ".ply", fault);
    if (!fault.empty()) return fault;
    tree.spacing = 1.0;
    tree.dimensions = 3;
    fault = dla::testing::tree_fault(tree, {0.0, std::numeric_limits<double>::infinity(), false});
    if (!fault.empty()) return prefix + ".ply is not a tree: " + fault;
    if (counted && (tree.particles.size() != particles || tree.particles.size() - tree.seed_count != edges ||
                    tree.links.size() != links))
      return prefix + ".ply counts another structure than the JSON or the CSV";
    if (!counted) {
      particles = tree.particles.size();
      edges = particles - tree.seed_count;
      links = tree.links.size();
      counted = true;
    }
  }

  // The files on disk are those asked for, and no other.
  std::set<std::string> written;
  const std::filesystem::path folder = dir.path() / std::filesystem::path(prefix).parent_path();
  const std::string stem = std::filesystem::path(prefix).filename().string();
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    const std::string relative = (std::filesystem::path(prefix).parent_path() / name).string();
    if (name.rfind(stem, 0) == 0 && name.size() > stem.size() && (name[stem.size()] == '.' || name[stem.size()] == '_') &&
        !input_names().count(relative))
      written.insert(relative);
  }
  const std::string stem_pov = read_file(dir / (prefix + ".pov"));
  const bool scene_mesh = stem_pov.find("#include \"" + stem + "_mesh.inc\"") != std::string::npos;
  const std::set<std::string> expected = expected_files(prefix, formats, lods, links > 0, scene_mesh);
  for (const std::string& name : expected)
    if (!std::filesystem::exists(dir / name)) return name + " was asked for but not written";
  for (const std::string& name : written)
    if (!expected.count(name)) return name + " was written but not asked for";

  if (wants("tips")) {
    const std::string tips = read_file(dir / (prefix + "_tips.ply"));
    const auto [header, body] = ply_parts(tips);
    const std::size_t at = header.find("element vertex ");
    if (at == std::string::npos) return prefix + "_tips.ply has no header";
    const auto points = static_cast<std::size_t>(std::atoll(header.c_str() + at + 15));
    // None is valid: no tip within --tips-within 0 of the mesh.
    if (counted && points > particles) return prefix + "_tips.ply has " + std::to_string(points) + " points";
    const bool binary = header.find("format binary_little_endian") != std::string::npos;
    if (binary ? body != 36 * points
               : static_cast<std::size_t>(std::count(tips.begin() + static_cast<std::ptrdiff_t>(header.size()), tips.end(), '\n')) != points)
      return prefix + "_tips.ply's body is not its header's size";
  }

  if (wants("html")) {
    const std::string html = read_file(dir / (prefix + ".html"));
    if (html.rfind("<!DOCTYPE html>", 0) != 0 || html.size() < 8 || html.compare(html.size() - 8, 8, "</html>\n") != 0)
      return prefix + ".html is not whole";
    if (counted && html.find("{\"particles\": " + std::to_string(particles) + ",") == std::string::npos)
      return prefix + ".html does not hold the " + std::to_string(particles) + " particles";
  }
  if (wants("glb")) {
    const std::string fault = glb_fault(dir, prefix + ".glb");
    if (!fault.empty()) return fault;
  }
  if (wants("obj")) {
    const std::string fault = obj_fault(dir, prefix + ".obj", true);
    if (!fault.empty()) return fault;
  }

  // The solid: closed and oriented, and with the JSON, its shells counted there.
  if (wants("json") && (wants("stl") || wants("3mf") || wants("vdb") || wants("solid-glb") || wants("solid-obj"))) {
    if (json.find("\"solid\": {") == std::string::npos) return prefix + ".json records no solid";
    if (!(json_value(json, "shells", "\"solid\"") >= 1)) return prefix + ".json's solid has no shell";
  }
  if (wants("stl")) {
    const SolidMesh stl = read_stl(dir / (prefix + ".stl"));
    if (stl.triangles.empty()) return prefix + ".stl is not a whole binary STL";
    const std::string faults = edge_faults(stl);
    if (!faults.empty()) return prefix + ".stl is not closed: " + faults;
  }
  if (wants("3mf")) {
    std::string fault;
    const SolidMesh mesh = read_3mf(dir / (prefix + ".3mf"), fault);
    if (!fault.empty()) return fault;
    if (mesh.triangles.empty()) return prefix + ".3mf holds no triangles";
    fault = edge_faults(mesh);
    if (!fault.empty()) return prefix + ".3mf is not closed: " + fault;
  }
  if (wants("vdb") && read_file(dir / (prefix + ".vdb")).rfind(std::string(" BDV\0\0\0\0", 8), 0) != 0)
    return prefix + ".vdb is not OpenVDB's";
  if (wants("solid-glb")) {
    const std::string fault = glb_fault(dir, prefix + "_solid.glb");
    if (!fault.empty()) return fault;
  }
  if (wants("solid-obj")) {
    const std::string fault = obj_fault(dir, prefix + "_solid.obj", false);
    if (!fault.empty()) return fault;
  }

  if (wants("png")) {
    const std::string png = read_file(dir / (prefix + ".png"));
    std::uint32_t size[2] = {0, 0};
    if (png.size() >= 45) std::memcpy(size, png.data() + 16, 8);
    if (png.size() < 45 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || png.compare(12, 4, "IHDR") != 0 ||
        size[0] == 0 || size[1] == 0 || png.compare(png.size() - 8, 4, "IEND") != 0)
      return prefix + ".png is not a whole PNG";
  }

  if (wants("svg")) {
    const std::string svg = read_file(dir / (prefix + ".svg"));
    std::size_t lines = 0;
    for (std::size_t at = svg.find("<line "); at != std::string::npos; at = svg.find("<line ", at + 1)) ++lines;
    if (svg.rfind("<?xml", 0) != 0 || svg.size() < 8 || svg.compare(svg.size() - 7, 7, "</svg>\n") != 0)
      return prefix + ".svg is not whole";
    if (counted && lines != edges + links) return prefix + ".svg draws " + std::to_string(lines) + " branches and links";
  }

  if (!wants("pov")) return "";
  const std::string pov = read_file(dir / (prefix + ".pov")), inc = read_file(dir / (prefix + ".inc"));
  const std::string name = std::filesystem::path(prefix).filename().string();
  if (pov.find("#include \"" + name + ".inc\"") == std::string::npos) return prefix + ".pov does not include its .inc";
  if (wants("tips") != (pov.find("#include \"" + name + "_tips.inc\"") != std::string::npos))
    return prefix + ".pov includes its tips without tips in --formats, or the other way round";
  if (wants("tips")) {
    const std::string tips = read_file(dir / (prefix + "_tips.inc"));
    if (tips.find("#declare DLA_TipCount = ") == std::string::npos || !balanced(tips, '{', '}'))
      return prefix + "_tips.inc does not declare its tips";
  }
  if (pov.find("#include \"" + name + "_growth.inc\"") == std::string::npos)
    return prefix + ".pov does not include its _growth.inc";
  if (!balanced(inc, '{', '}') || !balanced(pov, '{', '}') ||
      !balanced(read_file(dir / (prefix + "_growth.inc")), '{', '}'))
    return "the POV-Ray files' braces do not pair";
  // POV-Ray renders the scene, and a frame of its growth (the scene's own code builds it from
  // PREFIX_growth.inc). Its command line does not take every file name: the scene is copied
  // to a plain one.
  if (std::string(POVRAY_PATH).find("NOTFOUND") != std::string::npos || std::string(POVRAY_PATH).empty())
    return "POV-Ray is not installed (the README's setup installs povray): " + prefix + ".pov cannot be rendered";
  std::filesystem::copy_file(folder / (name + ".pov"), folder / "render_scene.pov");
  const std::string render = "cd '" + folder.string() + "' && '" + std::string(POVRAY_PATH) +
                             "' +Irender_scene.pov +Orender.png +W32 +H24 -D -V > povray.log 2>&1";
  if (std::system(render.c_str()) != 0)
    return "POV-Ray cannot render " + prefix + ".pov: " + read_file((folder / "povray.log").string());
  const std::string growth = "cd '" + folder.string() + "' && '" + std::string(POVRAY_PATH) +
                             "' +Irender_scene.pov +Ogrowth.png +W32 +H24 -D -V Declare=DLA_Show=0.5 > povray.log 2>&1";
  if (std::system(growth.c_str()) != 0)
    return "POV-Ray cannot render half the growth of " + prefix + ".pov: " + read_file((folder / "povray.log").string());
  return "";
}

//! Checks the files of a `dla3d frames` run that exited 0: `count` frames numbered from
//! PREFIX_0001, each the files of `formats` (with `lods` levels of the glb) read back whole as
//! a run's are; returns what is wrong.
std::string check_frames(const ScratchDir& dir, const std::string& prefix, std::size_t count, const std::string& formats,
                         int lods) {
  for (std::size_t k = 1; k <= count; ++k) {
    std::string number = std::to_string(k);
    number.insert(0, std::max<std::size_t>(4, std::to_string(count).size()) - number.size(), '0');
    const std::string fault = check_files(dir, prefix + "_" + number, formats, lods);
    if (!fault.empty()) return "frame " + number + ": " + fault;
  }
  return "";
}

//! What is wrong with the files a run stopped by a signal left in `dir` (`inputs` aside), or
//! "": none half-written (no temporary left, each glb and binary STL as long as it says, the
//! JSON whole), the CSV a tree, and the JSON saying where it stopped when the run did not end.
std::string stopped_files_fault(const ScratchDir& dir, const std::set<std::string>& inputs, bool ended) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path())) {
    const std::string name = entry.path().lexically_relative(dir.path()).string();
    if (inputs.count(name) || name == "err.txt" || !entry.is_regular_file()) continue;
    const auto ends_with = [&](const char* suffix) {
      const std::size_t n = std::strlen(suffix);
      return name.size() >= n && name.compare(name.size() - n, n, suffix) == 0;
    };
    const std::string bytes = read_file(entry.path());
    if (ends_with(".tmp")) return name + " was left";
    if (ends_with(".glb")) {
      std::uint32_t length = 0;
      if (bytes.size() >= 12) std::memcpy(&length, bytes.data() + 8, 4);
      if (bytes.size() < 12 || length != bytes.size()) return name + " is not whole";
    } else if (ends_with(".stl") && bytes.size() >= 84 && bytes.compare(0, 5, "solid") != 0) {
      std::uint32_t triangles = 0;
      std::memcpy(&triangles, bytes.data() + 80, 4);
      if (84 + 50 * static_cast<std::uint64_t>(triangles) != bytes.size()) return name + " is not whole";
    } else if (ends_with(".json")) {
      if (bytes.size() < 2 || bytes.substr(bytes.size() - 2) != "}\n" || !balanced(bytes, '{', '}')) return name + " is not whole";
      if (!ended && bytes.find("\"stopped_in\": ") == std::string::npos && bytes.find("\"generator\"") != std::string::npos)
        return name + " does not say where the run stopped";
    } else if (ends_with(".csv") && !ends_with("_links.csv") && !ends_with("_spheres.csv") &&
               name.find("frame") == std::string::npos) {
      try {
        const std::string fault = testing::tree_fault(read_csv(entry.path().string()), {0.0, 1e300, false});
        if (!fault.empty()) return name + " is not a tree: " + fault;
      } catch (const std::exception& e) {
        // Stopped before anything attached: seeds alone, which read_csv refuses to measure.
        if (std::string(e.what()).find("has no branches to measure") == std::string::npos)
          return name + " does not read back: " + e.what();
      }
    }
  }
  return "";
}

TEST(CliProperty, RandomCommandLinesNeverCrashHangOrLeaveBadFiles) {
  ScratchDir root;
  // The table knows every option of --help: a new option must join it.
  for (const std::string& name : options_of_help(root))
    EXPECT_TRUE(option_table().count(name)) << name << " is in dla3d --help but not in the property test's table";
  // Every model the library registers runs here, with its own options' table; a new model
  // must join. Each has a share of the runs (of 16, with one for frames); DLA's options are
  // the top level's.
  using Table = std::map<std::string, std::vector<std::string>>;
  struct ModelRuns {
    std::string_view name;
    std::size_t share;
    const Table* table;
  };
  const ModelRuns model_runs[] = {{"colonize", 4, &colonize_table()}, {"eden", 2, &eden_table()},
                                  {"drop", 1, &drop_table()},         {"ballistic", 1, &ballistic_table()},
                                  {"breakdown", 1, &breakdown_table()}, {"frames", 1, &frames_table()},
                                  {"aggregate", 1, &aggregate_table()}, {"grow", 5, nullptr}};
  for (const dla::Model& model : dla::models())
    EXPECT_TRUE(std::any_of(std::begin(model_runs), std::end(model_runs), [&](const ModelRuns& m) { return m.name == model.name; }))
        << "the property test runs no " << model.name;
  for (const ModelRuns& m : model_runs)
    if (m.table && m.name != "frames") {
      for (const std::string& name : options_of_help(root, std::string(m.name)))
        EXPECT_TRUE(m.table->count(name) || option_table().count(name))
            << name << " is in dla3d " << m.name << " --help but not in the property test's tables";
    }
  for (const std::string& name : options_of_help(root, "frames"))
    EXPECT_TRUE(frames_table().count(name) || option_table().count(name))
        << name << " is in dla3d frames --help but not in the property test's tables";
  // What the other models share with DLA: the Output and Look options (and help).
  const std::vector<const char*> shared = {
      "--output", "--ply-format", "--formats", "--png-scale", "--png-bands", "--radius", "--base-radius",
      "--tip-radius", "--pipe-exponent", "--color-by", "--look", "--tube-sides", "--tube-tolerance",
      "--tube-min-branch", "--uv-scale", "--lod", "--ddscat-resolution", "--leaf", "--instances", "--tips-within", "--tips-every",
      "--tips-exclude-paint", "--up", "--quiet", "--stream", "--help"};
  const auto flags_of = [&](const Table& table) {
    std::vector<std::string> model_flags(shared.begin(), shared.end());
    for (const auto& [flag, values] : table) model_flags.push_back(flag);
    return model_flags;
  };
  // A model's own table, else the shared options' values in DLA's.
  const auto values_of = [&](const std::string& flag, const Table* table)
      -> const std::vector<std::string>& { return table && table->count(flag) ? table->at(flag) : option_table().at(flag); };

  const char* runs_env = std::getenv("DLA_PROPERTY_RUNS");
  const char* seed_env = std::getenv("DLA_PROPERTY_SEED");
  const int runs = runs_env ? std::atoi(runs_env) : 150;
  std::mt19937_64 rng(seed_env ? std::strtoull(seed_env, nullptr, 10) : 14);
  const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  std::vector<std::string> flags;
  for (const auto& [flag, values] : option_table()) flags.push_back(flag);

  std::map<int, int> exits, stops;  // stops: the exits of runs stopped by a signal (0: ended before it)
  for (int run = 0; run < runs; ++run) {
    // A few options, mostly valid values: an invalid one ends most runs at once.
    std::size_t share = pick(16);
    const ModelRuns* model = model_runs;
    while (share >= model->share) share -= model->share, ++model;
    const bool colonizing = model->name == "colonize", framing = model->name == "frames";
    const Table* table = model->table;
    const std::vector<std::string> model_flags = table ? flags_of(*table) : flags;
    std::string args;
    bool particles_given = false, output_given = false;
    const std::size_t count = pick(7);
    for (std::size_t i = 0; i < count; ++i) {
      const std::string& flag = model_flags[pick(model_flags.size())];
      const std::vector<std::string>& values = values_of(flag, table);
      if (flag == "--help" || flag == "--version") {
        if (pick(8) != 0) continue;  // rare: they end every run with a print
      }
      args += " " + flag;
      if (!values.empty()) args += " " + values[pick(3) == 0 ? pick(values.size()) : pick(std::min<std::size_t>(2, values.size()))];
      particles_given = particles_given || flag == "--particles" || flag == "--max-nodes" || flag == "--sites" ||
                        flag == "--monomers";
      output_given = output_given || flag == "--output";
    }
    // A resume takes no -n: leave it alone so that some resumes are valid.
    if (!particles_given && !framing && args.find("--resume") == std::string::npos)
      args = " -n " + std::to_string(20 + pick(150)) + args;
    if (framing) {
      static const char* const csvs[] = {"out.csv", "folder.stl", "pipe.stl", "zero.stl", "cut.stl"};
      args = " frames " + std::string(pick(8) == 0 ? csvs[pick(5)] : "grown.csv") + args;
    }
    if (colonizing && args.find("--attractors ") == std::string::npos)
      args = " --attractors " + std::to_string(50 + pick(1000)) + args;
    if (table && !framing) args = " " + std::string(model->name) + args;
    const std::string command = args.substr(1);

    ScratchDir dir;
    make_inputs(dir);
    std::filesystem::create_directory(dir.path() / "dir");
    const std::set<std::string>& inputs = input_names();
    // The bound: far above what any of these takes (under the sanitizers too); `timeout`
    // kills a hang with 137 and the assertion below names the command.
    rusage before{}, after{};
    getrusage(RUSAGE_CHILDREN, &before);
    const testing::CliRun result = testing::dla3d(dir, command, "timeout -s KILL 120");
    getrusage(RUSAGE_CHILDREN, &after);
    const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    const double cpu_seconds = seconds(after.ru_utime) + seconds(after.ru_stime) - seconds(before.ru_utime) -
                               seconds(before.ru_stime);
    ++exits[result.exit_code];
    SCOPED_TRACE("dla3d " + command + "\nstderr: " + result.err);
    const bool one_error_line = result.err.rfind("dla3d: error: ", 0) == 0 &&
                                std::count(result.err.begin(), result.err.end(), '\n') == 1;
    std::set<std::string> written;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path())) {
      const std::string name = entry.path().lexically_relative(dir.path()).string();  // not through links
      if (!inputs.count(name)) written.insert(name);
    }
    ASSERT_NE(result.exit_code, 137) << "no exit within the bound";
    ASSERT_GE(result.exit_code, 0) << "ended by a signal";
    // A run that grew, again, stopped by Ctrl-C or SIGTERM at a moment drawn from its
    // processor time: in any of its stages (growth, links, the look, each writer, frames).
    const auto stop_again = [&] {
      if (pick(3) == 0 && command.find("--resume") == std::string::npos) {
        const int signal = pick(2) ? SIGINT : SIGTERM;
        const double moment = cpu_seconds * static_cast<double>(pick(1001)) / 1000.0;
        ScratchDir again;
        make_inputs(again);
        std::filesystem::create_directory(again.path() / "dir");
        const testing::InterruptedRun stopped = testing::interrupt_run(again, {command}, signal, moment, "", true);
        SCOPED_TRACE("stopped by signal " + std::to_string(signal) + " after " + std::to_string(moment) +
                     " s of processor time; stderr: " + read_file(again / "err.txt"));
        ++stops[stopped.signalled ? stopped.exit_code : 0];
        if (stopped.signalled) {
          ASSERT_TRUE(stopped.exit_code == 0 || stopped.exit_code == 128 + signal) << "exit " << stopped.exit_code;
          EXPECT_LT(stopped.exit_seconds, 2.0) << "the signal was not obeyed within 2 s";
        }
        ASSERT_EQ(stopped_files_fault(again, inputs, !stopped.signalled || stopped.exit_code == 0), "");
      }
    };
    switch (result.exit_code) {
      case 0: {
        if (command.find("--help") != std::string::npos || command.find("--version") != std::string::npos ||
            command.find("--preset list") != std::string::npos)
          break;
        // The model's own defaults for the files: an aggregate's are aggregate.* with its sphere list.
        const dla::Model* registered = dla::find_model(model->name);
        dla::RunOptions defaults = registered ? registered->options() : dla::RunOptions();
        const dla::OutputOptions& default_files = (registered ? *registered : dla::model_of(defaults)).files(defaults);
        std::string prefix = command.find("--resume saved.ck") != std::string::npos ? "resumed"
                             : framing                                          ? "grown"
                                                                                : default_files.output;
        if (output_given) {
          const std::size_t at = command.rfind("--output ");
          std::string value = command.substr(at + 9, command.find(" -", at + 9) - at - 9);
          if (value.front() == '\'') value = value.substr(1, value.size() - 2);
          if (prefix != "resumed") prefix = value;
        }
        if (framing) {
          ASSERT_EQ(check_frames(dir, prefix, std::stoul(last_value(command, "--count", "30")),
                                 last_value(command, "--formats", "glb"), std::atoi(last_value(command, "--lod", "0").c_str())),
                    "");
          stop_again();
          break;
        }
        ASSERT_EQ(check_files(dir, prefix, value_as_run(command, model->name, "--formats", dla::format_words(default_files.formats)),
                              std::atoi(last_value(command, "--lod", "0").c_str())), "");
        if (last_value(command, "--stream", "") == "live.bin") {
          ASSERT_EQ(stream_fault(dir / "live.bin"), "");
        }
        stop_again();
        break;
      }
      case 2:
        EXPECT_TRUE(one_error_line) << "bad input is not one line";
        EXPECT_TRUE(written.empty()) << "bad input left " << (written.empty() ? "" : *written.begin());
        break;
      case 1: {
        // Growth had begun: lines of progress (the mesh's summary) may come before the error.
        const std::size_t last = result.err.rfind("dla3d: error: ");
        EXPECT_TRUE(last != std::string::npos && result.err.find("dla3d: error: ") == last &&
                    result.err.find('\n', last) == result.err.size() - 1)
            << "a failure is not one error line, last";
        for (const std::string& name : written) {
          if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) {
            EXPECT_NE(read_file(dir / name).find("\"complete\": false"), std::string::npos) << name;
          }
        }
        break;
      }
      default: FAIL() << "exit " << result.exit_code;
    }
    if (::testing::Test::HasFatalFailure()) return;
  }
  std::string summary;
  for (const auto& [code, n] : exits) summary += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
  std::printf("%d command lines:%s\n", runs, summary.c_str());
  summary.clear();
  for (const auto& [code, n] : stops) summary += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
  std::printf("runs stopped again by a signal:%s\n", summary.c_str());
  EXPECT_GT(stops[130] + stops[143], exits[0] / 12) << "too few runs were stopped by their signal";
  EXPECT_GT(exits[0], runs / 10) << "too few command lines grew anything: the table draws too many faults";
  EXPECT_GT(exits[2], runs / 10) << "too few faults drawn";
}

//! `dla3d studio`'s options, drawn as the others; every option of `dla3d studio --help`.
const std::map<std::string, std::vector<std::string>>& studio_table() {
  static const std::map<std::string, std::vector<std::string>> table = {
      {"--host", {"127.0.0.1", "localhost", "::1", "256.0.0.1", "''", "'a b'", "no.such.host.invalid"}},
      {"--port", {"0", "0", "-1", "65536", "x", "''"}},
      {"--open", {}},
      {"--help", {}},
  };
  return table;
}

// The studio, started with random options and stopped by Ctrl-C once it printed its address:
// it exits 0, or gives one error line (exit 2 for a bad option, 1 when it cannot listen). A
// Ctrl-C sent at a random moment of the start-up ends it with exit 130 and nothing more than
// such an error line (one printed just before Ctrl-C came), or as above.
TEST(CliProperty, TheStudioStartsAndStopsWithRandomOptions) {
  ScratchDir root;
  for (const std::string& name : options_of_help(root, "studio"))
    EXPECT_TRUE(studio_table().count(name)) << name << " is in dla3d studio --help but not in the property test's table";
  std::mt19937_64 rng(69);
  const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  std::vector<std::string> flags;
  for (const auto& [flag, values] : studio_table()) flags.push_back(flag);
  setenv("BROWSER", "true", 1);  // --open's browser: one that opens nothing
  std::map<int, int> exits;
  for (int run = 0; run < 16; ++run) {
    std::string args = " studio --port 0";
    for (std::size_t i = 0, n = pick(4); i < n; ++i) {
      const std::string& flag = flags[pick(flags.size())];
      if (flag == "--help" && pick(4) != 0) continue;
      const std::vector<std::string>& values = studio_table().at(flag);
      args += " " + flag;
      if (!values.empty()) args += " " + values[pick(3) == 0 ? pick(values.size()) : 0];
    }
    const bool during_start_up = run % 4 == 3;
    ScratchDir dir;
    int code = -1;
    std::string out;
    if (during_start_up) {
      // Spawned, not started by a shell's `&`, which would start it with Ctrl-C ignored.
      const pid_t pid = start_dla3d(dir, {args.substr(1)}, true);
      ASSERT_GT(pid, 0);
      usleep(static_cast<useconds_t>(pick(500)) * 1000);  // anywhere in the start-up: each moment must end well
      kill(pid, SIGINT);
      int status = 0;
      bool ended = false;
      for (int i = 0; i < 600 && !(ended = waitpid(pid, &status, WNOHANG) == pid); ++i) usleep(100000);
      if (!ended) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        ADD_FAILURE() << "dla3d" << args << " still runs 60 s after Ctrl-C";
      }
      code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    } else {
      // The address line is the event Ctrl-C waits for; a studio that never prints one and
      // never exits is killed at the bound, which fails below.
      const std::string script = "cd '" + dir.path().string() + "' && { timeout -s KILL 60 '" DLA3D_PATH "'" + args +
                                 " > out.txt 2> err.txt & pid=$!; for i in $(seq 600); do grep -q http:// out.txt && "
                                 "break; kill -0 $pid 2> /dev/null || break; sleep 0.1; done; "
                                 "kill -INT $pid 2> /dev/null; wait $pid; echo $? > rc.txt; }";
      ASSERT_EQ(std::system(script.c_str()), 0);
      code = std::atoi(read_file(dir / "rc.txt").c_str());
      out = read_file(dir / "out.txt");
    }
    const std::string err = read_file(dir / "err.txt");
    SCOPED_TRACE("dla3d" + args + (during_start_up ? " (Ctrl-C during start-up)" : "") + "\nstdout: " + out + "\nstderr: " + err);
    if (!during_start_up) ++exits[code];
    if (args.find("--help") != std::string::npos && code == 0) continue;
    switch (code) {
      case 0:
        if (!during_start_up) {  // stdout is dropped
          EXPECT_EQ(out.rfind("dla3d studio: http://", 0), 0u);
        }
        break;
      case 1:
      case 2:
        EXPECT_EQ(err.rfind("dla3d: error: ", 0), 0u);
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
        break;
      case 128 + SIGINT:
        EXPECT_TRUE(during_start_up) << "a studio that printed its address ends Ctrl-C with exit 0";
        // Quietly, or after the one error line a bad option already printed when Ctrl-C came.
        if (!err.empty()) {
          EXPECT_EQ(err.rfind("dla3d: error: ", 0), 0u);
          EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
        }
        break;
      default: FAIL() << "exit " << code;
    }
  }
  EXPECT_GT(exits[0], 3) << "too few studios started";
}

//! `dla3d options`' own options, drawn as the others; every option of `dla3d options --help`.
const std::map<std::string, std::vector<std::string>>& option_list_table() {
  static const std::map<std::string, std::vector<std::string>> table = {
      {"--format", {"json", "markdown", "JSON", "md", "''", "'json markdown'"}},
      {"--help", {}},
  };
  return table;
}

// `dla3d options` with random options: the JSON, the page docs/options.md is, its help, or one
// line and exit 2.
TEST(CliProperty, TheOptionListTakesRandomOptions) {
  ScratchDir root;
  for (const std::string& name : options_of_help(root, "options"))
    EXPECT_TRUE(option_list_table().count(name)) << name << " is in dla3d options --help but not in the property test's table";
  std::mt19937_64 rng(70);
  const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  std::vector<std::string> flags;
  for (const auto& [flag, values] : option_list_table()) flags.push_back(flag);
  std::map<int, int> exits;
  for (int run = 0; run < 12; ++run) {
    std::string args = " options", format = "json";
    for (std::size_t i = 0, n = pick(3); i < n; ++i) {
      const std::string& flag = flags[pick(flags.size())];
      if (flag == "--help" && pick(3) != 0) continue;
      const std::vector<std::string>& values = option_list_table().at(flag);
      args += " " + flag;
      if (!values.empty()) args += " " + (format = values[pick(2) == 0 ? pick(values.size()) : pick(2)]);
    }
    ScratchDir dir;
    const std::string script = "cd '" + dir.path().string() + "' && timeout -s KILL 60 '" DLA3D_PATH "'" + args +
                               " > out.txt 2> err.txt; echo $? > rc.txt";
    ASSERT_EQ(std::system(script.c_str()), 0);
    const int code = std::atoi(read_file(dir / "rc.txt").c_str());
    const std::string out = read_file(dir / "out.txt"), err = read_file(dir / "err.txt");
    SCOPED_TRACE("dla3d" + args + "\nstderr: " + err);
    ++exits[code];
    if (code == 0) {
      EXPECT_TRUE(err.empty());
      if (args.find("--help") != std::string::npos) continue;
      EXPECT_TRUE(format == "json" || format == "markdown");  // the last --format given
      EXPECT_EQ(out.rfind(format == "markdown" ? "# Options\n" : "{\"version\": ", 0), 0u) << out.substr(0, 80);
      EXPECT_EQ(out.back(), '\n');
    } else {
      EXPECT_EQ(code, 2);
      EXPECT_EQ(err.rfind("dla3d: error: ", 0), 0u);
      EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
    }
  }
  EXPECT_GT(exits[0], 3) << "too few lists printed";
}

}  // namespace
}  // namespace dla
