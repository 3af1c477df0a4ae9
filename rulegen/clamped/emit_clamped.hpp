// Emission of the clamped-domain rules of issue 3 (derivatives, Rule 1, Rule 3, bimodal
// truncation, compact half-widths) into generated/bandlimit/rules_clamped.hpp,
// generated/bandlimit_clamped.glsl and entries appended to generated/manifest.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "derived.hpp"
#include "printer.hpp"

namespace bl::rulegen::clamped {

// What each section contributes to the three outputs.
struct Output {
  std::string impl;      // C++ templates in bl::detail::gen
  std::string api;       // C++ public functions (float/double overloads), each inside its namespace
  std::string registry;  // C++ RuleEntry initialisers
  std::string glsl;      // GLSL functions
  nlohmann::ordered_json manifest = nlohmann::ordered_json::array();
};

// Small printing helpers shared by the sections.
std::string lit(double v, sym::Lang lang);  // shortest round-trip literal, T(...) in C++
std::string bound(const sym::Bound& b, sym::Lang lang);
std::string piece_table(const std::string& name, const std::vector<sym::PolyPiece>& ps, sym::Lang lang);

void emit_derivatives(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, Output& out);
void emit_rules(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, Output& out);

// Writes the files; called by `rulegen emit` after the manifest exists.
void emit_clamped(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, const std::string& out_dir);

}  // namespace bl::rulegen::clamped
