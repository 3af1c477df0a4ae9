// Row-parallel loops over all cores, with an optional progress bar on stderr.
#pragma once

#include <functional>
#include <string>

namespace bl::render {

// Calls row_fn(y) for y in [0, rows) on all hardware threads (rows in any order). When `label` is
// non-empty, draws a progress bar on stderr (only when stderr is a terminal, or always with
// BL_PROGRESS=1; CI logs get one line at the end). Exceptions from row_fn are rethrown here.
void parallel_rows(int rows, const std::function<void(int)>& row_fn, const std::string& label = "");

int thread_count();  // hardware threads, or BL_THREADS when set

}  // namespace bl::render
