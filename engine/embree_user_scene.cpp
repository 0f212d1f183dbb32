#include "engine/embree_user_scene.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace ncpath {

namespace {

void embree_error(void*, RTCError code, const char* message) {
  // Registered so Embree never prints on its own; the constructor reads errors back with
  // rtcGetDeviceError after the scene build and throws.
  (void)code;
  (void)message;
}

}  // namespace

EmbreeUserScene::EmbreeUserScene(std::size_t primitive_count, void* user_data,
                                 RTCBoundsFunction bounds, RTCIntersectFunctionN intersect,
                                 RTCOccludedFunctionN occluded, RTCSceneFlags flags) {
  device_ = rtcNewDevice("threads=0");
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = rtcNewScene(device_);
  if (flags != RTC_SCENE_FLAG_NONE) rtcSetSceneFlags(scene_, flags);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(primitive_count));
  rtcSetGeometryUserData(geom, user_data);
  rtcSetGeometryBoundsFunction(geom, bounds, user_data);
  rtcSetGeometryIntersectFunction(geom, intersect);
  rtcSetGeometryOccludedFunction(geom, occluded);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  const RTCError err = rtcGetDeviceError(device_);
  if (err != RTC_ERROR_NONE) {
    // The destructor does not run for a throwing constructor: release here.
    release();
    throw std::runtime_error("Embree: scene build failed with error code " +
                             std::to_string(static_cast<int>(err)));
  }
}

EmbreeUserScene::~EmbreeUserScene() { release(); }

EmbreeUserScene::EmbreeUserScene(EmbreeUserScene&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)),
      scene_(std::exchange(other.scene_, nullptr)) {}

EmbreeUserScene& EmbreeUserScene::operator=(EmbreeUserScene&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, nullptr);
    scene_ = std::exchange(other.scene_, nullptr);
  }
  return *this;
}

void EmbreeUserScene::release() {
  // The scene before the device that made it.
  if (scene_) rtcReleaseScene(std::exchange(scene_, nullptr));
  if (device_) rtcReleaseDevice(std::exchange(device_, nullptr));
}

}  // namespace ncpath
