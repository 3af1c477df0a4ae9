// SceneResult <-> JSON: the MPI driver gathers finished scenes to rank 0 this way, and bltune writes
// result.json next to each report (machine-readable).
#pragma once

#include <string>

#include "tuner/finalize.hpp"

namespace bl::tuner {

std::string result_to_json(const SceneResult& r);
SceneResult result_from_json(const std::string& text);
// A result.json file read back; throws std::runtime_error naming the file when it is unreadable or
// malformed.
SceneResult load_result(const std::string& path);

}  // namespace bl::tuner
