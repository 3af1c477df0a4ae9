#include "camera/camera.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bl::camera {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;
}

void validate(const Camera& cam) {
  if (!(cam.position.z > 0)) {
    throw std::invalid_argument("camera: position.z = " + std::to_string(cam.position.z) +
                                ": the camera must be above the ground plane z = 0");
  }
  if (cam.width < 1 || cam.height < 1) {
    throw std::invalid_argument("camera: image size " + std::to_string(cam.width) + "x" +
                                std::to_string(cam.height) + " must be at least 1x1");
  }
  if (!(cam.vfov_deg > 0 && cam.vfov_deg < 180)) {
    throw std::invalid_argument("camera: vfov_deg = " + std::to_string(cam.vfov_deg) +
                                " is outside (0, 180)");
  }
}

Basis basis(const Camera& cam) {
  const double yaw = cam.yaw_deg * kDegree, pitch = cam.pitch_deg * kDegree, roll = cam.roll_deg * kDegree;
  const Vec3d forward{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
  // From the heading alone, so looking straight up or down stays well defined.
  const Vec3d right0{std::sin(yaw), -std::cos(yaw), 0.0};
  const Vec3d up0 = cross(right0, forward);
  const double c = std::cos(roll), s = std::sin(roll);
  return {c * right0 + s * up0, c * up0 - s * right0, forward};
}

double focal_px(const Camera& cam) {
  return 0.5 * cam.height / std::tan(0.5 * cam.vfov_deg * kDegree);
}

Vec3d ray_direction(const Camera& cam, const Basis& b, double px, double py) {
  return focal_px(cam) * b.forward + (px - 0.5 * cam.width) * b.right - (py - 0.5 * cam.height) * b.up;
}

}  // namespace bl::camera
