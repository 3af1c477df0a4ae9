// A pinhole camera over the ground plane z = 0.
//
// World: right-handed, z up; the ground is the plane z = 0 and the camera must be above it (z > 0).
// Orientation (degrees), applied as yaw, then pitch, then roll:
//   yaw   heading about +z: 0 looks along +x, 90 along +y (counter-clockwise seen from above);
//   pitch elevation: 0 horizontal, -90 straight down, +90 straight up;
//   roll  about the view axis: positive turns the camera counter-clockwise as seen from behind it,
//         so the scene turns clockwise in the image.
// Pixels: (px, py) are continuous image coordinates with y DOWN; pixel (i, j) covers
// [i, i+1) x [j, j+1) and has its centre at (i + 0.5, j + 0.5); row j = 0 is the top row. This is the
// order of bl::Image and of bl::gl::Context::render (where gl_FragCoord.xy = (px, py)).
#pragma once

#include "camera/vec3.hpp"

namespace bl::camera {

struct Camera {
  Vec3d position{0, 0, 1};
  double yaw_deg = 0;
  double pitch_deg = -30;
  double roll_deg = 0;
  double vfov_deg = 60;  // vertical field of view
  int width = 512;
  int height = 512;
};

// Orthonormal camera frame: image right, image up, and forward = the view direction.
struct Basis {
  Vec3d right, up, forward;
};

// Throws std::invalid_argument for a camera at or below the plane, a size < 1, or a FOV outside (0, 180).
void validate(const Camera& cam);

Basis basis(const Camera& cam);

// Focal length in pixels: (height / 2) / tan(vfov / 2).
double focal_px(const Camera& cam);

// The (unnormalized) direction of the ray through image point (px, py):
// forward * focal_px + right * (px - width/2) - up * (py - height/2). Linear in (px, py), so
// d/dpx = right and d/dpy = -up exactly; the plane differentials rely on that.
Vec3d ray_direction(const Camera& cam, const Basis& b, double px, double py);

}  // namespace bl::camera
