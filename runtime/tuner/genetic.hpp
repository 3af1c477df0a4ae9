// Genetic search for the Pareto front of (time, error) over rule assignments, after Yang & Barnes
// 2018 Section 5 (and Sitthi-Amorn et al. 2011): initial guesses with one rule on every node (each
// crossed with another guess with probability 0.5), two-point crossover in depth-first order,
// mutation of 1/2/4 adjacent nodes or a subtree, tournament selection on Pareto rank (crowding
// distance breaks ties), elitism, independent random restarts merged into one front.
//
// Deterministic given the seed, the problem (cost model, truth, pixel sample) and the options; the
// thread count only changes speed: candidates are pure functions of their genome, evaluated in
// parallel into a cache, and every random draw happens on the calling thread.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "tuner/genome.hpp"
#include "tuner/pareto.hpp"

namespace bl::tuner {

struct Problem {
  const ir::Graph* graph = nullptr;
  SearchSpace space;
  Palette palette;
  // Time and error of a schedule; called concurrently. Infeasible: +infinity in both.
  std::function<Objectives(const compiler::Schedule&)> evaluate;
  // Identifies everything the objectives depend on (checkpoints refuse to resume another problem).
  std::string key;
};

struct SearchOptions {
  int population = 40;
  int generations = 20;  // bred generations after the initial one
  int restarts = 3;
  double elite = 0.25;
  double crossover = 0.4;
  double mutation = 0.35;
  double init_crossover = 0.5;
  int tournament = 4;
  std::uint64_t seed = 1;
  int threads = 0;             // 0: all hardware threads
  std::string checkpoint_dir;  // empty: no checkpoints
  // Stop (as if interrupted) after this many generations were bred in this call; -1: never.
  int stop_after = -1;
  std::function<void(const std::string&)> log;  // one line per generation
};

struct Point {
  Genome genome;
  Objectives obj;
};

struct RestartResult {
  std::vector<Point> front;  // non-dominated points of everything this restart evaluated
  int evaluations = 0;       // distinct genomes evaluated in this call (cache misses)
  bool complete = false;     // false when stopped by stop_after
};

// Shared across restarts of one process: evaluated genomes (speed only, never results).
class EvalCache {
 public:
  bool find(const std::string& key, Objectives* out);
  void put(const std::string& key, const Objectives& o);

 private:
  std::mutex mu_;
  std::map<std::string, Objectives> map_;
};

// One restart (seeded by seed and restart). Resumes from checkpoint_dir/restart_<r>.json when it
// exists for the same problem key, seed and options, and writes it after every generation.
RestartResult run_restart(const Problem& prob, const SearchOptions& opt, int restart, EvalCache& cache);

// The non-dominated points of all fronts, in restart order (first of equal points kept).
std::vector<Point> merge_fronts(const std::vector<std::vector<Point>>& fronts);

// All restarts and the merged front; `complete` is false when any restart stopped early.
RestartResult search(const Problem& prob, const SearchOptions& opt);

// Crowding distance (NSGA-II) of each point within its rank: larger = more isolated.
std::vector<double> crowding(const std::vector<Objectives>& pts, const std::vector<int>& ranks);

}  // namespace bl::tuner
