#pragma once
// An Embree 3 device and scene holding one user geometry: the lifecycle (STYLE.md habit 4)
// shared by the engine's Embree indexes (drop_index, mesh_distance). Include it from .cpp
// files only: it brings in <embree3/rtcore.h>, which the indexes' headers keep out (pimpl).
//
// Also the float box padding both indexes hand to Embree: Embree works in float, the
// callbacks decide in double, so boxes are grown until rounding can only add candidates.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstddef>
#include <limits>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

// Owns an RTCDevice and an RTCScene with a single committed user geometry of
// `primitive_count` primitives. Move-only; a default-constructed or moved-from object owns
// nothing and scene() is null.
class EmbreeUserScene {
 public:
  EmbreeUserScene() = default;
  // `user_data` is handed to the bounds function (geometryUserPtr) and set as the geometry's
  // user data; it must outlive the scene. `flags` are set on the scene when not
  // RTC_SCENE_FLAG_NONE. Builds the BVH (quality high) at once. Throws std::runtime_error
  // when Embree cannot create a device or reports an error after the build.
  EmbreeUserScene(std::size_t primitive_count, void* user_data, RTCBoundsFunction bounds,
                  RTCIntersectFunctionN intersect, RTCOccludedFunctionN occluded,
                  RTCSceneFlags flags = RTC_SCENE_FLAG_NONE);
  ~EmbreeUserScene();
  EmbreeUserScene(EmbreeUserScene&& other) noexcept;
  EmbreeUserScene& operator=(EmbreeUserScene&& other) noexcept;
  EmbreeUserScene(const EmbreeUserScene&) = delete;
  EmbreeUserScene& operator=(const EmbreeUserScene&) = delete;

  // For rtcIntersect1, rtcPointQuery, ...; thread-safe to query once built.
  RTCScene scene() const { return scene_; }

 private:
  void release();

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// Float bounds that contain the double interval [lo, hi] with room for rounding: pad_down(lo)
// and pad_up(hi), grown by tol::kFloatBoxPad relative to (1 + |v|) and one float step more.
inline float pad_down(double v) {
  const double pad = tol::kFloatBoxPad * (1.0 + std::abs(v));
  return std::nextafter(static_cast<float>(v - pad), -std::numeric_limits<float>::infinity());
}
inline float pad_up(double v) {
  const double pad = tol::kFloatBoxPad * (1.0 + std::abs(v));
  return std::nextafter(static_cast<float>(v + pad), std::numeric_limits<float>::infinity());
}

}  // namespace ncpath
