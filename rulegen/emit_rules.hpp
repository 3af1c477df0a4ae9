// Emission of the rules beyond plain convolution that this module derives: the bivariate Gaussian
// operators (generated/bandlimit/rules_bivariate.hpp) and Rule 2, the mode fit
// (generated/bandlimit/rules_mode.hpp), their GLSL (generated/bandlimit_bivariate.glsl) and their
// manifest entries (appended to generated/manifest.json, which emit_manifest writes first).
#pragma once

#include <string>
#include <vector>

#include "catalog.hpp"
#include "derived.hpp"

namespace bl::rulegen {

void emit_rules(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, const std::string& out_dir);

}  // namespace bl::rulegen
