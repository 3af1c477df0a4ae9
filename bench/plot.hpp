// The accuracy-cost plot: RMS error against ns per call (both log), one panel per function
// family, one point style per method, drawn by gnuplot from the summary CSV.
#pragma once

#include <string>
#include <vector>

namespace blb {

// Runs gnuplot (pngcairo) on a generated script, one panel per family listed (those with rows);
// throws std::runtime_error with the reason when gnuplot is missing or fails.
void write_plot(const std::string& csv_path, const std::string& png_path,
                const std::vector<std::string>& panel_families);

}  // namespace blb
