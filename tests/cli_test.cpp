// dla3d as a user meets it: `dla3d -n N -o PREFIX` writes every file; every bad flag or value
// is one line on stderr, a non-zero exit and no files.

#include "mesh_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using dla::testing::ScratchDir;
using dla::testing::read_file;

struct CliRun {
  int exit_code;
  std::string err;
};

CliRun dla3d(const ScratchDir& dir, const std::string& args) {
  const std::string command =
      "cd '" + dir.path().string() + "' && '" DLA3D_PATH "' " + args + " > out.txt 2> err.txt";
  const int status = std::system(command.c_str());
  CliRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(dir / "err.txt")};
  std::filesystem::remove(dir / "out.txt");
  std::filesystem::remove(dir / "err.txt");
  return run;
}

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

TEST(Cli, SameSeedSameFiles) {
  ScratchDir dir;
  ASSERT_EQ(dla3d(dir, "-n 1000 -o a -q --seed-at=-5,0,0 --seed-at 5,0,0").exit_code, 0);
  ASSERT_EQ(dla3d(dir, "-n 1000 -o b -q --seed-at=-5,0,0 --seed-at 5,0,0").exit_code, 0);
  for (const char* ext : {".csv", ".ply", ".inc"})
    EXPECT_EQ(read_file(dir / (std::string("a") + ext)), read_file(dir / (std::string("b") + ext)));
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
  EXPECT_NE(read_file(dir / "in.inc").find("DLA_Mesh = mesh2"), std::string::npos);
  const std::string json = read_file(dir / "in.json");
  EXPECT_NE(json.find("\"side\": \"inside\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"spawn\": \"inside\""), std::string::npos) << json;
  ASSERT_EQ(dla3d(dir, "--stl box.stl --seeds 2 -n 800 -o again --spacing 0.5 -q --no-scene-mesh").exit_code, 0);
  EXPECT_EQ(read_file(dir / "in.csv"), read_file(dir / "again.csv"));
  EXPECT_EQ(read_file(dir / "again.inc").find("mesh2"), std::string::npos);
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
  EXPECT_NE(csv.find(",-1,1\n"), std::string::npos) << "no second seed";
}

// Starts dla3d in the background, sends it `signal` after `seconds`, and returns its exit code.
int interrupted(const ScratchDir& dir, const std::string& args, const char* signal, double seconds) {
  const std::string command = "cd '" + dir.path().string() + "' && { '" DLA3D_PATH "' " + args +
                              " 2> err.txt & pid=$!; sleep " + std::to_string(seconds) + "; kill -" + signal +
                              " $pid; wait $pid; echo $? > code.txt; }";
  EXPECT_EQ(std::system(command.c_str()), 0);
  return std::atoi(read_file(dir / "code.txt").c_str());
}

TEST(Cli, CtrlCKeepsTheWorkAndResumeEndsAsAnUninterruptedRun) {
  ScratchDir dir;
  const std::string run = "-n 150000 -q --rng-seed 3";
  const int code = interrupted(dir, run + " -o part --checkpoint part.ck --checkpoint-every 0.2", "INT", 0.7);
  if (code == 0) GTEST_SKIP() << "the run ended before the signal: this machine is too fast for the test";
  ASSERT_EQ(code, 130) << read_file(dir / "err.txt");
  const std::string err = read_file(dir / "err.txt");
  EXPECT_NE(err.find("stopped by SIGINT after "), std::string::npos) << err;
  EXPECT_NE(err.find("dla3d --resume part.ck"), std::string::npos) << err;
  EXPECT_NE(read_file(dir / "part.json").find("\"complete\": false"), std::string::npos);
  for (const char* name : {"part.csv", "part.ply", "part.pov", "part.inc", "part.ck"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;

  const CliRun resumed = dla3d(dir, "--resume part.ck -q");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "part.ck")) << "a finished run's checkpoint is left behind";
  ASSERT_EQ(dla3d(dir, run + " -o whole").exit_code, 0);
  EXPECT_TRUE(read_file(dir / "part.csv") == read_file(dir / "whole.csv")) << "resumed run differs";
  EXPECT_EQ(dla3d(dir, "--resume part.ck").exit_code, 1) << "the checkpoint is gone";
  EXPECT_EQ(dla3d(dir, "--resume whole.csv").exit_code, 2);
  EXPECT_EQ(dla3d(dir, "--resume whole.csv -n 5").exit_code, 2);
}

TEST(Cli, SigtermWritesPartialFiles) {
  ScratchDir dir;
  const int code = interrupted(dir, "-n 300000 -o part", "TERM", 0.5);
  if (code == 0) GTEST_SKIP() << "the run ended before the signal";
  EXPECT_EQ(code, 143) << read_file(dir / "err.txt");
  EXPECT_NE(read_file(dir / "part.json").find("\"complete\": false"), std::string::npos);
  const std::string csv = read_file(dir / "part.csv");
  EXPECT_EQ(csv.back(), '\n');
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 256);
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

}  // namespace
