// Issue 14's speed targets checked on one summary run: per-kernel median smoothed/plain (float and
// double), the worst periodic entry, entries above 10x, and double's ratio against float's. The
// section is written into <prefix>.md and its verdict lines to stderr; times are never asserted in
// a unit test (the machine is shared), only printed beside the target they are read against.
#pragma once

#include <ostream>
#include <vector>

#include "report.hpp"

namespace blb {

// Writes "## Speed targets" (markdown) and returns the number of targets missed.
int write_targets(std::ostream& o, const std::vector<Row>& rows);

}  // namespace blb
