// The one plotting helper of the notebooks: gnuplot (pngcairo) fed a script through a pipe, with
// the data inline as named datablocks, so a notebook writes only its PNG (and its .md).
#pragma once

#include <string>
#include <vector>

namespace nb {

// "$name << EOD ... EOD" with one row per line; NaN cells are written as NaN (gnuplot skips them).
std::string datablock(const std::string& name, const std::vector<std::vector<double>>& rows);

// Runs gnuplot on the script; throws std::runtime_error with the reason when gnuplot is missing
// (apt-get install gnuplot-nox) or fails.
void run_gnuplot(const std::string& script);

}  // namespace nb
