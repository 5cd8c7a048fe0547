// Embree 3 behind SurfaceIntersector. The scene is robust: with the default flags about 7% of
// segments through a mesh vertex pass the surface unseen.

#include "dla/mesh/surface_intersector.h"

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include <limits>
#include <string>

namespace dla {

struct SurfaceIntersector::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;  // set by Embree's error callback, thrown after the call returns

  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void check(const char* what) const {
    if (!error.empty()) throw GrowthError(std::string("Embree failed to ") + what + ": " + error);
  }
};

namespace {

//! Embree wants denormals flushed to zero; the walk's own arithmetic does not, so the mode is
//! set around each call only.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
};

}  // namespace

SurfaceIntersector::SurfaceIntersector(const TriangleMesh& mesh) : scene_(std::make_unique<Scene>()) {
  FlushDenormals flush;
  Scene& s = *scene_;
  s.device = rtcNewDevice("threads=1,set_affinity=0");
  if (!s.device) throw GrowthError("Embree cannot start: error " + std::to_string(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(
      s.device, [](void* user, RTCError, const char* message) { static_cast<Scene*>(user)->error = message; }, &s);
  s.scene = rtcNewScene(s.device);
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  s.check("allocate the mesh");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int a = 0; a < 3; ++a) vertices[3 * i + a] = static_cast<float>(mesh.vertices[i][a]);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int a = 0; a < 3; ++a) indices[3 * t + a] = mesh.triangles[t][a];
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(s.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(s.scene);
  s.check("build the scene");
}

SurfaceIntersector::~SurfaceIntersector() = default;
SurfaceIntersector::SurfaceIntersector(SurfaceIntersector&&) noexcept = default;
SurfaceIntersector& SurfaceIntersector::operator=(SurfaceIntersector&&) noexcept = default;

double SurfaceIntersector::first_hit(const Vec3& from, const Vec3& to, double t_min, double t_max) const {
  FlushDenormals flush;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit{};
  const Vec3 d = to - from;
  hit.ray.org_x = static_cast<float>(from.x());
  hit.ray.org_y = static_cast<float>(from.y());
  hit.ray.org_z = static_cast<float>(from.z());
  hit.ray.dir_x = static_cast<float>(d.x());
  hit.ray.dir_y = static_cast<float>(d.y());
  hit.ray.dir_z = static_cast<float>(d.z());
  hit.ray.tnear = static_cast<float>(t_min);
  hit.ray.tfar = static_cast<float>(t_max);
  hit.ray.mask = std::numeric_limits<unsigned>::max();
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_->scene, &context, &hit);
  return hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0 : static_cast<double>(hit.ray.tfar);
}

}  // namespace dla
