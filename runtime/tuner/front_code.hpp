// Code out: every measured front point as a self-contained smoothed shader function, the files a
// user includes in their renderer (the same form as blrender's shader.glsl / shader.hpp).
#pragma once

#include <string>

#include "tuner/finalize.hpp"

namespace bl::tuner {

// Writes <dir>/front/<label>.glsl and <dir>/front/<label>.hpp for every point of r.front, each the
// function `shade` (compiler::emit_glsl / emit_cpp) of the schedule read back from its text (so what
// is written is exactly what `blrender --schedule <dir>/front.csv:<label>` renders), with a banner
// naming the scene, the graph, the measured error and the schedule. Returns the number of points.
// With a footprint LOD (r.lod) also <dir>/front/lod.glsl and lod.hpp: compiler::emit_glsl_lod /
// emit_cpp_lod of its two points.
int write_front_code(const SceneTuner& t, const SceneResult& r, const std::string& dir);

}  // namespace bl::tuner
