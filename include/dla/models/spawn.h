#pragma once
//! \file spawn.h
//! Where walkers start: the spawn distributions of DlaOptions::spawn that need no mesh.

#include "dla/core/options.h"
#include "dla/core/random.h"

#include <cmath>

namespace dla {

//! A start drawn from the spawn distribution, for a structure centred at `center` whose
//! walkers launch at `launch_radius` (just outside the structure). A box start may fall inside
//! the structure; the caller checks it is clear.
inline Vec3 draw_spawn(const DlaOptions& o, const Vec3& center, double launch_radius, Rng& rng) {
  const double R = launch_radius;
  switch (o.spawn) {
    case SpawnMode::sphere:
      return center + R * random_direction(rng, o.dimensions);
    case SpawnMode::disk: {
      const int a = static_cast<int>(o.spawn_axis);
      Vec3 along = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();
      along[a] = 1.0;
      const double rho = o.disk_radius * R;
      if (o.dimensions == 2) {  // the disk is a segment across the axis, in the plane
        u[1 - a] = 1.0;
        return center + R * along + rho * (2.0 * rng.uniform() - 1.0) * u;
      }
      u[(a + 1) % 3] = 1.0;
      v[(a + 2) % 3] = 1.0;
      const double r = rho * std::sqrt(rng.uniform());
      const double phi = 6.283185307179586476925286766559 * rng.uniform();
      return center + R * along + r * (std::cos(phi) * u + std::sin(phi) * v);
    }
    case SpawnMode::box: {
      const Vec3 lo = o.spawn_box ? o.spawn_box->min : Vec3(center.array() - R);
      const Vec3 hi = o.spawn_box ? o.spawn_box->max : Vec3(center.array() + R);
      Vec3 x;
      for (int i = 0; i < 3; ++i) x[i] = lo[i] + (hi[i] - lo[i]) * rng.uniform();
      if (o.dimensions == 2) x.z() = 0.0;
      return x;
    }
    case SpawnMode::inside:
    case SpawnMode::radial:
    case SpawnMode::surface:
      break;  // drawn by a constraint mesh (MeshConstraint); grow() refuses them without one
  }
  return center;
}

}  // namespace dla
