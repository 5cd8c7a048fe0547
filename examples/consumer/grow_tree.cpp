// Grows a small two-seed structure from C++ and writes it for POV-Ray and as CSV.
// Usage: grow_tree PREFIX

#include <dla/io/csv_writer.h>
#include <dla/models/dla.h>
#include <dla/io/pov_writer.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: grow_tree PREFIX\n");
    return 2;
  }
  dla::DlaOptions options;
  options.particles = 5000;
  options.seeds = {{-15, 0, 0}, {15, 0, 0}};
  options.rng_seed = 7;
  const dla::Cluster tree = dla::grow(options);

  dla::write_pov(tree, argv[1]);
  dla::write_csv(tree, std::string(argv[1]) + ".csv");
  std::printf("grew %zu particles, bounding radius %.1f\n", tree.particles.size(),
              dla::bounding_radius(tree));
  return 0;
}
