// The stability figure: one log-log panel per entry, worst error against sigma for the naive and
// the emitted form in float and double, with the table's bounds.
#pragma once

#include <string>
#include <vector>

#include "entries.hpp"
#include "sweep.hpp"

namespace nbs {

void plot_sweep(const std::string& png, const std::vector<Entry>& entries,
                const std::vector<std::vector<Point>>& results);

}  // namespace nbs
