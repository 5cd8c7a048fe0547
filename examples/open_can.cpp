// Bourke's figure 4: an open can (a cylinder closed at the base, open at the top), walkers
// launched on a sphere about the can's centre, the seed at the centre of its top. The can is
// a wall (Side::both): branches may not pass through it, and they grow down into the can and
// out over its rim.
//
//   open_can [PARTICLES] [PREFIX]     defaults: 30000 open_can
//   povray +W1280 +H960 +A open_can.pov

#include "dla/mesh/constraint.h"
#include "dla/models/dla.h"
#include "dla/io/pov_writer.h"
#include "dla/mesh/shapes.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  try {
    dla::DlaOptions options;
    options.particles = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 30000;
    const std::string prefix = argc > 2 ? argv[2] : "open_can";
    const double radius = 40.0, height = 80.0;
    options.seeds = {dla::Vec3(0, 0, height)};  // the centre of the open top
    options.spawn = dla::SpawnMode::sphere;     // with a mesh: a sphere about the mesh

    dla::ConstraintOptions wall;
    wall.side = dla::Side::both;
    const dla::MeshConstraint can(dla::make_open_can(dla::Vec3::Zero(), radius, height), wall, options.spacing);
    dla::DlaStats stats;
    const dla::Cluster cluster = dla::grow(options, can, {}, nullptr, &stats);

    dla::PovOptions look;
    look.up = dla::Axis::z;
    dla::write_pov(cluster, prefix, look, &can.mesh());
    std::printf("open_can: %zu particles, %llu branches refused by the can; wrote %s.pov\n", cluster.particles.size(),
                static_cast<unsigned long long>(stats.walk.rejected), prefix.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "open_can: error: %s\n", e.what());
    return 1;
  }
}
