// blverify: the verification table (stdout) and the Markdown report.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "verify_entry.hpp"

namespace blv {

void print_table(std::FILE* out, const std::vector<EntryResult>& results, const VerifyOptions& opt, bool verbose);
std::string markdown_report(const std::vector<EntryResult>& results, const VerifyOptions& opt);

}  // namespace blv
