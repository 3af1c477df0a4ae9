// blverify: matching generated/manifest.json to the compiled registry, and --record (writes each
// entry's "verification" object, preserving the rest of the JSON and its key order).
#pragma once

#include <string>
#include <vector>

#include "registry_view.hpp"
#include "verify_entry.hpp"

namespace blv {

// For each registry entry, the index of its manifest entry (-1: none). Matched by "cpp", else by
// (atomic, kernel, squared, rule, order). Problems (unreadable file, entries on one side only,
// ambiguous matches) go to *warnings; returns false when the manifest cannot be read.
bool match_manifest(const std::string& manifest_path, const std::vector<EntryView>& entries,
                    std::vector<int>* match, std::vector<std::string>* warnings);

// Writes "verification" into the manifest entries matched by `results` (atomically: temp + rename).
bool record_manifest(const std::string& manifest_path, const std::vector<EntryView>& entries,
                     const std::vector<EntryResult>& results, const VerifyOptions& opt, std::string* error,
                     std::vector<std::string>* warnings);

}  // namespace blv
