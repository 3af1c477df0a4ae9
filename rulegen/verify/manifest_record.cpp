// blverify: manifest matching and --record (see manifest_record.hpp).
#include "manifest_record.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

namespace blv {
namespace {

using json = nlohmann::ordered_json;

bool read_text(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  *text = ss.str();
  return true;
}

// Indentation of the existing file (spaces before the first key), so the emitter and the
// verifier write the same layout.
int detect_indent(const std::string& text) {
  std::size_t nl = text.find('\n');
  if (nl == std::string::npos) return 2;
  int n = 0;
  for (std::size_t i = nl + 1; i < text.size() && text[i] == ' '; ++i) ++n;
  return n > 0 ? n : 2;
}

std::string str_field(const json& j, const char* k) {
  auto it = j.find(k);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

using Key = std::tuple<std::string, std::string, bool, std::string, int>;
Key key_of(const EntryView& e) { return {e.atomic, e.kernel, e.squared, e.rule, e.rule == "moment" ? e.order : 0}; }
Key key_of(const json& j) {
  bool sq = j.contains("squared") && j["squared"].is_boolean() && j["squared"].get<bool>();
  int order = j.contains("order") && j["order"].is_number_integer() ? j["order"].get<int>() : 0;
  std::string rule = str_field(j, "rule");
  if (rule.empty()) rule = "convolution";
  return {str_field(j, "atomic"), str_field(j, "kernel"), sq, rule, rule == "moment" ? order : 0};
}

bool load(const std::string& path, json* doc, std::string* text, std::string* error) {
  if (!read_text(path, text)) {
    *error = "cannot read " + path;
    return false;
  }
  try {
    *doc = json::parse(*text);
  } catch (const std::exception& ex) {
    *error = path + ": " + ex.what();
    return false;
  }
  if (!doc->contains("entries") || !(*doc)["entries"].is_array()) {
    *error = path + ": no \"entries\" array";
    return false;
  }
  return true;
}

bool do_match(const json& doc, const std::vector<EntryView>& entries, std::vector<int>* match,
              std::vector<std::string>* warnings) {
  const json& arr = doc["entries"];
  std::map<std::string, std::vector<int>> by_cpp;
  std::map<Key, std::vector<int>> by_key;
  for (int j = 0; j < static_cast<int>(arr.size()); ++j) {
    by_cpp[str_field(arr[j], "cpp")].push_back(j);
    by_key[key_of(arr[j])].push_back(j);
  }
  match->assign(entries.size(), -1);
  std::vector<int> used(arr.size(), 0);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const EntryView& e = entries[i];
    auto it = by_cpp.find(e.cpp);
    const std::vector<int>* cand = nullptr;
    if (it != by_cpp.end()) {
      cand = &it->second;
    } else {
      auto kt = by_key.find(key_of(e));
      if (kt != by_key.end()) cand = &kt->second;
    }
    if (!cand) {
      warnings->push_back("registry entry " + e.cpp + " has no manifest entry");
      continue;
    }
    if (cand->size() > 1) {
      warnings->push_back("registry entry " + e.cpp + " matches " + std::to_string(cand->size()) +
                          " manifest entries; not recorded");
      continue;
    }
    (*match)[i] = (*cand)[0];
    ++used[(*cand)[0]];
  }
  for (std::size_t j = 0; j < arr.size(); ++j) {
    const std::string rule = str_field(arr[j], "rule");
    // Rule entries have their own checks (rules_check.hpp, verify/clamped).
    if (rule != "convolution" && rule != "moment" && !rule.empty()) continue;
    if (used[j] == 0) warnings->push_back("manifest entry " + str_field(arr[j], "cpp") + " is not in the compiled registry (rebuild blverify after `rulegen emit`)");
    if (used[j] > 1) warnings->push_back("manifest entry " + str_field(arr[j], "cpp") + " matched by several registry entries");
  }
  return true;
}

}  // namespace

bool match_manifest(const std::string& path, const std::vector<EntryView>& entries, std::vector<int>* match,
                    std::vector<std::string>* warnings) {
  json doc;
  std::string text, error;
  if (!load(path, &doc, &text, &error)) {
    warnings->push_back(error);
    return false;
  }
  return do_match(doc, entries, match, warnings);
}

bool record_manifest(const std::string& path, const std::vector<EntryView>& entries,
                     const std::vector<EntryResult>& results, const VerifyOptions& opt, std::string* error,
                     std::vector<std::string>* warnings) {
  json doc;
  std::string text;
  if (!load(path, &doc, &text, error)) return false;
  std::vector<int> match;
  do_match(doc, entries, &match, warnings);
  json& arr = doc["entries"];
  for (const EntryResult& r : results) {
    int j = match[r.index];
    if (j < 0) continue;
    json v;
    v["points"] = r.points;
    v["skipped"] = r.skipped;
    v["worst_rel_error_double"] = round2(r.worst_d);
    v["worst_rel_error_float"] = round2(r.worst_f);
    v["bound_double"] = opt.bound_double;
    v["bound_float"] = opt.bound_float;
    if (std::isnan(r.formula50))
      v["formula_error_50digits"] = nullptr;
    else
      v["formula_error_50digits"] = round2(r.formula50);
    v["status"] = r.status;
    arr[j]["verification"] = v;  // replaces in place (keeps the key order) or appends
  }
  std::string out = doc.dump(detect_indent(text));
  if (!text.empty() && text.back() == '\n') out += '\n';
  const std::string tmp = path + ".blverify.tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o || !(o << out) || !o.flush()) {
      *error = "cannot write " + tmp;
      std::remove(tmp.c_str());
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    *error = "cannot rename " + tmp + " to " + path;
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace blv
