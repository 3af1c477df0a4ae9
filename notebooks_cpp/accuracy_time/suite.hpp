// The tuner's suite output (bltune --suite DIR): one folder per scene with result.json, read with the
// tuner's own result_from_json; speed-ups at equal error with the tuner's speedups().
#pragma once

#include <string>
#include <vector>

#include "tuner/finalize.hpp"
#include "tuner/report.hpp"

namespace nb::acc {

struct Suite {
  std::string dir;
  bool found = false;                          // the directory exists
  std::vector<bl::tuner::SceneResult> scenes;  // in the order of scenes/suite (finished ones)
  std::vector<std::string> missing;            // scenes of scenes/suite without a result.json
};

// Reads DIR/<scene>/result.json for every scene file in scenes_dir (scenes/suite/*.json).
Suite read_suite(const std::string& dir, const std::string& scenes_dir);

// The MSAA baseline with n samples; nullptr when absent.
const bl::tuner::Measured* msaa(const bl::tuner::SceneResult& r, int n);
// The speed-up record at MSAA-n (front_index -1 when no front point reaches its error).
bl::tuner::Speedup speedup_at(const bl::tuner::SceneResult& r, int n);

}  // namespace nb::acc
