// SceneResult <-> JSON: the MPI driver gathers finished scenes to rank 0 this way, and bltune writes
// result.json next to each report (machine-readable).
#pragma once

#include <string>

#include "tuner/finalize.hpp"

namespace bl::tuner {

std::string result_to_json(const SceneResult& r);
SceneResult result_from_json(const std::string& text);

}  // namespace bl::tuner
