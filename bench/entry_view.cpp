// Builds the entry views from the generated registry (the one place the table is instantiated).
#include "entry_view.hpp"

#include <cstring>
#include <map>
#include <stdexcept>

#include "bandlimit/registry.hpp"

namespace blb {
namespace {

Kernel parse_kernel(const char* k) {
  if (std::strcmp(k, "gaussian") == 0) return Kernel::Gaussian;
  if (std::strcmp(k, "box") == 0) return Kernel::Box;
  if (std::strcmp(k, "tent") == 0) return Kernel::Tent;
  throw std::runtime_error(std::string("bench_table: unknown kernel ") + k);
}

std::string family_of(const std::string& atomic) {
  static const std::map<std::string, std::string> kFamily = {
      {"sin", "trig"},           {"cos", "trig"},
      {"exp", "exp-like"},       {"sinh", "exp-like"},
      {"cosh", "exp-like"},      {"abs", "piecewise"},
      {"sign", "piecewise"},     {"step", "piecewise"},
      {"saturate", "piecewise"}, {"smoothstep", "piecewise"},
      {"fract", "periodic"},     {"triangle", "periodic"},
      {"square", "periodic"},    {"floor", "periodic"},
      {"ceil", "periodic"},      {"trunc", "periodic"},
      {"tan", "singular"},       {"tanh", "singular"},
      {"log", "singular"},       {"sqrt", "singular"},
      {"inv", "singular"},       {"inv2", "singular"},
      {"laplace", "piecewise"},  {"exp_decay", "piecewise"},
      {"exp_ramp", "piecewise"}, {"pulse30", "periodic"},
      {"xexp", "exp-like"},      {"moment", "powers"}};
  if (atomic.rfind("pow", 0) == 0) return "powers";
  auto it = kFamily.find(atomic);
  return it == kFamily.end() ? "other" : it->second;
}

template <class T>
std::vector<EntryView<T>> build() {
  int n = 0;
  const bl::registry::Entry<T>* e = bl::registry::entries<T>(&n);
  std::vector<EntryView<T>> out;
  for (int i = 0; i < n; ++i) {
    const bool moment = std::strcmp(e[i].rule, "moment") == 0;
    std::string fn;
    if (moment) {
      fn = "moment" + std::to_string(e[i].order);
    } else {
      fn = e[i].cpp;
      fn = fn.substr(fn.rfind("::") + 2);
    }
    const int power = moment ? e[i].order : (e[i].squared ? 2 : 1);
    out.push_back({&e[i], parse_kernel(e[i].kernel), power, std::string(e[i].kernel) + "/" + fn,
                   family_of(e[i].atomic->name)});
  }
  return out;
}

}  // namespace

const std::vector<EntryView<double>>& double_entries() {
  static const std::vector<EntryView<double>> v = build<double>();
  return v;
}

const std::vector<EntryView<float>>& float_entries() {
  static const std::vector<EntryView<float>> v = build<float>();
  return v;
}

const std::vector<std::string>& families() {
  static const std::vector<std::string> f = {"trig",      "exp-like", "powers",
                                             "piecewise", "periodic", "singular"};
  return f;
}

}  // namespace blb
