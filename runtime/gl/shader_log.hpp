// Turns a GLSL compiler info log into a message that shows the offending source lines.
#pragma once

#include <string>
#include <vector>

namespace bl::gl {

// 1-based source line numbers the log refers to, in order of first mention. Understands Mesa
// ("0:12(7): error: ...") and NVIDIA/AMD ("0(12) : error ...") formats.
std::vector<int> shader_log_lines(const std::string& log);

// The log followed by each referenced line of `source`, numbered ("  12 | vec3 c = ...").
std::string annotate_shader_log(const std::string& log, const std::string& source);

}  // namespace bl::gl
