#include "tuner/genome.hpp"

#include <map>
#include <stdexcept>

namespace bl::tuner {

using rules::Kind;
using rules::Rule;

namespace {

int uniform_int(Rng& rng, int lo, int hi) {  // [lo, hi], identical on every platform
  return lo + static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
}

}  // namespace

Palette Palette::parse(const std::vector<std::string>& names) {
  if (names.empty()) throw std::invalid_argument("tuner: the rule palette is empty");
  if (names.size() > 250) throw std::invalid_argument("tuner: more than 250 rules in the palette");
  Palette p;
  std::map<int, int> family_of_kind;
  for (const std::string& n : names) {
    Rule r;
    if (n == "gaussian:rho=const") {
      r.kind = Kind::Gaussian;
      r.rho = rules::Rho::Constant;
    } else {
      r = rules::parse_rule(n);
    }
    for (const std::string& seen : p.names)
      if (seen == n) throw std::invalid_argument("tuner: rule '" + n + "' is listed twice in the palette");
    const int kind = static_cast<int>(r.kind);
    if (!family_of_kind.count(kind)) {
      family_of_kind[kind] = static_cast<int>(p.families.size());
      p.families.emplace_back();
    }
    p.families[family_of_kind[kind]].push_back(static_cast<int>(p.rules.size()));
    p.rules.push_back(r);
    p.names.push_back(n);
  }
  return p;
}

std::vector<std::string> Palette::default_names() {
  std::vector<std::string> out;
  for (const Rule& r : rules::all_rules()) out.push_back(rules::to_string(r));
  out.push_back("gaussian:rho=const");
  return out;
}

int Palette::random_rule(Rng& rng) const {
  const auto& fam = families[uniform_int(rng, 0, static_cast<int>(families.size()) - 1)];
  return fam[uniform_int(rng, 0, static_cast<int>(fam.size()) - 1)];
}

SearchSpace SearchSpace::build(const ir::Graph& g) {
  SearchSpace s;
  std::vector<int> gene_of(g.size(), -1);
  for (int node : g.depth_first_order()) {
    if (g.node(node).op == ir::Op::Const) continue;
    gene_of[node] = static_cast<int>(s.genes.size());
    s.genes.push_back(node);
  }
  // Subtrees: a node's descendants (shared nodes included), as gene positions in depth-first order.
  s.subtree.resize(s.genes.size());
  for (std::size_t k = 0; k < s.genes.size(); ++k) {
    std::vector<char> seen(g.size(), 0);
    std::vector<int> stack{s.genes[k]};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[n]) continue;
      seen[n] = 1;
      const ir::Node& nd = g.node(n);
      for (int a : {nd.a, nd.b, nd.c})
        if (a >= 0) stack.push_back(a);
    }
    for (std::size_t j = 0; j < s.genes.size(); ++j)
      if (seen[s.genes[j]]) s.subtree[k].push_back(static_cast<int>(j));
  }
  s.rho_constant.assign(g.size(), 0.0);
  return s;
}

Rule gene_rule(const SearchSpace& space, const Palette& pal, int k, int rule) {
  Rule r = pal.rules.at(rule);
  if (r.kind == Kind::Gaussian && r.rho == rules::Rho::Constant && pal.names[rule] == "gaussian:rho=const")
    r.rho_value = space.rho_constant[space.genes[k]];
  return r;
}

compiler::Schedule to_schedule(const ir::Graph& g, const SearchSpace& space, const Palette& pal,
                               const Genome& x) {
  if (static_cast<int>(x.size()) != space.size())
    throw std::invalid_argument("tuner: genome of " + std::to_string(x.size()) + " genes for a space of " +
                                std::to_string(space.size()));
  compiler::Schedule s(g.size());
  for (int k = 0; k < space.size(); ++k) {
    if (x[k] >= pal.rules.size())
      throw std::invalid_argument("tuner: gene " + std::to_string(k) + " holds rule index " +
                                  std::to_string(x[k]) + ", the palette has " +
                                  std::to_string(pal.rules.size()));
    s[space.genes[k]] = gene_rule(space, pal, k, x[k]);
  }
  return s;
}

Genome uniform_genome(const SearchSpace& space, int rule) {
  return Genome(space.size(), static_cast<std::uint8_t>(rule));
}

Genome crossover(const Genome& a, const Genome& b, Rng& rng) {
  const int n = static_cast<int>(a.size());
  if (n < 2) return a;
  int i = uniform_int(rng, 0, n - 1), j = uniform_int(rng, 0, n - 1);
  if (i > j) std::swap(i, j);
  Genome c = a;
  for (int k = i; k <= j; ++k) c[k] = b[k];
  return c;
}

Genome mutate(const Genome& x, const SearchSpace& space, const Palette& pal, Rng& rng) {
  Genome y = x;
  if (y.empty()) return y;
  const auto rule = static_cast<std::uint8_t>(pal.random_rule(rng));
  const int n = static_cast<int>(y.size());
  const int how = uniform_int(rng, 0, 3);
  const int at = uniform_int(rng, 0, n - 1);
  if (how == 3) {
    for (int k : space.subtree[at]) y[k] = rule;
  } else {
    const int len = 1 << how;  // 1, 2 or 4 adjacent genes, kept inside the genome
    const int start = std::min(at, std::max(0, n - len));
    for (int k = start; k < std::min(n, start + len); ++k) y[k] = rule;
  }
  return y;
}

std::string genome_key(const Genome& x) {
  static const char* digits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  std::string s;
  s.reserve(x.size() * 2);
  for (std::uint8_t v : x) {
    if (v < 62)
      s += digits[v];
    else
      s += '~', s += std::to_string(v), s += '.';
  }
  return s;
}

Genome genome_from_key(const std::string& key, int palette_size) {
  Genome x;
  for (std::size_t i = 0; i < key.size(); ++i) {
    const char c = key[i];
    int v = -1;
    if (c >= '0' && c <= '9')
      v = c - '0';
    else if (c >= 'a' && c <= 'z')
      v = 10 + c - 'a';
    else if (c >= 'A' && c <= 'Z')
      v = 36 + c - 'A';
    else if (c == '~') {
      const auto dot = key.find('.', i);
      if (dot == std::string::npos) break;
      v = std::stoi(key.substr(i + 1, dot - i - 1));
      i = dot;
    }
    if (v < 0 || v >= palette_size)
      throw std::invalid_argument("tuner: genome key '" + key.substr(0, 40) + "...' has a bad gene at " +
                                  std::to_string(i) + " for a palette of " + std::to_string(palette_size));
    x.push_back(static_cast<std::uint8_t>(v));
  }
  return x;
}

}  // namespace bl::tuner
