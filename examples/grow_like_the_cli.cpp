// The main job, `dla3d --stl bust.stl --seeds 2`, from C++: the library's run layer takes the
// same defaults from the mesh as the command line does (spacing, spawn, seeds, radii) and
// writes the same files.
//   grow_like_the_cli bust.stl [PARTICLES] [PREFIX]

#include <dla/run/run.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  dla::DlaRunOptions options;
  options.stl = argc > 1 ? argv[1] : "bust.stl";
  options.seeds.count = 2;
  if (argc > 2) options.particles = std::stoul(argv[2]);  // unset: the mesh's default, 30,000
  options.files.output = argc > 3 ? argv[3] : "bust_tree";
  try {
    const auto run = dla::prepare_run(options);
    dla::RunRecord record;
    const dla::Cluster tree = dla::grow_recorded(*run, {}, nullptr, record);
    dla::write_run(*run, tree, record);  // bust_tree.pov .inc .csv .ply .json
    std::printf("%s\n", run->summary(tree, record).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grow_like_the_cli: %s\n", e.what());  // options named as in C++: `seeds`
    return 1;
  }
  return 0;
}
