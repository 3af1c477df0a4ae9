// One frame of a scene: camera for a view, footprint options, and the shader inputs of a pixel.
#pragma once

#include "camera/camera.hpp"
#include "camera/plane_batch.hpp"
#include "camera/plane_hit.hpp"
#include "scene/scene.hpp"

namespace bl::render {

camera::Camera make_camera(const scene::Scene& s, int view);
camera::FootprintOptions footprint_options(const scene::Scene& s);

// Pixel i's colour channel from its shaded value: the plane's share (coverage) of the shade, the rest
// the background (a miss is all background).
inline double covered(const camera::PlaneBatch& b, std::size_t i, double shade, double background) {
  if (!b.hit[i]) return background;
  const double c = b.coverage[i];
  return c * shade + (1 - c) * background;
}

// The native shader's inputs at one traced sample.
shaders::Inputs<float> native_inputs(const scene::Scene& s, const camera::PlaneSample& p, double time);

}  // namespace bl::render
