// dla3d as a user meets it: `dla3d -n N -o PREFIX` writes every file; every bad flag or value
// is one line on stderr, a non-zero exit and no files.

#include "dla/io/mesh_writers.h"
#include "dla/io/csv_reader.h"
#include "dla/run/output.h"
#include "dla/run/presets.h"
#include "dla/run/run.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/shapes.h"
#include "cli_util.h"
#include "mesh_util.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>

namespace {

using dla::testing::ScratchDir;
using dla::testing::read_file;

using dla::testing::CliRun;
using dla::testing::dla3d;
using dla::testing::InterruptedRun;
using dla::testing::cpu_seconds_of_run;
using dla::testing::interrupt_run;

TEST(Cli, WritesEveryFile) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "-n 2000 -o out --rng-seed 5");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* name : {"out.pov", "out.inc", "out.csv", "out.ply", "out.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  EXPECT_NE(run.err.find("grew 2,000 particles"), std::string::npos) << run.err;
  const std::string json = read_file(dir / "out.json");
  EXPECT_NE(json.find("\"rng_seed\": 5"), std::string::npos);
  EXPECT_NE(read_file(dir / "out.pov").find("// dla3d -n 2000 -o out --rng-seed 5"), std::string::npos);
}

// The PLY is binary unless asked for as text; the flag from before --ply-format still works.
TEST(Cli, PlyFormat) {
  ScratchDir dir;
  const auto format_of = [&](const std::string& args) {
    const CliRun run = dla3d(dir, "-n 300 -q --formats ply -o out " + args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const std::string ply = read_file(dir / "out.ply");
    return ply.substr(0, ply.find(" 1.0\n"));
  };
  EXPECT_EQ(format_of(""), "ply\nformat binary_little_endian");
  EXPECT_EQ(format_of("--ply-format ascii"), "ply\nformat ascii");
  EXPECT_EQ(format_of("--binary"), "ply\nformat binary_little_endian");
  const CliRun bad = dla3d(dir, "-n 300 -q --ply-format text -o bad");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "dla3d: error: --ply-format 'text' is not one of binary, ascii\n");
}

TEST(Cli, SameSeedSameFiles) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 1000 -o a -q --seed-at=-5,0,0 --seed-at 5,0,0").exit_code, 0);
  ASSERT_EQ(dla3d(dir, "-n 1000 -o b -q --seed-at=-5,0,0 --seed-at 5,0,0").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("a") + ext)), read_file(dir / (std::string("b") + ext)));
}

TEST(Cli, ThreadsChangeNoFile) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 5000 -o a -q").exit_code, 0);
  ASSERT_EQ(dla3d(dir, "-n 5000 -o b -q --threads 2").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("a") + ext)), read_file(dir / (std::string("b") + ext))) << ext;
  // The sidecar differs only in the command and the timings, which say how the run was spread.
  const auto growth_part = [](const std::string& json) {
    const std::size_t command = json.find("  \"command\""), after = json.find('\n', command) + 1;
    return json.substr(0, command) + json.substr(after, json.find("\"timings\"") - after);
  };
  const std::string a = read_file(dir / "a.json"), b = read_file(dir / "b.json");
  EXPECT_EQ(growth_part(a), growth_part(b));
  EXPECT_NE(a.find("\"command\": \"dla3d -n 5000 -o a -q\""), std::string::npos) << a;
  EXPECT_NE(b.find("\"threads\": 2"), std::string::npos);
}

TEST(Cli, QuietPrintsNothing) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "-n 300 -o q --quiet --dimensions 2 --spawn disk --spawn-axis y");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.err, "");
}

TEST(Cli, GrowsInAMeshWithAHoleAndConvertsIt) {
  ScratchDir dir;
  CliRun run = dla3d(dir, "convert " TEST_DATA_DIR "/open_box.off box.stl");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = dla3d(dir, "--stl box.stl --seeds 2 -n 800 -o in --spacing 0.5");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("box.stl: 10 triangles; merged"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("closed 1 hole"), std::string::npos) << run.err;
  EXPECT_NE(read_file(dir / "in_mesh.inc").find("DLA_Mesh = mesh2"), std::string::npos);
  const std::string json = read_file(dir / "in.json");
  EXPECT_NE(json.find("\"side\": \"inside\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"spawn\": \"surface\""), std::string::npos) << json;
  ASSERT_EQ(dla3d(dir, "--stl box.stl --seeds 2 -n 800 -o again --spacing 0.5 -q --no-scene-mesh").exit_code, 0);
  EXPECT_EQ(read_file(dir / "in.csv"), read_file(dir / "again.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "again_mesh.inc"));
  EXPECT_EQ(read_file(dir / "again.pov").find("DLA_Mesh"), std::string::npos);
}

TEST(Cli, TheMainJobGrowsTwoSeedsInTheBust) {
  DLA_NEED_BUST(bust);
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "convert '" + bust + "' bust.stl").exit_code, 0);
  const CliRun run = dla3d(dir, "--stl bust.stl --seeds 2 -n 3000");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("bust.stl: 25,888 triangles; merged 64,687 duplicate vertices, closed 1 hole"), std::string::npos)
      << run.err;
  const std::string json = read_file(dir / "dla.json");
  EXPECT_NE(json.find("\"closed\": true"), std::string::npos);
  EXPECT_NE(json.find("\"attached\": 3000"), std::string::npos);
  EXPECT_NE(read_file(dir / "dla.pov").find("#declare DLA_Sky = z;"), std::string::npos) << "the bust is z-up";
  const std::string csv = read_file(dir / "dla.csv");
  EXPECT_NE(csv.find(",-1,1,"), std::string::npos) << "no second seed";
}

// The README's main job: the default surface spawn gets walkers into the thin horns, so the
// roots reach their tips (the volume spawn left them three units, 8 spacings, short).
// How near a run's particles come to a horn's tip varies from 0.4 to 2.6 between seeds; over
// three seeds and both horns it is about 0.9 with the surface spawn, and 3.4 with `--spawn
// inside`, whose walkers seldom find their way up a horn.
TEST(Cli, TheMainJobReachesIntoTheBustsHorns) {
  DLA_NEED_BUST(bust);
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "convert '" + bust + "' bust.stl").exit_code, 0);
  // The horns rise from the forehead (y < -6, the face side) on either side of x = 0.
  dla::Vec3 tips[2] = {dla::Vec3(0, 0, -1e9), dla::Vec3(0, 0, -1e9)};
  for (const dla::Vec3& v : dla::read_mesh(bust).vertices)
    if (v.y() < -6.0 && v.z() > tips[v.x() < 0.0].z()) tips[v.x() < 0.0] = v;
  double sum = 0.0;
  for (int seed = 1; seed <= 3; ++seed) {
    const CliRun run = dla3d(dir, "--stl bust.stl --seeds 2 --formats csv -q --rng-seed " + std::to_string(seed));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const dla::Cluster grown = dla::read_csv(dir / "dla.csv");
    ASSERT_EQ(grown.particles.size(), 30002u) << "the default count with a mesh, and two seeds";
    for (const dla::Vec3& tip : tips) {
      double nearest = 1e9;
      for (const dla::Particle& p : grown.particles) nearest = std::min(nearest, (p.position - tip).norm());
      sum += nearest;
    }
  }
  EXPECT_LT(sum / 6.0, 1.6) << "4 spacings of 0.4 from the horns' tips, on average";
}

//! `dla3d ARGS` (words split at spaces), stopped by `signal` once it catches it.
int interrupted(const ScratchDir& dir, const std::string& args, int signal, double work = 0.0,
                const std::string& exists = "") {
  std::vector<std::string> words;
  std::istringstream in(args);
  for (std::string word; in >> word;) words.push_back(word);
  return dla::testing::interrupted(dir, words, signal, work, exists);
}

TEST(Cli, CtrlCKeepsTheWorkAndResumeEndsAsAnUninterruptedRun) {
  ScratchDir dir;
  const std::string run = "-n 150000 -q --rng-seed 3";
  // Interrupted once the first checkpoint is saved: growth is under way (a finished run
  // removes its checkpoint).
  const int code = interrupted(dir, run + " -o part --checkpoint part.ck --checkpoint-every 0.2", SIGINT, 0.0, "part.ck");
  ASSERT_EQ(code, 130) << read_file(dir / "err.txt");
  const std::string err = read_file(dir / "err.txt");
  EXPECT_NE(err.find("stopped by SIGINT after "), std::string::npos) << err;
  EXPECT_NE(err.find("dla3d --resume part.ck"), std::string::npos) << err;
  EXPECT_NE(read_file(dir / "part.json").find("\"complete\": false"), std::string::npos);
  for (const char* name : {"part.csv", "part.ply", "part.pov", "part.inc", "part.ck"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;

  const CliRun resumed = dla3d(dir, "--resume part.ck -q --threads 2");  // the count may change
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "part.ck")) << "a finished run's checkpoint is left behind";
  ASSERT_EQ(dla3d(dir, run + " -o whole").exit_code, 0);
  EXPECT_TRUE(read_file(dir / "part.csv") == read_file(dir / "whole.csv")) << "resumed run differs";
  EXPECT_EQ(dla3d(dir, "--resume part.ck").exit_code, 1) << "the checkpoint is gone";
  EXPECT_EQ(dla3d(dir, "--resume whole.csv").exit_code, 2);
  const CliRun with_count = dla3d(dir, "--resume whole.csv -n 5");
  EXPECT_EQ(with_count.exit_code, 2);
  EXPECT_NE(with_count.err.find("--resume takes no other options but -q, --threads, --stream"), std::string::npos)
      << with_count.err;
}

TEST(Cli, CtrlCWhileTheSolidBuildsKeepsTheOtherFilesAndLeavesNoSolidFile) {
  ScratchDir dir;
  // Interrupted once the CSV is in place: growth has ended and the files are being written,
  // the solid, at a fine voxel, for seconds beside the CSV's hundredths.
  const int code = interrupted(dir, "-n 3000 -q --radius pipe --solid-voxel 0.03 --formats csv,json,stl,vdb -o part",
                               SIGINT, 0.0, "part.csv");
  const std::string err = read_file(dir / "err.txt");
  ASSERT_EQ(code, 130) << err;
  EXPECT_NE(err.find("stopped by SIGINT while the files were written; those finished are whole, no other is written"),
            std::string::npos) << err;
  const std::string json = read_file(dir / "part.json");
  EXPECT_NE(json.find("\"complete\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stopped_in\": \"files\""), std::string::npos) << json;
  EXPECT_TRUE(std::filesystem::exists(dir / "part.csv"));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name.find(".stl") == std::string::npos && name.find(".vdb") == std::string::npos &&
                name.find(".tmp") == std::string::npos) << name << " was left";
  }
}

//! The words of `args`, split at spaces.
std::vector<std::string> words_of(const std::string& args) {
  std::vector<std::string> words;
  std::istringstream in(args);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// Issue 67's case: SIGTERM while the links are made. Growth alone is timed first, so the
// signal comes well after it on any build; the links of 50,000 particles within 100 spacings,
// every pair of them, take many times longer.
TEST(Cli, SigtermWhileTheLinksAreMadeEndsAtOnceAndKeepsTheTree) {
  ScratchDir timed, dir;
  const std::string run = "ballistic -n 50000 -q -o part";
  const double growth = cpu_seconds_of_run(timed, words_of(run + " --formats csv"));
  const InterruptedRun ended =
      interrupt_run(dir, words_of(run + " --formats csv,json,stl --links 100,64"), SIGTERM, 1.5 * growth + 1.0);
  const std::string err = read_file(dir / "err.txt");
  ASSERT_TRUE(ended.signalled) << "the links ended before the signal: " << err;
  ASSERT_EQ(ended.exit_code, 143) << err;
  EXPECT_LT(ended.exit_seconds, 2.0);
  EXPECT_NE(err.find("stopped by SIGTERM while the links were made, after 50,001 particles; the files hold them, "
                     "without links, and no solid: they are made for a whole run"), std::string::npos) << err;
  const std::string json = read_file(dir / "part.json");
  EXPECT_NE(json.find("\"stopped_in\": \"links\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"complete\": false"), std::string::npos) << json;
  const dla::Cluster kept = dla::read_csv(dir / "part.csv");
  EXPECT_EQ(kept.particles.size(), 50001u);
  EXPECT_TRUE(kept.links.empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "part.stl")) << "a stopped run builds no solid";
}

// Issue 67's case: closed venation with a vast influence, SIGTERM while nodes are taken in.
TEST(Cli, SigtermInClosedVenationEndsAtOnceAndKeepsTheTree) {
  ScratchDir dir;
  const InterruptedRun ended = interrupt_run(
      dir, words_of("colonize --venation closed --influence 1000 --attractors 200000 -q --formats csv,json -o part"),
      SIGTERM, 2.0);
  const std::string err = read_file(dir / "err.txt");
  ASSERT_TRUE(ended.signalled) << err;
  ASSERT_EQ(ended.exit_code, 143) << err;
  EXPECT_LT(ended.exit_seconds, 2.0);
  EXPECT_NE(read_file(dir / "part.json").find("\"stopped_in\": \"growth\""), std::string::npos);
  EXPECT_GT(dla::read_csv(dir / "part.csv").particles.size(), 1u);
}

// SIGTERM while a whole run's glb and its levels of detail are written: the writers stop at
// once; those finished stay whole, the others are not there, and nothing half-written is.
TEST(Cli, SigtermWhileTheFilesAreWrittenKeepsOnlyWholeOnes) {
  ScratchDir dir;
  const InterruptedRun ended =
      interrupt_run(dir, words_of("-n 200000 -q --formats csv,glb,json --lod 4 -o part"), SIGTERM, 0.0, "part.csv");
  const std::string err = read_file(dir / "err.txt");
  ASSERT_TRUE(ended.signalled) << err;
  ASSERT_EQ(ended.exit_code, 143) << err;
  EXPECT_LT(ended.exit_seconds, 2.0);
  EXPECT_EQ(dla::read_csv(dir / "part.csv").particles.size(), 200001u);
  EXPECT_FALSE(std::filesystem::exists(dir / "part_lod4.glb")) << "the last level was written, after the signal";
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name << " was left";
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".glb") == 0) {
      const std::string glb = read_file(entry.path());
      std::uint32_t length = 0;
      ASSERT_GE(glb.size(), 12u) << name;
      std::memcpy(&length, glb.data() + 8, 4);
      EXPECT_EQ(length, glb.size()) << name << " is not whole";
    }
  }
}

// The estimates before growth: tubes past a glb's 4.29 GB, and links past the memory free.
TEST(Cli, TubesAndLinksThatCannotFitAreRefusedBeforeGrowth) {
  ScratchDir dir;
  const CliRun glb = dla3d(dir, "-n 10000000 --formats glb -o big", "ulimit -t 20 &&");
  ASSERT_EQ(glb.exit_code, 2) << glb.err;
  EXPECT_EQ(glb.err.rfind("dla3d: error: --formats glb: the tubes of 10,000,000 particles take at least 6.3 GB, past a "
                          "glb's 4.29 GB: 6,882,960 particles fit with these --tube-sides", 0), 0u) << glb.err;
  EXPECT_EQ(std::count(glb.err.begin(), glb.err.end(), '\n'), 1) << glb.err;
  // 10^9 particles with 64 links each could take a terabyte: no machine of ours has that free.
  const CliRun links = dla3d(dir, "ballistic -n 1000000000 --links 2,64 -o big", "ulimit -t 20 &&");
  ASSERT_EQ(links.exit_code, 2) << links.err;
  EXPECT_EQ(links.err.rfind("dla3d: error: --links 2,64 may make 64 links for each of 1,000,000,001 particles, "
                            "1024.1 GB, past the ", 0), 0u) << links.err;
  EXPECT_EQ(std::count(links.err.begin(), links.err.end(), '\n'), 1) << links.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// A solid that no structure of the count asked for can fit is refused before growth: 2 x 10^7
// particles would grow for minutes (the CPU limit ends such a run), and nothing is written.
TEST(Cli, ASolidThatCannotFitIsRefusedBeforeGrowth) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "-n 20000000 --formats csv,json,stl --solid-voxel 0.001 --solid-memory 100 -o big",
                           "ulimit -t 20 &&");
  ASSERT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(run.err.rfind("dla3d: error: the solid of 20,000,000 particles at --solid-voxel 0.001 spacings would take at least ", 0),
            0u) << run.err;
  EXPECT_NE(run.err.find("(--solid-memory): give --solid-voxel "), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Cli, SigtermWritesPartialFiles) {
  ScratchDir dir;
  // Once the first checkpoint is saved, a fifth of a second into growth of some seconds.
  const int code = interrupted(dir, "-n 300000 -o part --checkpoint part.ck --checkpoint-every 0.2", SIGTERM, 0.0, "part.ck");
  EXPECT_EQ(code, 143) << read_file(dir / "err.txt");
  EXPECT_NE(read_file(dir / "part.json").find("\"complete\": false"), std::string::npos);
  const std::string csv = read_file(dir / "part.csv");
  EXPECT_EQ(csv.back(), '\n');
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 256);
}

// Issue 14's cases: numbers at their extremes are one-line errors before anything is written.
TEST(Cli, ExtremeNumbersAreOneLineErrors) {
  const struct {
    const char* args;
    const char* says;
  } cases[] = {
      {"--spacing 1e300", "spacing 1e+300 is not in [1e-25, 1e+25]"},
      {"--spacing 1e-300", "spacing 1e-300 is not in [1e-25, 1e+25]"},
      {"--spacing 4.9e-324", "spacing 4.94066e-324 is not in"},
      {"--spacing inf", "spacing inf is not in"},
      {"--spacing nan", "spacing nan is not in"},
      {"--spacing -0", "spacing -0 is not in"},
      {"--stickiness 1e-300", "--stickiness 1e-300 is not in [0.0001, 1]"},
      {"--min-step 1e-300", "--min-step 1e-300 is not in [0.01, 1]"},
      {"--disk-radius 1e300 --spawn disk", "--disk-radius 1e+300 is not in (0, 1000]"},
      {"--seed-at 1e300,0,0", "seed 1 lies more than 1e+09 spacings from the origin"},
      {"--seed-at nan,0,0", "seed 1 is not finite"},
      {"--spawn box --box 0,0,0,1e300,1,1", "spawn box's max corner lies more than 1e+09 spacings"},
      {"--drift 0,0,nan", "drift length nan is not below 1"},
      {"--tip-radius 1e300", "--tip-radius 1e+300 is not in [0.001, 1000]"},
      {"--base-radius 1e-300", "--base-radius 1e-300 is not in [0.001, 1000]"},
      {"--checkpoint-every nan --checkpoint c.ck", "--checkpoint-every nan is not a number of seconds"},
      // Past what an integer holds: refused as typed, not as a clamped number.
      {"-n 99999999999999999999", "--particles 99999999999999999999 is not in [0, 2e+09]"},
      {"-n 1999999999", "needs about 96 GB of memory"},
      {"--threads 99999999999", "--threads 99999999999 is not in [1, 256]"},
      {"--threads 2.5", "--threads 2.5 is not a whole number"},
      {"--threads 2x", "--threads '2x' is not a whole number"},
      {"--seeds 0 --stl x.stl", "--seeds 0: there must be a seed"},
  };
  for (const auto& c : cases) {
    ScratchDir dir;
    const CliRun run = dla3d(dir, std::string("-q -o out ") + c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args << ": " << run.err;
    EXPECT_EQ(run.err.rfind("dla3d: error: ", 0), 0u) << c.args << ": " << run.err;
    EXPECT_NE(run.err.find(c.says), std::string::npos) << c.args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << c.args << ": " << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << c.args << " left files";
  }
}

// A prefix with spaces and quotes works in every file or is refused before growing: POV-Ray's
// #include cannot name a file with a quote or a backslash; a space is fine, and the command
// line goes into the JSON escaped and into the scene's comment on one line.
TEST(Cli, AwkwardPrefixesWorkEverywhereOrAreRefused) {
  ScratchDir dir;
  for (const char* prefix : {"'we\"ird name'", "'back\\slash'", "\"$(printf 'new\\nline')\""}) {
    const CliRun run = dla3d(dir, std::string("-n 100 -q -o ") + prefix);
    EXPECT_EQ(run.exit_code, 2) << prefix << ": " << run.err;
    EXPECT_NE(run.err.find("which POV-Ray's #include cannot name"), std::string::npos) << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << prefix << " left files";
  }
  // A number may have white space before it, a newline too: the echoes stay one line.
  ASSERT_EQ(dla3d(dir, "-n 100 -q -o 'with space' --seed-at \"$(printf '1,\\n0,0')\"").exit_code, 0);
  const std::string pov = read_file(dir / "with space.pov");
  EXPECT_EQ(pov.rfind("// dla3d -n 100 -q -o 'with space' --seed-at '1,\\x0a0,0'\n", 0), 0u) << pov;
  EXPECT_NE(pov.find("#include \"with space.inc\""), std::string::npos);
  EXPECT_NE(read_file(dir / "with space.json")
                .find("\"command\": \"dla3d -n 100 -q -o 'with space' --seed-at '1,\\u000a0,0'\""),
            std::string::npos);
}

// A run that cannot go on keeps what grew, as Ctrl-C does: the files, marked incomplete, then
// the message on one line, then exit 1.
TEST(Cli, AnErrorDuringGrowthKeepsWhatGrew) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "--spawn box --box -2,-2,-2,2,2,2 -n 1000 -o filled");
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(run.err.rfind("dla3d: error: no free start in 1000000 draws from the box spawn: the structure fills it; "
                          "filled.* hold the ", 0), 0u) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  const std::string json = read_file(dir / "filled.json");
  EXPECT_NE(json.find("\"complete\": false"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stopped_by\": \"error: no free start"), std::string::npos) << json;
  const std::string csv = read_file(dir / "filled.csv");
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 20) << "the particles grown before the error are lost";

  const CliRun away = dla3d(dir, "--drift 0,0.9,0 --spawn disk --spawn-axis y -n 10 -o away");
  EXPECT_EQ(away.exit_code, 1) << away.err;
  EXPECT_NE(away.err.find("the drift carries them away"), std::string::npos) << away.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "away.csv"));
}

// 2D DLA of 10^6 particles stopped at 3 x 10^5 with "beyond 512 grid cells" and wrote nothing.
TEST(Cli, TheGridHoldsAMillionParticlesIn2D) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "-n 1000000 --dimensions 2 -q -o flat --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(read_file(dir / "flat.json").find("\"attached\": 1000000"), std::string::npos);
}

// A stop request ends a run wherever it is, here inside walks that touch the structure ten
// thousand times before they stick: 256 particles take seconds, and the run stops long
// before.
TEST(Cli, SigtermStopsInsideAWalk) {
  ScratchDir dir;
  EXPECT_EQ(interrupted(dir, "-n 100000 --stickiness 1e-4 -q -o slow --formats json", SIGTERM, 0.3), 143)
      << read_file(dir / "err.txt");
  const std::string json = read_file(dir / "slow.json");
  EXPECT_NE(json.find("\"stopped_by\": \"SIGTERM\""), std::string::npos) << json;
  const std::size_t at = json.find("\"attached\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_LT(std::stoul(json.substr(at + 12)), 256u) << json;
}

// Every malformed mesh: one line naming the file and the fault, exit 2, no files written.
TEST(Cli, MalformedMeshesAreOneLineErrors) {
  std::string binary(84, '\0');
  binary[80] = 2;  // two triangles counted, none there
  std::string absurd(84 + 50, '\0');
  absurd[80] = absurd[81] = absurd[82] = absurd[83] = '\xff';  // 4,294,967,295 triangles
  std::string nan_stl(84, '\0');
  nan_stl[80] = 1;
  nan_stl += std::string(12, '\0') + std::string("\x00\x00\xc0\x7f", 4) + std::string(34, '\0');  // x = NaN
  std::string random_bytes;
  for (int i = 0; i < 1000; ++i) random_bytes += static_cast<char>((i * 7919 + 13) % 251);
  const struct {
    const char* name;
    std::string bytes;
    const char* says;
  } cases[] = {
      {"empty.stl", "", "is empty"},
      {"header.stl", std::string(84, '\0'), "has no triangles"},
      {"header.off", "OFF\n", "no vertex, face and edge counts"},
      {"truncated.stl", binary + std::string(60, '\0'), "not a valid binary STL"},
      {"overlong.stl", binary + std::string(150, '\0'), "counts 2 triangles, 184 bytes, but the file has 234"},
      {"absurd.stl", absurd, "4294967295 triangles"},
      {"absurd.off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n", "more than its"},
      {"nan.stl", nan_stl, "not a finite number"},
      {"inf.off", "OFF\n3 1 0\n0 0 inf\n1 0 0\n0 1 0\n3 0 1 2\n", "not a finite number"},
      {"garbage.stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 zero\n", "a vertex needs 3 numbers"},
      {"cut.stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n", "ends in the middle"},
      {"random.stl", random_bytes, "STL"},
      {"random.ply", random_bytes, "is not a PLY file"},
      {"random.obj", random_bytes, "has no triangles"},
      {"notes.off", "These are my notes, not a mesh.\n", "does not begin with OFF"},
      {"flat.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n3 2 1 0\n", "degenerate"},
  };
  for (const auto& c : cases) {
    ScratchDir dir;
    std::ofstream(dir / c.name, std::ios::binary) << c.bytes;
    const CliRun run = dla3d(dir, std::string("--stl ") + c.name + " -n 50 -q -o out");
    EXPECT_EQ(run.exit_code, 2) << c.name << ": " << run.err;
    EXPECT_EQ(run.err.rfind(std::string("dla3d: error: ") + c.name + ": ", 0), 0u) << c.name << ": " << run.err;
    EXPECT_NE(run.err.find(c.says), std::string::npos) << c.name << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << c.name << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csv")) << c.name;
  }
}

// Valid but awkward files grow: binary STL whose header says "solid", ASCII with CRLF, half
// the triangles flipped with zeroed normals.
TEST(Cli, AwkwardButValidMeshesGrow) {
  ScratchDir dir;
  const dla::TriangleMesh sphere = dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24);
  dla::write_stl(sphere, dir / "plain.stl");
  std::string solid = read_file(dir / "plain.stl");
  solid.replace(0, 12, "solid sphere");
  std::ofstream(dir / "solid.stl", std::ios::binary) << solid;
  std::string crlf = "solid sphere\r\n", flipped = "solid sphere\n";
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    auto tri = sphere.triangles[t];
    const auto facet = [&](std::string& out, const char* end) {
      out += std::string(" facet normal 0 0 0") + end + "  outer loop" + end;
      for (std::uint32_t id : tri) {
        const dla::Vec3& v = sphere.vertices[id];
        out += "   vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + end;
      }
      out += std::string("  endloop") + end + " endfacet" + end;
    };
    facet(crlf, "\r\n");
    if (t % 2) std::swap(tri[1], tri[2]);
    facet(flipped, "\n");
  }
  std::ofstream(dir / "crlf.stl", std::ios::binary) << crlf << "endsolid sphere\r\n";
  std::ofstream(dir / "flipped.stl", std::ios::binary) << flipped << "endsolid sphere\n";
  for (const char* name : {"solid.stl", "crlf.stl", "flipped.stl"}) {
    const CliRun run = dla3d(dir, std::string("--stl ") + name + " -n 300 -o " + name + " --spacing 0.5");
    EXPECT_EQ(run.exit_code, 0) << name << ": " << run.err;
    EXPECT_NE(run.err.find("grew 300 particles"), std::string::npos) << name << ": " << run.err;
  }
}

TEST(Cli, AnalyzeMeasuresAGrownStructure) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 20000 -q -o grown --spacing 0.5").exit_code, 0);
  const std::string command = "cd '" + dir.path().string() + "' && '" DLA3D_PATH "' analyze grown.csv > out.json";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string json = read_file(dir / "out.json");
  EXPECT_NE(json.find("\"particles\": 20001"), std::string::npos) << json;
  EXPECT_NE(json.find("\"spacing\": 0.5"), std::string::npos) << json;
  const auto value = [&](const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\": ");
    return at == std::string::npos ? 0.0 : std::atof(json.c_str() + at + key.size() + 4);
  };
  EXPECT_NEAR(value("fractal_dimension_gyration"), 2.5, 0.2) << json;
  EXPECT_NEAR(value("fractal_dimension_mass_radius"), 2.5, 0.25) << json;
  EXPECT_NE(read_file(dir / "grown.json").find("\"fractal_dimension_mass_radius\": 2."), std::string::npos);
  const CliRun bad = dla3d(dir, "analyze grown.json");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("is not a dla3d CSV"), std::string::npos) << bad.err;
}

// dla3d frames: K numbered files of each format, frame k the seeds and the first k/K of the
// rest in attach order; the last is the whole structure, byte for byte in the CSV.
TEST(Cli, FramesWriteTheStructureAsItGrew) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 500 -q -o grown --formats csv,glb --seed-at 0,0,0 --seed-at 30,0,0").exit_code, 0);
  const CliRun run = dla3d(dir, "frames grown.csv --count 4 --formats csv,ply,glb");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("wrote 4 frames of growth, grown_0001.* to grown_0004.*"), std::string::npos) << run.err;
  const dla::Cluster whole = dla::read_csv(dir / "grown.csv");
  for (int k = 1; k <= 4; ++k) {
    SCOPED_TRACE(k);
    const std::string frame = "grown_000" + std::to_string(k);
    for (const char* ext : {".ply", ".glb"}) EXPECT_FALSE(read_file(dir / (frame + ext)).empty()) << ext;
    const dla::Cluster part = dla::read_csv(dir / (frame + ".csv"));
    ASSERT_EQ(part.particles.size(), 2u + 500u * k / 4);
    EXPECT_EQ(part.seed_count, 2u);
    for (std::size_t i = 0; i < part.particles.size(); ++i) {
      EXPECT_EQ(part.particles[i].position, whole.particles[i].position);
      EXPECT_EQ(part.particles[i].parent, whole.particles[i].parent);
    }
  }
  EXPECT_EQ(read_file(dir / "grown_0004.csv"), read_file(dir / "grown.csv"));
  EXPECT_EQ(read_file(dir / "grown_0004.glb"), read_file(dir / "grown.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "grown_0005.csv"));
  // -o names them; glb by default.
  ASSERT_EQ(dla3d(dir, "frames grown.csv --count 2 -o film -q").exit_code, 0);
  EXPECT_FALSE(read_file(dir / "film_0002.glb").empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "film_0001.csv"));
  for (const char* bad : {"frames grown.csv --count 0", "frames grown.csv --formats json", "frames grown.csv --formats svg",
                          "frames grown.csv --radius boundary", "frames"}) {
    const CliRun refused = dla3d(dir, bad);
    EXPECT_EQ(refused.exit_code, 2) << bad;
    EXPECT_EQ(refused.err.rfind("dla3d: error: ", 0), 0u) << refused.err;
  }
}

TEST(Cli, HelpAndVersion) {
  ScratchDir dir;
  EXPECT_EQ(dla3d(dir, "--help").exit_code, 0);
  EXPECT_EQ(dla3d(dir, "--version").exit_code, 0);
}

TEST(Cli, BadInputIsOneLineAndNoFiles) {
  const char* cases[] = {
      "-n -5",
      "-n lots",
      "--stickiness 1.7",
      "--stickiness 0",
      "--spacing 0",
      "--spawn cube",
      "--index octree",
      "--threads 0",
      "--threads 2 --index kdtree",
      "--dimensions 4",
      "--seed-at 1,2",
      "--seed-at 0,0,0 --seed-at 0.5,0,0",
      "--box 0,0,0,1,1,1",
      "--spawn box --box 1,1,1,0,0,0",
      "--drift 0,0,2",
      "--tip-radius -1",
      "--no-such-flag",
      "-o missing-folder/out",
      "-o ''",
      "--stl no-such.stl",
      "--stl " TEST_DATA_DIR "/open_box.off --side sideways",
      "--stl " TEST_DATA_DIR "/open_box.off --constraint bend",
      "--stl " TEST_DATA_DIR "/open_box.off --seed-at 50,50,50",
      "--stl " TEST_DATA_DIR "/open_box.off --seeds 2 --seed-at 1,1,1",
      "--stl " TEST_DATA_DIR "/open_box.off --side both",
      "--stl " TEST_DATA_DIR "/open_box.off --spawn radial --side outside",
      "--seeds 2",
      "--spawn inside",
      "--spawn surface",
      "--stl " TEST_DATA_DIR "/open_box.off --spawn surface --side both --seed-at 1,1,1",
      "--stl " TEST_DATA_DIR "/../constraint_test.cpp",
      "--up w",
  };
  for (const char* args : cases) {
    ScratchDir dir;
    const CliRun run = dla3d(dir, std::string("-n 100 -q -o out ") + args);
    EXPECT_NE(run.exit_code, 0) << args;
    EXPECT_EQ(run.err.rfind("dla3d: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << args << " left files";
  }
}

TEST(Cli, ColonizeWritesTheSameFilesAsGrowth) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "colonize -o tree --attractors 2000 --attractor-radius 25 --noise 0.3,5 --rng-seed 3");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("dla3d: grew "), std::string::npos) << run.err;
  for (const char* name : {"tree.pov", "tree.inc", "tree.csv", "tree.ply", "tree.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  const dla::Cluster tree = dla::read_csv(dir / "tree.csv");
  ASSERT_GT(tree.particles.size(), 300u);
  EXPECT_EQ(tree.seed_count, 1u);
  // The default root: the attractors' lowest point.
  EXPECT_EQ(tree.particles[0].position, dla::Vec3(0, -25, 0));
  const std::string json = read_file(dir / "tree.json");
  EXPECT_NE(json.find("\"model\": \"colonize\""), std::string::npos);
  EXPECT_NE(json.find("\"influence\": 0,"), std::string::npos) << "unbounded";
  EXPECT_NE(json.find("\"particles\": " + std::to_string(tree.particles.size())), std::string::npos);
  // The same seed, the same bytes; three roots on the sphere around the attractors; 2D.
  ASSERT_EQ(dla3d(dir, "colonize -q -o again --attractors 2000 --attractor-radius 25 --noise 0.3,5 --rng-seed 3").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("tree") + ext)), read_file(dir / (std::string("again") + ext))) << ext;
  ASSERT_EQ(dla3d(dir, "colonize -q -o three --roots 3 --attractors 1500 --attractor-radius 20").exit_code, 0);
  const dla::Cluster three = dla::read_csv(dir / "three.csv");
  ASSERT_EQ(three.seed_count, 3u);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(three.particles[r].position.norm(), 20.0, 1e-9);
  ASSERT_EQ(dla3d(dir, "colonize -q -o wide --roots 3 --roots-scale 1.5 --attractors 1500 --attractor-radius 20").exit_code, 0);
  const dla::Cluster wide = dla::read_csv(dir / "wide.csv");
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(wide.particles[r].position.norm(), 30.0, 1e-9);
  ASSERT_EQ(dla3d(dir, "colonize -q -o leaf --dimensions 2 --attractors-in box --attractor-box -20,-20,0,20,20,0 "
                       "--influence 6 --formats svg,csv,json").exit_code, 0);
  for (const dla::Particle& p : dla::read_csv(dir / "leaf.csv").particles) ASSERT_EQ(p.position.z(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "leaf.svg"));
}

// Every file option refuses a folder, a FIFO (which a reader would wait on for ever) and a
// device that never ends, in one line naming the option, before anything is written; an
// endless device is never read to its end. The `timeout` is only a bound against a hang.
TEST(Cli, SpecialFilesAreRefusedInOneLineNamingTheOption) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  std::filesystem::create_directory(dir / "folder.stl");
  ASSERT_EQ(mkfifo((dir / "pipe.stl").c_str(), 0644), 0);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
  // Each special file and what it is; each command line (F for the file) and the option it names.
  const std::pair<const char*, const char*> specials[] = {
      {"folder.stl", "a folder"}, {"pipe.stl", "a pipe (FIFO)"}, {"zero.stl", "a device"}};
  const std::pair<const char*, std::string> options[] = {
      {"--stl F -n 10 -o out", "--stl"},
      {"--stl ball.stl --seed-mesh F -n 10 -o out", "--seed-mesh"},
      {"--leaf F --formats glb -n 10 -o out", "--leaf"},
      {"--text A --font F -n 10 -o out", "--font"},
      {"colonize --attractors-from F -n 10 -o out", "--attractors-from"},
      {"colonize --collide F --attractors 50 -n 10 -o out", "--collide"},
      {"colonize --stl F --attractors 50 -n 10 -o out", "--stl"},
      {"drop --stl F -n 10 -o out", "--stl"},
      {"eden --mode drop --mask F -n 10 -o out", "--mask"},
      {"--resume F", "--resume"},
      {"frames F -o out", ""},
      {"analyze F", ""},
  };
  for (const auto& [file, kind] : specials)
    for (const auto& [command, option] : options) {
      std::string args = command;
      args.replace(args.find('F'), 1, file);
      SCOPED_TRACE("dla3d " + args);
      const CliRun run = dla3d(dir, args, "timeout -s KILL 60");
      ASSERT_EQ(run.exit_code, 2) << run.err;
      const std::string says = (option.empty() ? "" : option + " ") + "'" + file + "' is " + kind + ", not a file";
      EXPECT_NE(run.err.find(says), std::string::npos) << run.err;
      EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
      EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
    }
}

// Closed venation grows without --influence: 4 times the kill distance, which the JSON records.
TEST(Cli, ClosedVenationGrowsWithADefaultInfluence) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "colonize --venation closed -q -n 2000 --formats csv,json -o veins");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string json = read_file(dir / "veins.json");
  EXPECT_NE(json.find("\"influence\": 8,"), std::string::npos) << json;  // the kill distance is 2
  EXPECT_NE(json.find("\"venation\": \"closed\""), std::string::npos) << json;
  EXPECT_GT(dla::read_csv(dir / "veins.csv").particles.size(), 1000u);
}

TEST(Cli, ColonizeGrowsInAVesselAndReadsItsAttractorsFromAFile) {
  ScratchDir dir;
  const dla::Vec3 lo(-10, -10, -10), hi(10, 10, 10);
  dla::write_stl(dla::make_box(lo, hi), dir / "box.stl");
  const CliRun run = dla3d(dir, "colonize -q -o vessel --stl box.stl --attractors-in mesh --attractors 1500 --roots 2 "
                                "--roots-in mesh --tropism 0,1,0 --radius boundary");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster tree = dla::read_csv(dir / "vessel.csv");
  ASSERT_GT(tree.particles.size(), 300u);
  EXPECT_EQ(tree.seed_count, 2u);
  for (const dla::Particle& p : tree.particles)
    ASSERT_TRUE((p.position.array() > lo.array()).all() && (p.position.array() < hi.array()).all());
  EXPECT_NE(read_file(dir / "vessel.json").find("\"stl\": \"box.stl\""), std::string::npos);
  EXPECT_NE(read_file(dir / "vessel_mesh.inc").find("DLA_Mesh"), std::string::npos) << "the vessel shows in the scene";

  // dla3d's own CSV as attractors, a sample of 300; the root is the lowest of them.
  ASSERT_EQ(dla3d(dir, "colonize -q -o again --attractors-from vessel.csv --attractors 300").exit_code, 0);
  const std::string json = read_file(dir / "again.json");
  EXPECT_NE(json.find("\"attractors\": 300,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"attractors_from\": \"vessel.csv\""), std::string::npos) << json;
  const dla::Vec3 root = dla::read_csv(dir / "again.csv").particles[0].position;
  EXPECT_TRUE(std::any_of(tree.particles.begin(), tree.particles.end(),
                          [&](const dla::Particle& p) { return p.position == root; }));
}

TEST(Cli, EdenWritesTheSameFilesAsGrowth) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "eden -o sq -n 3000 --rng-seed 4");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("dla3d: grew 3,000 sites on a square4 lattice"), std::string::npos) << run.err;
  for (const char* name : {"sq.pov", "sq.inc", "sq.csv", "sq.ply", "sq.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  const dla::Cluster square = dla::read_csv(dir / "sq.csv");
  ASSERT_EQ(square.particles.size(), 3000u);
  for (const dla::Particle& p : square.particles) ASSERT_EQ(p.position.z(), 0.0);
  const std::string json = read_file(dir / "sq.json");
  EXPECT_NE(json.find("\"model\": \"eden\""), std::string::npos);
  EXPECT_NE(json.find("\"lattice\": \"square4\""), std::string::npos);
  ASSERT_EQ(dla3d(dir, "eden -q -o again -n 3000 --rng-seed 4").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("sq") + ext)), read_file(dir / (std::string("again") + ext))) << ext;

  // 3D, and a mask drawn in a file: the two sites to the left and the one above them.
  ASSERT_EQ(dla3d(dir, "eden -q -o cube --dimensions 3 -n 2000 --formats csv,json").exit_code, 0);
  EXPECT_NE(read_file(dir / "cube.json").find("\"lattice\": \"cubic6\""), std::string::npos);
  std::ofstream(dir / "lean.txt") << "; leans right\n.x.\nxxo\n";
  ASSERT_EQ(dla3d(dir, "eden -q -o lean --mode drop --mask lean.txt -n 500 --formats csv,json,svg").exit_code, 0);
  const std::string lean = read_file(dir / "lean.json");
  EXPECT_NE(lean.find("\"mask_sites\": [[-1, 1, 0], [-2, 0, 0], [-1, 0, 0]]"), std::string::npos) << lean;
  EXPECT_NE(lean.find("\"mask\": \"lean.txt\""), std::string::npos) << lean;
  for (const dla::Particle& p : dla::read_csv(dir / "lean.csv").particles) ASSERT_GE(p.position.x(), 0.0);

  // A threshold no site can meet: growth ends early, and says so.
  const CliRun stalled = dla3d(dir, "eden -o alone --mode drop --mask B --mask-threshold 2 -n 50 --formats json");
  ASSERT_EQ(stalled.exit_code, 0) << stalled.err;
  EXPECT_NE(stalled.err.find("grew 1 sites on a square4 lattice in "), std::string::npos) << stalled.err;
  EXPECT_NE(stalled.err.find("(then no site could stick)"), std::string::npos) << stalled.err;
}

TEST(Cli, EdenStopsOnSigintWithTheClusterSoFar) {
  ScratchDir dir;
  const int code = interrupted(dir, "eden -n 1000000000 -q -o part --formats ply,json", SIGINT, 0.2);
  ASSERT_EQ(code, 130) << read_file(dir / "err.txt");
  EXPECT_NE(read_file(dir / "err.txt").find("stopped by SIGINT after "), std::string::npos);
  const std::string json = read_file(dir / "part.json");
  EXPECT_NE(json.find("\"complete\": false"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stopped_by\": \"SIGINT\""), std::string::npos) << json;
}

// Ctrl-C stops dla3d frames between frames: exit 130, and every frame written is whole.
TEST(Cli, FramesStopOnSigintBetweenFrames) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 20000 -q -o grown --formats csv").exit_code, 0);
  // The signal once the first frame is whole (written, then renamed into place): an event, where
  // a span of processor time need not reach it under a sanitizer.
  const int code = interrupted(dir, "frames grown.csv --count 100000 -q --formats ply", SIGINT, 0.0, "grown_000001.ply");
  ASSERT_EQ(code, 130) << read_file(dir / "err.txt");
  EXPECT_NE(read_file(dir / "err.txt").find("stopped by SIGINT after "), std::string::npos) << read_file(dir / "err.txt");
  std::size_t frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("grown_", 0) != 0) continue;
    ASSERT_EQ(entry.path().extension(), ".ply") << name << ": a temporary file left behind";
    const std::string ply = read_file(entry.path());
    ASSERT_NE(ply.find("end_header\n"), std::string::npos) << name;
    ++frames;
  }
  EXPECT_GT(frames, 0u);
}

TEST(Cli, EdenBadInputIsOneLineAndNoFiles) {
  const char* cases[] = {
      "-n 0", "--dimensions 4", "--lattice square5", "--lattice cubic6 --dimensions 2", "--mode random",
      "--mask B", "--mask-threshold 2", "--mode drop --mask-threshold 0", "--mode drop --mask D --mask-threshold 25",
      "--seed-radius 101", "--spacing 0", "--formats svg --dimensions 3", "--radius boundary", "--attractors 5",
      // A mask that cannot be read: exit 1.
      "--mode drop --mask missing.txt",
  };
  for (const char* args : cases) {
    ScratchDir dir;
    const CliRun run = dla3d(dir, std::string("eden -q -o out ") + args);
    EXPECT_EQ(run.exit_code, std::string(args).find("missing") != std::string::npos ? 1 : 2) << args;
    EXPECT_EQ(run.err.rfind("dla3d: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << args << " left files";
  }
}

TEST(Cli, ColonizeBadInputIsOneLineAndNoFiles) {
  const char* cases[] = {
      "--kill-distance 0.5", "--influence 1", "--noise 1", "--noise 11,1", "--tropism 0,0,20", "--attractors 0",
      "--attractors-in cone", "--attractor-radius 0", "--attractor-box 0,0,0,1,1,1", "--root-at 1,2",
      "--roots -1", "--roots 2 --root-at 0,0,0", "-n 0", "--max-iterations 0", "--dimensions 2 --root-at 0,0,1",
      "--spacing 1e-100", "--particles 10", "--radius boundary", "--formats svg", "--attractors-in mesh",
      "--roots-in mesh", "--attractors-from a.csv --attractors-in box", "--roots-scale 2", "--roots 2 --roots-scale 0",
      // Files that cannot be read: exit 1.
      "--attractors-from missing.csv", "--stl missing.stl", "--collide missing.stl --roots 2 --roots-in surface",
  };
  for (const char* args : cases) {
    ScratchDir dir;
    const CliRun run = dla3d(dir, std::string("colonize -q -o out ") + args);
    EXPECT_EQ(run.exit_code, std::string(args).find("missing") != std::string::npos ? 1 : 2) << args;
    EXPECT_EQ(run.err.rfind("dla3d: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << args << " left files";
  }
}

}  // namespace

TEST(Cli, DropAndBallisticWriteTheSameFilesAsGrowth) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "drop -o rain -n 2000 --rng-seed 4");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("dla3d: grew 2,000 particles from "), std::string::npos) << run.err;
  for (const char* name : {"rain.pov", "rain.inc", "rain.csv", "rain.ply", "rain.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  ASSERT_EQ(dla::read_csv(dir / "rain.csv").particles.size(), 2001u);
  const std::string json = read_file(dir / "rain.json");
  EXPECT_NE(json.find("\"model\": \"drop\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"zone_radius\": 0,"), std::string::npos) << "growing: " << json;
  EXPECT_NE(json.find("\"on_structure\": "), std::string::npos) << json;
  ASSERT_EQ(dla3d(dir, "drop -q -o again -n 2000 --rng-seed 4").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("rain") + ext)), read_file(dir / (std::string("again") + ext))) << ext;

  // The paper's biased drops in 2D, as PNG pictures.
  for (const char* bias : {"circle", "same:5", "offset:20,3"}) {
    const CliRun biased = dla3d(dir, std::string("drop -q -o biased --dimensions 2 --zone-radius 40 -n 800 --formats png,json --drop ") + bias);
    ASSERT_EQ(biased.exit_code, 0) << bias << ": " << biased.err;
    EXPECT_NE(read_file(dir / "biased.json").find(std::string("\"drop\": \"") + bias + "\""), std::string::npos) << bias;
    EXPECT_GT(std::filesystem::file_size(dir / "biased.png"), 1000u);
  }

  // Inside a mesh, dropped inside it: every particle stays inside the sphere.
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  const CliRun inside = dla3d(dir, "drop -o held --stl ball.stl --zone mesh -n 600 --formats csv,json");
  ASSERT_EQ(inside.exit_code, 0) << inside.err;
  for (const dla::Particle& p : dla::read_csv(dir / "held.csv").particles) ASSERT_LT(p.position.norm(), 10.0);
  EXPECT_NE(read_file(dir / "held.json").find("\"stl\": \"ball.stl\""), std::string::npos);
  const CliRun layered = dla3d(dir, "drop -q -o layered --stl ball.stl --side surface -n 50");
  EXPECT_EQ(layered.exit_code, 2) << "shells are for DLA: " << layered.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "layered.csv"));

  const CliRun flown = dla3d(dir, "ballistic -o lines -n 2000 --dimensions 2 --formats csv,json,svg");
  ASSERT_EQ(flown.exit_code, 0) << flown.err;
  EXPECT_NE(flown.err.find("dla3d: grew 2,000 particles from "), std::string::npos) << flown.err;
  const std::string lines = read_file(dir / "lines.json");
  EXPECT_NE(lines.find("\"model\": \"ballistic\""), std::string::npos) << lines;
  EXPECT_NE(lines.find("\"direction\": [0, 0, 0]"), std::string::npos) << "random: " << lines;
  ASSERT_EQ(dla3d(dir, "ballistic -q -o rained -n 1000 --direction 0,0,-1 --formats csv,json").exit_code, 0);
  EXPECT_NE(read_file(dir / "rained.json").find("\"direction\": [0, 0, -1]"), std::string::npos);
}

TEST(Cli, DropAndBallisticStopOnSigintWithTheStructureSoFar) {
  for (const char* model : {"drop", "ballistic"}) {
    ScratchDir dir;
    const int code = interrupted(dir, std::string(model) + " -n 1000000000 -q -o part --formats ply,json", SIGINT, 0.2);
    ASSERT_EQ(code, 130) << read_file(dir / "err.txt");
    EXPECT_NE(read_file(dir / "err.txt").find("stopped by SIGINT after "), std::string::npos);
    const std::string json = read_file(dir / "part.json");
    EXPECT_NE(json.find("\"complete\": false"), std::string::npos) << json;
  }
}

TEST(Cli, DropAndBallisticBadInputIsOneLineAndNoFiles) {
  const char* cases[] = {
      "drop --dimensions 4", "drop --zone cone", "drop --zone mesh", "drop --zone-radius 0.5", "drop --zone-margin 0",
      "drop --zone-box 0,0,0,1,1", "drop --zone-box 1,1,1,0,0,0 --zone box", "drop --zone-box 0,0,0,1,1,1",
      "drop --drop same:0", "drop --drop offset:3", "drop --drop rain", "drop --stickiness 0", "drop --side outside",
      "drop --seed-at 0,0,1 --dimensions 2", "drop --seed-at 0,0,0 --seed-at 0.5,0,0", "drop -n -1", "drop --spacing 0",
      "drop --formats png", "drop --radius boundary", "ballistic --direction 0,0,nan", "ballistic --direction 1,2",
      "ballistic --dimensions 2 --direction 0,0,1", "ballistic --zone ball", "ballistic --formats svg",
      // A mesh that cannot be read: exit 1.
      "drop --stl missing.stl",
  };
  for (const char* args : cases) {
    ScratchDir dir;
    const std::string words(args);
    const CliRun run = dla3d(dir, words.substr(0, words.find(' ')) + " -q -o out" + words.substr(words.find(' ')));
    EXPECT_EQ(run.exit_code, words.find("missing") != std::string::npos ? 1 : 2) << args;
    EXPECT_EQ(run.err.rfind("dla3d: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << args << " left files";
  }
}

//! Each of `cases`, after `-q -o bad -n 50`, is refused as bad input: exit 2, one line, no file.
void expect_refused(const ScratchDir& dir, std::initializer_list<const char*> cases) {
  for (const char* args : cases) {
    const CliRun run = dla3d(dir, std::string("-q -o bad -n 50 ") + args);
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.csv")) << args;
  }
}

// A plane cluster of 10^8 particles reaches about 40,000 spacings from its seed. Two seeds
// 60,000 spacings apart need the grid that far from the first: it holds them, and grows both.
TEST(Cli, PlaneGrowthReachesAsFarAsTenToTheEightParticlesDo) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "-q --dimensions 2 --seed-at -30000,0,0 --seed-at 30000,0,0 -n 300 -o far --formats csv");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster far = dla::read_csv(dir / "far.csv");
  ASSERT_EQ(far.particles.size(), 302u);
  std::array<int, 2> grown{0, 0};
  for (std::size_t i = 2; i < far.particles.size(); ++i) ++grown[far.particles[i].seed];
  EXPECT_GT(grown[0], 50);
  EXPECT_GT(grown[1], 50);
}

TEST(Cli, RotateTurnsTheSpawnAndIsRefusedWithAMesh) {
  ScratchDir dir;
  const CliRun turned = dla3d(dir, "-q -o turned -n 500 --spawn disk --spawn-axis x --rotate z,90 --formats csv,json");
  ASSERT_EQ(turned.exit_code, 0) << turned.err;
  const std::string json = read_file(dir / "turned.json");
  EXPECT_NE(json.find("\"rotate\": \"z,90\""), std::string::npos) << json;
  ASSERT_EQ(dla3d(dir, "-q -o straight -n 500 --spawn disk --spawn-axis x --formats csv").exit_code, 0);
  EXPECT_NE(read_file(dir / "turned.csv"), read_file(dir / "straight.csv"));
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  expect_refused(dir, {"--stl ball.stl --rotate y,30", "--rotate y", "--rotate q,30", "--rotate z,4e4",
                       "--dimensions 2 --rotate x,10"});
}

TEST(Cli, FillGrowsUntilTheMeshIsCovered) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  const CliRun run = dla3d(dir, "--stl ball.stl --fill 0.5 -o filled --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("% of the mesh's volume within 3 spacings of it"), std::string::npos) << run.err;
  const std::string json = read_file(dir / "filled.json");
  EXPECT_NE(json.find("\"fill\": 0.5"), std::string::npos) << json;
  EXPECT_NE(json.find("\"spawn\": \"inside\""), std::string::npos) << json;  // the default when filling
  const std::size_t at = json.find("\"filled\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_GE(std::stod(json.substr(at + 10)), 0.5);
  EXPECT_NE(json.find("\"complete\": true"), std::string::npos) << json;
  EXPECT_LT(dla::read_csv(dir / "filled.csv").particles.size(), 1000000u);  // stopped long before its cap, 10^7
  expect_refused(dir, {"--fill 0.5", "--stl ball.stl --fill-distance 2", "--stl ball.stl --fill 1.5",
                       "--stl ball.stl --fill 0.5 --side outside --seed-at 20,0,0"});
}

TEST(Cli, SeedSurfaceStartsFromTheWholeSurface) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  const CliRun run = dla3d(dir, "-q --stl ball.stl --spacing 0.5 --seed-surface -n 500 -o lined --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster lined = dla::read_csv(dir / "lined.csv");
  EXPECT_GT(lined.seed_count, 1000u);  // about 5,000 spacings² of surface
  EXPECT_EQ(lined.particles.size(), lined.seed_count + 500);
  for (std::size_t i = 0; i < lined.seed_count; ++i) ASSERT_EQ(lined.particles[i].parent, -1);
  const std::string json = read_file(dir / "lined.json");
  EXPECT_NE(json.find("\"seeds\": " + std::to_string(lined.seed_count)), std::string::npos) << json.substr(0, 2000);
  expect_refused(dir, {"--seed-surface", "--stl ball.stl --seed-surface --seeds 2",
                       "--stl ball.stl --seed-surface --seed-at 0,0,0", "--stl ball.stl --seed-surface --side both"});
}

TEST(Cli, TextGrowsInEachLetter) {
  ScratchDir dir;
  const CliRun run = dla3d(dir, "--text DLA -n 600 -o text --formats csv,json,pov");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("dla3d: the text 'DLA': "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("spacing 1\n"), std::string::npos) << run.err;  // a hundredth of the em
  const dla::Cluster grown = dla::read_csv(dir / "text.csv");
  ASSERT_EQ(grown.seed_count, 3u);  // one in each letter
  std::vector<std::size_t> per_seed(3, 0);
  for (const dla::Particle& p : grown.particles) {
    ++per_seed[static_cast<std::size_t>(p.seed)];
    EXPECT_GT(p.position.z(), 0.0);
    EXPECT_LT(p.position.z(), 25.0);
  }
  for (const std::size_t n : per_seed) EXPECT_GT(n, 20u) << "every letter grows";
  EXPECT_NE(read_file(dir / "text.pov").find("#declare DLA_Sky = y;"), std::string::npos) << "upright";
  const CliRun lines = dla3d(dir, "-q --text 'A\\nB' --seeds 2 -n 100 -o lines --formats csv");
  ASSERT_EQ(lines.exit_code, 0) << lines.err;
  EXPECT_EQ(dla::read_csv(dir / "lines.csv").seed_count, 2u);
  const CliRun vines = dla3d(dir, "-q --text DLA --side outside --shell 3 -n 300 -o vines --formats csv");
  ASSERT_EQ(vines.exit_code, 0) << vines.err;
  const dla::Cluster vines_grown = dla::read_csv(dir / "vines.csv");
  ASSERT_EQ(vines_grown.seed_count, 3u);  // one off the front of each letter
  for (std::size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(vines_grown.particles[i].position.z(), 25.5);
  const CliRun missing = dla3d(dir, "-q -o bad --text DLA --font missing.ttf");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  expect_refused(dir, {"--text DLA --stl ball.stl", "--font x.ttf", "--text ''", "--text '  '",
                       "--text DLA --side both --seeds 2", "--text DLA --spacing 0"});
}

TEST(Cli, ShellGrowsOverTheSurface) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  const CliRun run = dla3d(dir, "-q --stl ball.stl --side outside --shell 2 --spacing 0.5 -n 400 -o frost --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string json = read_file(dir / "frost.json");
  EXPECT_NE(json.find("\"spawn\": \"inside\""), std::string::npos) << "uniform in the shell by default";
  const dla::Cluster frost = dla::read_csv(dir / "frost.csv");
  for (const dla::Particle& p : frost.particles) {
    EXPECT_GT(p.position.norm(), 10.0 * std::cos(3.14159265 / 12) - 1e-3) << p.position.transpose();
    EXPECT_LT(p.position.norm(), 11.0 + 1e-3) << p.position.transpose();
  }
  // An open box, frosted on both sides of its walls.
  std::filesystem::copy_file(TEST_DATA_DIR "/open_box.off", dir / "box.off");
  const CliRun open = dla3d(dir, "-q --stl box.off --side surface -n 300 -o open --formats csv");
  ASSERT_EQ(open.exit_code, 0) << open.err;
  expect_refused(dir, {"--shell 2", "--stl ball.stl --shell 0.5", "--stl ball.stl --shell 2 --fill 0.5",
                       "--stl ball.stl --side outside --shell 2 --spawn radial", "--stl ball.stl --shell x",
                       "--stl ball.stl --side outside --shell 2 --seed-at 0,0,0"});
}

TEST(Cli, SeedsAllIsTheWholeSurface) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  ASSERT_EQ(dla3d(dir, "-q --stl ball.stl --spacing 0.5 --seed-surface -n 200 -o surface --formats csv").exit_code, 0);
  ASSERT_EQ(dla3d(dir, "-q --stl ball.stl --spacing 0.5 --seeds all -n 200 -o all --formats csv").exit_code, 0);
  EXPECT_EQ(read_file(dir / "surface.csv"), read_file(dir / "all.csv"));
  expect_refused(dir, {"--stl ball.stl --seeds some", "--stl ball.stl --seeds 1e3", "--seeds all"});
}

TEST(Cli, SeedPaintGrowsFromThePaintedPart) {
  ScratchDir dir;
  // A ball painted red above z = 5, in a PLY as Blender writes one.
  dla::TriangleMesh ball = dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24);
  for (const dla::Vec3& v : ball.vertices) ball.colors.push_back(v.z() > 5.0 ? dla::Vec3(1, 0, 0) : dla::Vec3(1, 1, 1));
  std::ofstream(dir / "painted.ply") << dla::testing::painted_ply(ball);
  const CliRun run = dla3d(dir, "-q --stl painted.ply --spacing 0.5 --seed-paint ff0000 -n 300 -o painted --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster painted = dla::read_csv(dir / "painted.csv");
  EXPECT_GT(painted.seed_count, 30u);  // the cap is some 310 units² (less its blended rim)
  EXPECT_EQ(painted.particles.size(), painted.seed_count + 300);
  for (std::size_t i = 0; i < painted.seed_count; ++i) EXPECT_GT(painted.particles[i].position.z(), 3.5) << i;
  ASSERT_EQ(dla3d(dir, "-q --stl painted.ply --spacing 0.5 --seed-surface --seed-paint ff0000 -n 300 -o surface "
                       "--formats csv").exit_code, 0);
  EXPECT_EQ(read_file(dir / "surface.csv"), read_file(dir / "painted.csv")) << "the painted part of the surface";
  ASSERT_EQ(dla3d(dir, "-q --stl painted.ply --spacing 0.5 --seed-paint red,0.1 --seeds 2 -n 100 -o two --formats csv")
                .exit_code, 0);
  EXPECT_EQ(dla::read_csv(dir / "two.csv").seed_count, 2u);
  dla::write_stl(ball, dir / "plain.stl");
  expect_refused(dir, {"--seed-paint red", "--stl plain.stl --seed-paint red", "--stl painted.ply --seed-paint blue",
                       "--stl painted.ply --seed-paint pink", "--stl painted.ply --seed-paint red,1",
                       "--stl painted.ply --seed-paint red,x", "--stl painted.ply --seed-paint red --seed-at 0,0,0",
                       "--stl painted.ply --seed-paint red --side both", "--stl painted.ply --seed-paint red --seeds 5000"});
}

// Colonization's attractors on the painted part of the vessel: the tree grows up into the cap.
TEST(Cli, AttractorPaintGrowsTheTreeToThePaintedPart) {
  ScratchDir dir;
  dla::TriangleMesh ball = dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24);
  for (const dla::Vec3& v : ball.vertices) ball.colors.push_back(v.z() > 5.0 ? dla::Vec3(0, 1, 0) : dla::Vec3(1, 1, 1));
  std::ofstream(dir / "painted.ply") << dla::testing::painted_ply(ball);
  const std::string common = "colonize -q --stl painted.ply --spacing 0.5 --attractors 400 --root-at 0,0,-8 -n 400 ";
  const CliRun run = dla3d(dir, common + "--attractors-in surface --attractor-paint 00ff00 -o cap --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster tree = dla::read_csv(dir / "cap.csv");
  double highest = -1e9;
  for (const auto& p : tree.particles) highest = std::max(highest, p.position.z());
  EXPECT_GT(highest, 5.0) << "the tree reaches the painted cap";
  EXPECT_NE(read_file(dir / "cap.json").find("\"attractor_paint\": \"00ff00,0.3\""), std::string::npos);
  dla::write_stl(ball, dir / "plain.stl");
  for (const char* args : {"--stl painted.ply --attractor-paint green",
                           "--stl painted.ply --attractors-in surface --attractor-paint red",
                           "--stl plain.stl --attractors-in surface --attractor-paint green",
                           "--attractors-in surface --attractor-paint green",
                           "--stl painted.ply --attractors-in surface --attractor-paint pink"}) {
    const CliRun refused = dla3d(dir, std::string("colonize -q -o bad -n 50 ") + args);
    EXPECT_EQ(refused.exit_code, 2) << args << ": " << refused.err;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << args << ": " << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.csv")) << args;
  }
}

// drop and colonize take DLA's mesh controls: seeds (colonize: roots) on the painted part, on the
// surface, K far apart; DLA's --fill and --shell are refused with why.
TEST(Cli, DropAndColonizeTakeTheMeshControls) {
  ScratchDir dir;
  dla::TriangleMesh ball = dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24);
  for (const dla::Vec3& v : ball.vertices) ball.colors.push_back(v.z() > 5.0 ? dla::Vec3(1, 0, 0) : dla::Vec3(1, 1, 1));
  std::ofstream(dir / "painted.ply") << dla::testing::painted_ply(ball);
  const auto seeds_of = [&](const std::string& args) {  // the model's words first
    std::filesystem::remove(dir / "out.csv");
    const CliRun run = dla3d(dir, args + " -q --stl painted.ply --spacing 0.5 -o out --formats csv");
    EXPECT_EQ(run.exit_code, 0) << args << ": " << run.err;
    const dla::Cluster grown = dla::read_csv(dir / "out.csv");
    return std::vector<dla::Particle>(grown.particles.begin(), grown.particles.begin() + grown.seed_count);
  };
  for (const char* model : {"drop -n 100", "colonize --attractors-in mesh --attractors 500 -n 3000"}) {
    const std::string m = model;
    const std::vector<dla::Particle> painted = seeds_of(m + " --seed-paint red");
    EXPECT_GT(painted.size(), 30u) << model;
    for (const dla::Particle& p : painted) EXPECT_GT(p.position.z(), 3.5) << model;
    EXPECT_EQ(seeds_of(m + " --seed-paint red --seeds 3").size(), 3u) << model;
    EXPECT_EQ(seeds_of(m + " --seeds 4").size(), 4u) << model;
    const std::vector<dla::Particle> surface = seeds_of(m + " --seed-surface");
    EXPECT_GT(surface.size(), painted.size()) << model;
    for (const dla::Particle& p : surface) EXPECT_NEAR(p.position.norm(), 10.0, 0.5) << model;  // half a spacing in
  }
  for (const char* args : {"drop --fill 0.5", "drop --shell 3", "colonize --fill 0.5", "colonize --shell 3",
                           "drop --seeds 2", "colonize --seed-surface", "drop --stl painted.ply --seeds 2 --seed-at 0,0,0",
                           "colonize --stl painted.ply --attractors-in mesh --seeds 2 --roots 3"}) {
    const CliRun run = dla3d(dir, std::string(args) + " -q -o bad");
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.csv")) << args;
  }
  EXPECT_EQ(dla3d(dir, "drop --fill 0.5").err,
            "dla3d: error: --fill grows DLA until a mesh is full; drop grows to its count, --particles\n");
}

TEST(Cli, SeedMeshGrowsFromWhereARodEnters) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  dla::write_stl(dla::make_open_can(dla::Vec3(0, 0, 5), 2.0, 10.0, 16), dir / "rod.stl");
  dla::write_stl(dla::make_open_can(dla::Vec3(5, 0, -15), 1.5, 10.0, 16), dir / "rod2.stl");
  const CliRun run = dla3d(dir, "-q --stl ball.stl --spacing 0.5 --seed-mesh rod.stl --seed-mesh rod2.stl -n 300 "
                                "--radius seed-distance -o entered --formats csv,json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const dla::Cluster entered = dla::read_csv(dir / "entered.csv");
  EXPECT_GT(entered.seed_count, 20u);  // two rings, some 22 units round
  bool top = false, bottom = false;
  for (std::size_t i = 0; i < entered.seed_count; ++i) {
    const dla::Vec3& p = entered.particles[i].position;
    top = top || p.z() > 9.0;
    bottom = bottom || p.z() < -7.0;
    EXPECT_TRUE(p.z() > 9.0 || p.z() < -7.0) << p.transpose();
  }
  EXPECT_TRUE(top && bottom) << "a ring for each rod";
  const CliRun missing = dla3d(dir, "-q -o bad --stl ball.stl --seed-mesh missing.stl");
  EXPECT_EQ(missing.exit_code, 1);  // as for any file that cannot be read
  EXPECT_EQ(missing.err, "dla3d: error: cannot read 'missing.stl': No such file or directory\n");
  expect_refused(dir, {"--seed-mesh rod.stl",
                       "--stl ball.stl --seed-mesh rod.stl --seed-paint red", "--stl ball.stl --seed-mesh rod.stl --seed-surface",
                       "--stl ball.stl --seed-mesh rod.stl --seed-at 0,0,0"});
}

namespace {

//! The particles of a --stream file (cli/stream.h), each frame written at its `first`, and the
//! last frame's done and total; an empty string, or what is wrong with it.
struct Streamed {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::int32_t> parents;
  std::uint64_t done = 0, total = 0;
  std::size_t frames = 0;
  std::string fault;
};

Streamed read_stream(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  Streamed s;
  std::size_t at = 0;
  while (at < bytes.size()) {
    if (bytes.size() - at < 32 || bytes.compare(at, 4, "DLAs") != 0) return s.fault = "a frame's header is cut or wrong", s;
    std::uint32_t count = 0;
    std::uint64_t first = 0;
    std::memcpy(&count, bytes.data() + at + 4, 4);
    std::memcpy(&first, bytes.data() + at + 8, 8);
    std::memcpy(&s.done, bytes.data() + at + 16, 8);
    std::memcpy(&s.total, bytes.data() + at + 24, 8);
    if (bytes.size() - at - 32 < 16ull * count) return s.fault = "a frame's particles are cut", s;
    if (first > s.positions.size()) return s.fault = "a frame leaves a gap", s;
    s.positions.resize(std::max<std::size_t>(s.positions.size(), first + count));
    s.parents.resize(s.positions.size());
    std::memcpy(&s.positions[first], bytes.data() + at + 32, 12ull * count);
    std::memcpy(&s.parents[first], bytes.data() + at + 32 + 12ull * count, 4ull * count);
    at += 32 + 16ull * count;
    ++s.frames;
  }
  return s;
}

void expect_stream_is(const Streamed& s, const dla::Cluster& grown) {
  ASSERT_EQ(s.fault, "");
  ASSERT_EQ(s.positions.size(), grown.particles.size());
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis)
      ASSERT_EQ(s.positions[i][axis], static_cast<float>(grown.particles[i].position[axis])) << i;
    ASSERT_EQ(s.parents[i], grown.particles[i].parent) << i;
  }
}

}  // namespace

TEST(Cli, StreamSendsEachParticleAsItAttachesAndChangesNoFile) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 60000 -q --formats csv,json -o streamed --stream live.bin").exit_code, 0);
  ASSERT_EQ(dla3d(dir, "-n 60000 -q --formats csv,json -o plain").exit_code, 0);
  EXPECT_EQ(read_file(dir / "streamed.csv"), read_file(dir / "plain.csv"));
  // The run's record leaves the stream out: it is no part of what grew.
  EXPECT_EQ(read_file(dir / "streamed.json").find("live.bin"), std::string::npos);
  const Streamed s = read_stream(dir / "live.bin");
  expect_stream_is(s, dla::read_csv(dir / "plain.csv"));
  EXPECT_EQ(s.done, 60000u);
  EXPECT_EQ(s.total, 60000u);
  EXPECT_GE(s.frames, 2u);
  // Every model streams.
  for (const char* model : {"colonize --attractors 3000", "eden -n 2000", "drop -n 500", "ballistic -n 500",
                            "breakdown -n 300"}) {
    SCOPED_TRACE(model);
    ASSERT_EQ(dla3d(dir, std::string(model) + " -q --formats csv -o model --stream model.bin").exit_code, 0);
    expect_stream_is(read_stream(dir / "model.bin"), dla::read_csv(dir / "model.csv"));
  }
}

TEST(Cli, StreamToAClosedPipeEndsTheStreamNotTheRun) {
  ScratchDir dir;
  // `head -c 100` takes a frame's start and goes away: the run goes on and writes its files.
  ASSERT_EQ(std::system(("cd '" + dir.path().string() + "' && '" DLA3D_PATH
                         "' -n 100000 -q --formats csv -o piped --stream /dev/stdout | head -c 100 > /dev/null")
                            .c_str()),
            0);
  EXPECT_EQ(dla::read_csv(dir / "piped.csv").particles.size(), 100001u);
}

TEST(Cli, StreamResumedStartsAgainAtTheFirstParticle) {
  ScratchDir dir;
  const std::string run = "-n 150000 -q --rng-seed 3";
  ASSERT_EQ(interrupted(dir, run + " -o part --checkpoint part.ck --checkpoint-every 0.2", SIGINT, 0.0, "part.ck"), 130);
  const CliRun resumed = dla3d(dir, "--resume part.ck --stream resumed.bin");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_stream_is(read_stream(dir / "resumed.bin"), dla::read_csv(dir / "part.csv"));
}

TEST(Cli, StreamToAFolderOrNowhereIsOneLineAndNoFile) {
  ScratchDir dir;
  std::filesystem::create_directory(dir / "folder");
  for (const char* where : {"folder", "missing/live.bin", "''"}) {
    const CliRun run = dla3d(dir, std::string("-n 10 -q -o bad --stream ") + where);
    SCOPED_TRACE(where);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.csv"));
  }
  EXPECT_EQ(dla3d(dir, "frames bad.csv --stream x.bin").exit_code, 2) << "frames grows nothing to stream";
}

TEST(Cli, OptionsDescribesEveryModelsHelp) {
  ScratchDir dir;
  ASSERT_EQ(std::system(("cd '" + dir.path().string() + "' && '" DLA3D_PATH "' options > options.json").c_str()), 0);
  const std::string json = read_file(dir / "options.json");
  for (const dla::Model& model : dla::models()) {
    SCOPED_TRACE(model.name);
    EXPECT_NE(json.find("{\"name\": \"" + std::string(model.name) + "\""), std::string::npos);
  }
  // Each of --help's options of DLA is there, with its default.
  for (const char* entry : {"\"name\": \"--particles\", \"short\": [\"-n\"]", "\"default\": \"10000\"",
                            "\"name\": \"--eta\"", "\"name\": \"--stream\"", "\"name\": \"--seed-paint\""})
    EXPECT_NE(json.find(entry), std::string::npos) << entry;
  EXPECT_EQ(json.find("\"name\": \"--help\""), std::string::npos);
  // What the library's description adds: a word's choices, a number's range, a flag as a flag.
  for (const char* entry :
       {"\"kind\": \"word\", \"choices\": [\"walkers\", \"conductor\", \"charges\"]",
        "\"kind\": \"real\", \"min\": 0, \"max\": 10, \"min_open\": false, \"max_open\": false}",
        "\"kind\": \"integer\", \"min\": 1, \"max\": 4096, \"min_open\": false, \"max_open\": false, "
        "\"special\": {\"value\": 0, \"means\": \"chosen by eta\"}}",
        "\"kind\": \"word\", \"choices\": [\"grid\", \"kdtree\", \"brute\"]",
        "\"kind\": \"real\", \"min\": 0, \"max\": 1000, \"min_open\": true, \"max_open\": false}",
        "\"name\": \"--stop-at-strike\", \"short\": [], \"negation\": [\"--no-stop-at-strike\"], \"flag\": true"})
    EXPECT_NE(json.find(entry), std::string::npos) << entry;
  // What a front end that paints reads: the roles, the exclusions both ways, what an option needs.
  const auto entry_of = [&json](const std::string& model, const std::string& option) {
    const std::size_t at = json.find("{\"name\": \"" + model + "\""), next = json.find("\n {\"name\": ", at + 1);
    const std::size_t from = json.find("{\"name\": \"" + option + "\"", at);
    return from >= next ? std::string() : json.substr(from, json.find('\n', from) - from);
  };
  for (const auto& [model, option, says] : std::vector<std::array<std::string, 3>>{
           {"grow", "--seed-paint", "\"paints\": \"seeds\""},
           {"grow", "--seed-paint", "\"excludes\": [\"--seed-at\", \"--seed-mesh\"]"},
           {"grow", "--seed-at", "\"--seed-paint\""},
           {"grow", "--tips-exclude-paint", "\"paints\": \"bare\""},
           {"grow", "--threads", "\"speed_only\": true"},
           {"colonize", "--attractor-paint", "\"paints\": \"attractors\""},
           {"colonize", "--attractor-paint", "\"needs\": [\"--attractors-in\", \"surface\"]"},
           {"eden", "--mask", "\"choices\": [\"A\", \"B\", \"C\", \"D\"]"},
           {"eden", "--mask", "\"paints\": \"mask\""},
           {"eden", "--links", "\"group\": \"Eden\""}})
    EXPECT_NE(entry_of(model, option).find(says), std::string::npos) << model << " " << option << ": " << says;
  EXPECT_EQ(entry_of("colonize", "--fill"), "") << "a refused option is not offered";
}

// The description is the one place an option is named: the CLI's and the studio's code names
// only options of their own (--stream, --preset, --checkpoint, --port) in its strings.
TEST(Cli, NoFrontEndSpellsADescribedOption) {
  std::vector<std::string> described;
  const auto add = [&](const dla::OptionDescription& about) {
    described.push_back(dla::cli_flag(about.name));
    if (!about.negation.empty()) described.push_back(dla::cli_flag(about.negation));
  };
  for (const dla::Model& model : dla::models())
    for (const auto& row : model.option_table) add(row.about);
  for (const auto& row : dla::output_option_table()) add(row.about);
  ASSERT_GT(described.size(), 100u);
  const std::filesystem::path root = std::filesystem::path(DLA_EXAMPLES_DIR).parent_path();
  std::size_t files = 0;
  for (const char* folder : {"cli", "studio"})
    for (const auto& entry : std::filesystem::directory_iterator(root / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h" && ext != ".py" && ext != ".js" && ext != ".html") continue;
      ++files;
      const std::string text = read_file(entry.path());
      for (const std::string& flag : described)
        for (const char quote : {'"', '\''})
          EXPECT_EQ(text.find(quote + flag + quote), std::string::npos) << entry.path() << " names " << flag;
    }
  EXPECT_GT(files, 10u);
}

TEST(Cli, EveryPresetGrowsAndOptionsBesideItOverrideIt) {
  ScratchDir dir;
  dla::write_stl(dla::make_sphere(dla::Vec3::Zero(), 10.0, 12, 24), dir / "ball.stl");
  for (const dla::Preset& preset : dla::presets()) {
    SCOPED_TRACE(std::string(preset.model) + " --preset " + std::string(preset.name));
    const std::string summary(preset.summary);
    // What the preset needs beside it, as its summary says; few particles, for speed.
    const std::string mesh = summary.find("--stl") != std::string::npos       ? " --stl ball.stl"
                             : summary.find("--collide") != std::string::npos ? " --collide ball.stl"
                                                                              : "";
    const std::string count = preset.model == "colonize" ? " --max-nodes 60" : " -n 60";
    const std::string command = (preset.model == "grow" ? "" : std::string(preset.model) + " ") + "--preset " +
                                std::string(preset.name) + mesh + count + " --formats json -o p";
    const CliRun run = dla3d(dir, command);
    ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.err;
    // The preset's options are recorded as the user's are: each in the JSON's command, and the
    // model's own in its options, a word as the word given.
    const std::string json = read_file(dir / "p.json");
    const std::string options = json.substr(json.find("\"options\": {"));
    const dla::Model& model = *dla::find_model(preset.model);
    for (const dla::PresetOption& option : preset.options) {
      if (option.name == "particles" || option.name == "formats") continue;  // given beside it, overriding it
      const std::string words = " " + dla::cli_flag(option.name) + (option.value.empty() ? "" : " " + std::string(option.value));
      EXPECT_NE(json.find(words), std::string::npos) << words;
      const auto row = std::find_if(model.option_table.begin(), model.option_table.end(),
                                    [&](const auto& r) { return r.about.name == option.name; });
      if (row == model.option_table.end()) continue;  // the look's or the files'
      const std::string field = "\"" + std::string(option.name) + "\": ";
      EXPECT_LT(options.find(field), options.find('}')) << field;
      if (row->about.kind == dla::OptionKind::word) {
        EXPECT_NE(options.find(field + "\"" + std::string(option.value) + "\""), std::string::npos) << field;
      }
    }
    EXPECT_EQ(json.find("--preset"), std::string::npos) << "recorded as the options it stands for";
    std::filesystem::remove(dir / "p.json");
  }
  // Beside it, --eta overrides the preset's, and --target-point excludes its --target-plane.
  const CliRun over = dla3d(dir, "breakdown --preset lightning --eta 2 --target-point 0,-30,0 -n 30 --formats json -o o");
  ASSERT_EQ(over.exit_code, 0) << over.err;
  const std::string json = read_file(dir / "o.json");
  EXPECT_NE(json.find("\"eta\": 2,"), std::string::npos) << json;
  EXPECT_EQ(json.find("--target-plane"), std::string::npos);
  EXPECT_NE(json.find(" --seed-at 0,40,0 "), std::string::npos);
  EXPECT_EQ(json.find("--eta 3"), std::string::npos);
  // Bad uses: one line each, naming --preset.
  for (const auto& [args, message] : std::initializer_list<std::pair<const char*, const char*>>{
           {"breakdown --preset nope", "dla3d: error: --preset 'nope' is not one of lightning, lichtenberg, spark\n"},
           {"--preset coral --preset frost", "dla3d: error: --preset is given twice: give one, and options beside it\n"},
           {"drop --preset", "dla3d: error: --preset needs a NAME; --preset list prints them\n"},
           {"eden --preset coral", nullptr}}) {
    const CliRun bad = dla3d(dir, args);
    EXPECT_EQ(bad.exit_code, 2) << args;
    if (message) EXPECT_EQ(bad.err, message) << args;
    else EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
  ASSERT_EQ(std::system(("cd '" + dir.path().string() + "' && '" DLA3D_PATH "' breakdown --preset list > list.txt").c_str()), 0);
  const std::string list = read_file(dir / "list.txt");
  for (const char* entry : {"lightning: a bolt", "--eta 3 --seed-at 0,40,0 --target-plane y=-40", "spark: "})
    EXPECT_NE(list.find(entry), std::string::npos) << list;
}

TEST(Cli, BadInputFoundOnceGrowthBeganLeavesNoStreamFile) {
  // A root the vessel does not hold is found as colonization starts, after the stream is open.
  ScratchDir dir;
  dla::write_stl(dla::make_box(dla::Vec3(-10, -10, -10), dla::Vec3(10, 10, 10)), dir / "box.stl");
  const CliRun run = dla3d(dir, "colonize --attractors 933 -n 33 --stl box.stl --root-at 50,0,0 --stream live.bin -o bad");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "live.bin"));
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}
