// The walk's building blocks: directions, the exterior return rule (checked by simulating the
// Brownian motion it replaces) and the contact test of a short step.

#include "dla/core/random.h"
#include "dla/models/walk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dla {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(RandomDirection, IsUnitAndIsotropic) {
  for (int dims : {2, 3}) {
    Rng rng(3);
    const int n = 200000;
    Vec3 mean = Vec3::Zero(), mean2 = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
      const Vec3 u = random_direction(rng, dims);
      ASSERT_NEAR(u.norm(), 1.0, 1e-12);
      mean += u / n;
      mean2 += u.cwiseProduct(u) / n;
    }
    const double sd = std::sqrt(1.0 / dims / n);
    for (int a = 0; a < dims; ++a) {
      EXPECT_NEAR(mean[a], 0.0, 5 * sd);
      EXPECT_NEAR(mean2[a], 1.0 / dims, 0.01);
    }
    if (dims == 2) {
      EXPECT_EQ(mean2.z(), 0.0);
    }
  }
}

TEST(Rng, StreamsDifferAndRepeat) {
  Rng a(5, 0), b(5, 1), c(5, 0);
  const auto first = a();
  EXPECT_NE(first, b());
  EXPECT_EQ(first, c());
}

// Brownian motion from distance r outside a sphere of radius R, simulated by walk-on-spheres in
// the empty exterior until it comes within eps of the sphere or passes a far radius K.
struct Simulated {
  double returned_fraction;
  double mean_cos;  // of the angle between the start direction and the hitting point
};

Simulated simulate_exterior(double r, double R, double K, int walkers, Rng& rng) {
  const double eps = 1e-4 * R;
  int returned = 0;
  double sum_cos = 0.0;
  for (int w = 0; w < walkers; ++w) {
    Vec3 x(r, 0, 0);
    for (;;) {
      const double d = x.norm();
      if (d - R < eps) {
        ++returned;
        sum_cos += x.x() / d;
        break;
      }
      if (d > K) break;
      x += std::min(d - R, K + 1.0 - d) * random_direction(rng, 3);
    }
  }
  return {static_cast<double>(returned) / walkers, sum_cos / std::max(returned, 1)};
}

TEST(ReturnRule, ReturnFractionAndPlaceMatchBrownianMotion) {
  const double R = 10.0, r = 25.0, K = 2000.0;
  const int n = 40000;
  Rng sim_rng(17);
  const Simulated sim = simulate_exterior(r, R, K, n, sim_rng);
  // Escaping to K instead of infinity changes the return probability to this.
  const double expected = (1.0 / r - 1.0 / K) / (1.0 / R - 1.0 / K);
  const double sd = std::sqrt(expected * (1 - expected) / n);
  EXPECT_NEAR(sim.returned_fraction, expected, 4 * sd) << "the simulation itself is off";

  Rng rng(23);
  int returned = 0;
  double sum_cos = 0.0;
  for (int i = 0; i < n; ++i) {
    const ReturnPoint back = return_to_sphere(Vec3(0, r, 0), R, rng, 3);
    if (!back.returned) continue;
    ++returned;
    ASSERT_NEAR(back.offset.norm(), R, 1e-9);
    sum_cos += back.offset.y() / R;
  }
  EXPECT_NEAR(static_cast<double>(returned) / n, R / r, 4 * std::sqrt(R / r * (1 - R / r) / n));
  // Where it lands: the mean cosine agrees with the simulated motion within the noise of both.
  const double cos_sd = std::sqrt(1.0 / returned + 1.0 / (sim.returned_fraction * n));
  EXPECT_NEAR(sum_cos / returned, sim.mean_cos, 4 * cos_sd);
  EXPECT_GT(sum_cos / returned, 0.2) << "returns should favour the near side";
}

TEST(ReturnRule, PlanarReturnIsWrappedCauchy) {
  // In 2D every walker returns; the mean cosine of the wrapped Cauchy law is its
  // concentration R/r.
  const double R = 4.0, r = 10.0;
  const int n = 100000;
  Rng rng(29);
  double sum_cos = 0.0;
  for (int i = 0; i < n; ++i) {
    const ReturnPoint back = return_to_sphere(Vec3(r, 0, 0), R, rng, 2);
    ASSERT_TRUE(back.returned);
    ASSERT_NEAR(back.offset.norm(), R, 1e-9);
    ASSERT_EQ(back.offset.z(), 0.0);
    sum_cos += back.offset.x() / R;
  }
  EXPECT_NEAR(sum_cos / n, R / r, 0.01);
}

TEST(Contact, FirstTouchAlongAStep) {
  const Vec3 center(0, 0, 0);
  // Heading straight in from 3 with contact 1: touches at 2, a quarter of a step of 8.
  EXPECT_NEAR(contact_along(Vec3(3, 0, 0), Vec3(-8, 0, 0), center, 1.0), 0.25, 1e-15);
  EXPECT_LT(contact_along(Vec3(3, 0, 0), Vec3(-1, 0, 0), center, 1.0), 0.0) << "stops short";
  EXPECT_LT(contact_along(Vec3(3, 0, 0), Vec3(0, 5, 0), center, 1.0), 0.0) << "passes by";
  EXPECT_LT(contact_along(Vec3(3, 0, 0), Vec3(4, 0, 0), center, 1.0), 0.0) << "moves away";
  EXPECT_EQ(contact_along(Vec3(1, 0, 0), Vec3(-1, 0, 0), center, 1.0), 0.0) << "in contact, inwards";
  EXPECT_LT(contact_along(Vec3(1, 0, 0), Vec3(1, 0, 0), center, 1.0), 0.0) << "in contact, outwards";
  // A grazing step: the touching point is at distance 1 from the centre.
  const Vec3 from(-3, 0.999, 0), step(6, 0, 0);
  const double t = contact_along(from, step, center, 1.0);
  ASSERT_GE(t, 0.0);
  EXPECT_NEAR((from + t * step).norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace dla
