// The spawn distributions: where starts fall, and that they are uniform there.

#include "dla/models/spawn.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace dla {
namespace {

TEST(Spawn, SphereIsUniformOnTheLaunchSphere) {
  DlaOptions o;
  const Vec3 center(5, -2, 1);
  Rng rng(1);
  std::array<int, 8> octants{};
  const int n = 80000;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = draw_spawn(o, center, 30.0, rng) - center;
    ASSERT_NEAR(x.norm(), 30.0, 1e-9);
    ++octants[(x.x() > 0) + 2 * (x.y() > 0) + 4 * (x.z() > 0)];
  }
  double chi2 = 0.0;
  for (int count : octants) chi2 += std::pow(count - n / 8.0, 2) / (n / 8.0);
  EXPECT_LT(chi2, 24.3) << "chi-square with 7 degrees of freedom, p = 0.001";
}

TEST(Spawn, DiskIsUniformInASmallDiskOnTheAxis) {
  DlaOptions o;
  o.spawn = SpawnMode::disk;
  o.spawn_axis = Axis::y;
  o.disk_radius = 0.2;
  Rng rng(2);
  const int n = 40000;
  int inner = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = draw_spawn(o, Vec3::Zero(), 50.0, rng);
    ASSERT_NEAR(x.y(), 50.0, 1e-9);
    const double rho = std::hypot(x.x(), x.z());
    ASSERT_LE(rho, 10.0 + 1e-9);
    inner += rho < 10.0 / std::sqrt(2.0);
  }
  EXPECT_NEAR(static_cast<double>(inner) / n, 0.5, 0.015) << "half the area is within r/sqrt(2)";
}

TEST(Spawn, PlanarDiskIsASegmentInThePlane) {
  DlaOptions o;
  o.dimensions = 2;
  o.spawn = SpawnMode::disk;
  o.spawn_axis = Axis::x;
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 x = draw_spawn(o, Vec3::Zero(), 20.0, rng);
    ASSERT_NEAR(x.x(), 20.0, 1e-9);
    ASSERT_LE(std::abs(x.y()), 5.0 + 1e-9);
    ASSERT_EQ(x.z(), 0.0);
  }
}

TEST(Spawn, BoxIsUniformInTheBox) {
  DlaOptions o;
  o.spawn = SpawnMode::box;
  o.spawn_box = Box{Vec3(-1, 2, 3), Vec3(5, 4, 13)};
  Rng rng(4);
  const int n = 60000;
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 x = draw_spawn(o, Vec3::Zero(), 10.0, rng);
    for (int a = 0; a < 3; ++a) {
      ASSERT_GE(x[a], o.spawn_box->min[a]);
      ASSERT_LE(x[a], o.spawn_box->max[a]);
    }
    mean += x / n;
  }
  const Vec3 middle = 0.5 * (o.spawn_box->min + o.spawn_box->max);
  for (int a = 0; a < 3; ++a) {
    const double width = o.spawn_box->max[a] - o.spawn_box->min[a];
    EXPECT_NEAR(mean[a], middle[a], 5 * width / std::sqrt(12.0 * n));
  }
}

TEST(Spawn, DefaultBoxIsTheCubeAroundTheLaunchSphere) {
  DlaOptions o;
  o.spawn = SpawnMode::box;
  Rng rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 x = draw_spawn(o, Vec3(1, 1, 1), 7.0, rng);
    ASSERT_LE((x - Vec3(1, 1, 1)).cwiseAbs().maxCoeff(), 7.0);
  }
}

}  // namespace
}  // namespace dla
