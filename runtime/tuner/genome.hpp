// The search space: a genome holds one palette index per *gene*, a graph node whose rule can matter
// (every node reachable from the outputs except constants), in depth-first (post-order) order, so
// "adjacent nodes" for crossover and mutation means adjacent in Graph::depth_first_order().
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "compiler/lower.hpp"
#include "ir/graph.hpp"
#include "rules/rule.hpp"

namespace bl::tuner {

using Genome = std::vector<std::uint8_t>;  // palette index per gene
using Rng = std::mt19937_64;

// The rules the search may assign. Rules are grouped into families (one per Rule::Kind: the MC
// counts form one family, the rho modes of "gaussian" another, the Rule 1 kernels another), and a
// random rule picks a family uniformly, then a member uniformly (Yang & Barnes 5: sample counts and
// rho modes with equal probability). "gaussian:rho=const" stands for a per-node constant rho
// estimated by sampling (rho_estimate.hpp); it is filled in per node when a schedule is built.
struct Palette {
  std::vector<rules::Rule> rules;
  std::vector<std::string> names;          // as given (reports, checkpoints)
  std::vector<std::vector<int>> families;  // indices into rules

  // Throws std::invalid_argument naming a bad rule text, a duplicate, or an empty list.
  static Palette parse(const std::vector<std::string>& names);
  static std::vector<std::string> default_names();  // every rule of all_rules() + gaussian:rho=const
  int random_rule(Rng& rng) const;
};

struct SearchSpace {
  std::vector<int> genes;                 // graph node per gene, depth-first order
  std::vector<std::vector<int>> subtree;  // per gene: gene positions of its subtree (incl. itself)
  std::vector<double> rho_constant;       // per graph node: estimated rho for rho=const (0 if none)

  static SearchSpace build(const ir::Graph& g);
  int size() const { return static_cast<int>(genes.size()); }
};

// Palette rule `rule` as gene k carries it (gaussian:rho=const takes the gene's estimated rho).
rules::Rule gene_rule(const SearchSpace& space, const Palette& pal, int k, int rule);

// The schedule of a genome: palette rules on the genes, "none" elsewhere (constants).
compiler::Schedule to_schedule(const ir::Graph& g, const SearchSpace& space, const Palette& pal,
                               const Genome& x);

Genome uniform_genome(const SearchSpace& space, int rule);

// Two-point crossover: a with the gene range [i, j] taken from b (i <= j drawn uniformly).
Genome crossover(const Genome& a, const Genome& b, Rng& rng);

// Assigns one new random rule to 1, 2 or 4 adjacent genes, or to a whole subtree, each with
// probability 1/4.
Genome mutate(const Genome& x, const SearchSpace& space, const Palette& pal, Rng& rng);

std::string genome_key(const Genome& x);  // compact text, unique per genome (cache and checkpoints)
Genome genome_from_key(const std::string& key, int palette_size);

}  // namespace bl::tuner
