// One frame of a scene: camera for a view, footprint options, and the shader inputs of a pixel.
#pragma once

#include "camera/camera.hpp"
#include "camera/plane_hit.hpp"
#include "scene/scene.hpp"

namespace bl::render {

camera::Camera make_camera(const scene::Scene& s, int view);
camera::FootprintOptions footprint_options(const scene::Scene& s);

// The native shader's inputs at one traced sample.
shaders::Inputs<float> native_inputs(const scene::Scene& s, const camera::PlaneSample& p, double time);

}  // namespace bl::render
