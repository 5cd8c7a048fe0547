// Faults a user meets on long runs: a disk that fills up, and a process killed while it writes.
// Neither may leave a truncated file under a final name, or spoil a checkpoint already saved.

#include "cli_util.h"
#include "test_util.h"

#include "dla/io/checkpoint.h"
#include "dla/models/dla.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <set>
#include <string>

namespace dla {
namespace {

using testing::CliRun;
using testing::ScratchDir;
using testing::dla3d;
using testing::read_file;

//! File names in `dir`.
std::set<std::string> files_in(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

// A full disk: a tmpfs of 1.2 MB in a mount namespace of the test's own (unshare), holding a
// checkpoint of 30,000 particles. Resuming it fills the disk: every save fails (a warning,
// growth goes on), then the files fail: a clear error, no temporary file left, the checkpoint
// as it was.
TEST(Faults, AFullDiskIsAClearErrorAndKeepsTheCheckpoint) {
  ScratchDir dir;
  DlaOptions o;
  o.particles = 30000;
  Cluster part = grow(o);
  part.complete = false;
  write_checkpoint({{"-n", "60000", "-q", "-o", "out", "--checkpoint", "part.ck", "--checkpoint-every", "0"}, 0, part, {}},
                   dir / "part.ck");
  const std::string saved = read_file(dir / "part.ck");
  const std::string small = (dir.path() / "small").string();
  std::filesystem::create_directory(small);
  const std::string script =
      "mount -t tmpfs -o size=1200k tmpfs '" + small + "' || exit 99; cd '" + small + "' && cp ../part.ck . && '" +
      DLA3D_PATH "' --resume part.ck 2> ../err.txt; echo \\$? > ../code.txt; ls -a > ../files.txt; cp part.ck ../after.ck";
  const int status = std::system(("unshare -rm sh -c \"" + script + "\"").c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 99)
    GTEST_SKIP() << "cannot mount a small tmpfs here (unshare -rm, mount): the full-disk case is not run";
  const std::string err = read_file(dir / "err.txt");
  EXPECT_EQ(std::atoi(read_file(dir / "code.txt").c_str()), 1) << err;
  EXPECT_NE(err.find("dla3d: warning: cannot write 'part.ck': No space left on device; growth goes on\n"),
            std::string::npos) << err;
  EXPECT_NE(err.find("dla3d: error: cannot write 'out."), std::string::npos) << err;
  EXPECT_NE(err.find("': No space left on device\n"), std::string::npos) << err;
  const std::string files = read_file(dir / "files.txt");
  EXPECT_EQ(files.find(".tmp"), std::string::npos) << "a temporary file is left:\n" << files;
  EXPECT_TRUE(read_file(dir / "after.ck") == saved) << "the checkpoint on disk changed";
}

// SIGKILL at moments of the writing, each an event on disk: a writer's temporary file opened
// (the first, the glb's, the OBJ's), a file renamed into place while others are written. Any
// file under a final name is whole, the same bytes as an uninterrupted run's (the JSON up to
// its timings). Every file the run writes is checked, with every 3D format asked for, so
// writers added later are covered too.
TEST(Faults, AKillWhileWritingNeverLeavesATruncatedFile) {
  const std::string args = "-n 60000 --threads 2 -q -o out --rng-seed 4 --formats pov,csv,ply,json,glb,obj,tips";
  ScratchDir reference;
  ASSERT_EQ(dla3d(reference, args).exit_code, 0);
  const std::set<std::string> finals = files_in(reference.path());
  const auto growth_part = [](const std::string& json) { return json.substr(0, json.find("\"timings\"")); };
  int killed_while_writing = 0;
  // The shell test that is true once the moment has come.
  for (const std::string moment : {"-n \"$(ls | grep '\\.tmp$')\"", "-e out.glb.tmp", "-e out.obj.tmp",
                                   "-e out.csv -a -n \"$(ls | grep '\\.tmp$')\""}) {
    ScratchDir dir;
    // Waits for the moment (or the run's end), then kills at once.
    const std::string command = "cd '" + dir.path().string() + "' && { '" DLA3D_PATH "' " + args +
                                " & pid=$!; while ! [ " + moment +
                                " ] && kill -0 $pid 2>/dev/null; do sleep 0.001; done; kill -KILL $pid 2>/dev/null; "
                                "wait $pid; echo $? > code.txt; }";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const bool killed = std::atoi(read_file(dir / "code.txt").c_str()) == 128 + SIGKILL;
    std::filesystem::remove(dir / "code.txt");
    killed_while_writing += killed;
    for (const std::string& name : files_in(dir.path())) {
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) continue;  // not a final name
      ASSERT_TRUE(finals.count(name)) << name << " is not a file the run writes";
      const std::string written = read_file(dir / name), whole = read_file(reference / name);
      if (name == "out.json")
        EXPECT_EQ(growth_part(written), growth_part(whole)) << "killed at [ " << moment << " ]";
      else
        EXPECT_TRUE(written == whole) << name << " is not whole, killed at [ " << moment << " ]";
    }
  }
  // The first moment comes while the process runs and writes: its kill lands then.
  EXPECT_GT(killed_while_writing, 0) << "no run was killed while it wrote";
}

}  // namespace
}  // namespace dla
