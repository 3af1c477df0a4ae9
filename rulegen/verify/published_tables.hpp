// blverify --published: every entry of Yang & Barnes 2018 Table 3 and Dorn et al. 2015 Table 1,
// transcribed as printed, compared with quadrature and with the registry.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "registry_view.hpp"

namespace blv {

// Prints one verdict per published entry to `out`, writes a Markdown report when report_path is
// not empty. Returns 0 unless a registry entry disagrees with quadrature (a typo in a paper is a
// finding, not a failure), 2 when the report cannot be written.
int run_published(const std::vector<EntryView>& entries, const std::string& report_path, std::FILE* out);

}  // namespace blv
