#pragma once
// Embree 3's scene of a triangle mesh, shared by SurfaceIntersector (rays) and SurfaceDistance
// (point queries). Private to libdla: Embree stays out of the public headers.

#include "dla/core/errors.h"
#include "dla/mesh/mesh.h"

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include <string>

namespace dla::detail {

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

//! A device of its own on one thread, and the mesh's scene in floats: robust (no ray slips
//! through a vertex) and built for many queries. Throws GrowthError if Embree fails.
class EmbreeScene {
 public:
  explicit EmbreeScene(const TriangleMesh& mesh) {
    FlushDenormals flush;
    device_ = rtcNewDevice("threads=1,set_affinity=0");
    if (!device_) throw GrowthError("Embree cannot start: error " + std::to_string(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(
        device_, [](void* user, RTCError, const char* message) { static_cast<EmbreeScene*>(user)->error_ = message; },
        this);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.vertices.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    check("allocate the mesh");
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      for (int a = 0; a < 3; ++a) vertices[3 * i + a] = static_cast<float>(mesh.vertices[i][a]);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int a = 0; a < 3; ++a) indices[3 * t + a] = mesh.triangles[t][a];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    check("build the scene");
  }
  ~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene scene() const { return scene_; }

 private:
  void check(const char* what) const {
    if (!error_.empty()) throw GrowthError(std::string("Embree failed to ") + what + ": " + error_);
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::string error_;  // set by Embree's error callback, thrown after the call returns
};

}  // namespace dla::detail
