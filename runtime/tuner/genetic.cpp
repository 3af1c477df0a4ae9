#include "tuner/genetic.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <thread>

#include "tuner/checkpoint.hpp"

namespace bl::tuner {

namespace {

std::uint64_t mix64(std::uint64_t x) {  // splitmix64: independent streams per restart
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double uniform01(Rng& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

int uniform_int(Rng& rng, int n) {
  return static_cast<int>(rng() % static_cast<std::uint64_t>(n));
}

// Evaluates every genome not in the cache, on `threads` threads, in a fixed order of work items.
std::vector<Objectives> evaluate_all(const Problem& prob, const std::vector<Genome>& pop, int threads,
                                     EvalCache& cache, int* evaluations) {
  std::vector<std::string> keys(pop.size());
  std::vector<Objectives> out(pop.size());
  std::vector<int> todo;
  std::map<std::string, int> first;
  for (std::size_t i = 0; i < pop.size(); ++i) {
    keys[i] = genome_key(pop[i]);
    if (cache.find(keys[i], &out[i])) continue;
    if (first.emplace(keys[i], static_cast<int>(i)).second) todo.push_back(static_cast<int>(i));
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mu;
  auto worker = [&] {
    for (int k; (k = next.fetch_add(1)) < static_cast<int>(todo.size());) {
      const int i = todo[k];
      try {
        out[i] = prob.evaluate(to_schedule(*prob.graph, prob.space, prob.palette, pop[i]));
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mu);
        if (!error) error = std::current_exception();
      }
    }
  };
  const int n = std::max(1, std::min(threads, static_cast<int>(todo.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  for (int i : todo) cache.put(keys[i], out[i]);
  for (std::size_t i = 0; i < pop.size(); ++i) cache.find(keys[i], &out[i]);
  *evaluations += static_cast<int>(todo.size());
  return out;
}

std::vector<Point> update_front(std::vector<Point> front, const std::vector<Genome>& pop,
                                const std::vector<Objectives>& obj) {
  for (std::size_t i = 0; i < pop.size(); ++i)
    if (std::isfinite(obj[i].time) && std::isfinite(obj[i].error)) front.push_back({pop[i], obj[i]});
  std::vector<Objectives> pts;
  for (const Point& p : front) pts.push_back(p.obj);
  std::vector<Point> out;
  for (int i : pareto_front(pts)) out.push_back(front[i]);
  return out;
}

std::vector<Genome> initial_population(const Problem& prob, const SearchOptions& opt, Rng& rng) {
  const int rules = static_cast<int>(prob.palette.rules.size());
  std::vector<Genome> pop;
  for (int r = 0; r < rules && static_cast<int>(pop.size()) < opt.population; ++r)
    pop.push_back(uniform_genome(prob.space, r));
  while (static_cast<int>(pop.size()) < opt.population) {
    Genome g = uniform_genome(prob.space, prob.palette.random_rule(rng));
    if (uniform01(rng) < opt.init_crossover)
      g = crossover(g, uniform_genome(prob.space, prob.palette.random_rule(rng)), rng);
    else
      g = mutate(g, prob.space, prob.palette, rng);
    pop.push_back(std::move(g));
  }
  return pop;
}

std::vector<Genome> breed(const Problem& prob, const SearchOptions& opt, const std::vector<Genome>& pop,
                          const std::vector<Objectives>& obj, Rng& rng) {
  const int n = static_cast<int>(pop.size());
  const std::vector<int> rank = pareto_ranks(obj);
  const std::vector<double> crowd = crowding(obj, rank);
  auto better = [&](int a, int b) {
    if (rank[a] != rank[b]) return rank[a] < rank[b];
    if (crowd[a] != crowd[b]) return crowd[a] > crowd[b];
    return a < b;
  };
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), better);
  std::vector<Genome> next;
  const int elites = static_cast<int>(std::lround(opt.elite * n));
  for (int i = 0; i < elites && i < n; ++i) next.push_back(pop[order[i]]);
  auto tournament = [&] {
    int best = uniform_int(rng, n);
    for (int t = 1; t < opt.tournament; ++t) {
      const int c = uniform_int(rng, n);
      if (better(c, best)) best = c;
    }
    return best;
  };
  while (static_cast<int>(next.size()) < opt.population) {
    Genome child = pop[tournament()];
    if (uniform01(rng) < opt.crossover) child = crossover(child, pop[tournament()], rng);
    if (uniform01(rng) < opt.mutation) child = mutate(child, prob.space, prob.palette, rng);
    next.push_back(std::move(child));
  }
  return next;
}

std::string options_key(const SearchOptions& o) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "pop=%d gen=%d restarts=%d elite=%.17g cx=%.17g mut=%.17g init=%.17g tour=%d", o.population,
                o.generations, o.restarts, o.elite, o.crossover, o.mutation, o.init_crossover, o.tournament);
  return buf;
}

}  // namespace

bool EvalCache::find(const std::string& key, Objectives* out) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto it = map_.find(key);
  if (it == map_.end()) return false;
  *out = it->second;
  return true;
}

void EvalCache::put(const std::string& key, const Objectives& o) {
  std::lock_guard<std::mutex> lock(mu_);
  map_.emplace(key, o);
}

std::vector<double> crowding(const std::vector<Objectives>& pts, const std::vector<int>& ranks) {
  const int n = static_cast<int>(pts.size());
  std::vector<double> d(n, 0.0);
  const int max_rank = n ? *std::max_element(ranks.begin(), ranks.end()) : -1;
  for (int r = 0; r <= max_rank; ++r) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (ranks[i] == r) idx.push_back(i);
    for (int obj = 0; obj < 2; ++obj) {
      auto val = [&](int i) { return obj == 0 ? pts[i].time : pts[i].error; };
      std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return val(a) < val(b); });
      const double range = val(idx.back()) - val(idx.front());
      d[idx.front()] = d[idx.back()] = std::numeric_limits<double>::infinity();
      if (!(range > 0) || !std::isfinite(range)) continue;
      for (std::size_t k = 1; k + 1 < idx.size(); ++k)
        d[idx[k]] += (val(idx[k + 1]) - val(idx[k - 1])) / range;
    }
  }
  return d;
}

std::vector<Point> merge_fronts(const std::vector<std::vector<Point>>& fronts) {
  std::vector<Point> all;
  for (const auto& f : fronts) all.insert(all.end(), f.begin(), f.end());
  std::vector<Objectives> pts;
  for (const Point& p : all) pts.push_back(p.obj);
  std::vector<Point> out;
  for (int i : pareto_front(pts)) out.push_back(all[i]);
  return out;
}

RestartResult run_restart(const Problem& prob, const SearchOptions& opt, int restart, EvalCache& cache) {
  const auto t0 = std::chrono::steady_clock::now();
  const int threads = opt.threads > 0 ? opt.threads : std::max(1u, std::thread::hardware_concurrency());
  RestartResult res;
  Checkpoint ck;
  ck.problem_key = prob.key;
  ck.options_key = options_key(opt);
  ck.seed = opt.seed;
  ck.restart = restart;
  const std::string path =
      opt.checkpoint_dir.empty() ? "" : opt.checkpoint_dir + "/restart_" + std::to_string(restart) + ".json";
  Rng rng(mix64(opt.seed ^ mix64(static_cast<std::uint64_t>(restart) + 1)));
  std::vector<Genome> pop;
  std::vector<Objectives> obj;
  int gen = 0;
  Checkpoint saved;
  if (!path.empty() && load_checkpoint(path, ck, prob.palette, &saved)) {
    if (saved.complete) {
      res.front = saved.front;
      res.complete = true;
      if (opt.log) opt.log("restart " + std::to_string(restart) + ": complete in checkpoint " + path);
      return res;
    }
    rng = saved.rng;
    pop = saved.population;
    obj = saved.objectives;
    res.front = saved.front;
    gen = saved.generation;
    if (opt.log)
      opt.log("restart " + std::to_string(restart) + ": resuming after generation " + std::to_string(gen));
  } else {
    pop = initial_population(prob, opt, rng);
    obj = evaluate_all(prob, pop, threads, cache, &res.evaluations);
    res.front = update_front({}, pop, obj);
  }
  int bred = 0;
  auto report = [&] {
    double best = std::numeric_limits<double>::infinity();
    for (const Point& p : res.front) best = std::min(best, p.obj.error);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char line[200];
    std::snprintf(line, sizeof line, "restart %d gen %2d: best error %.5f, front %zu, evaluations %d, %.1f s",
                  restart, gen, best, res.front.size(), res.evaluations, s);
    if (opt.log) opt.log(line);
    if (!path.empty()) {
      ck.generation = gen;
      ck.rng = rng;
      ck.population = pop;
      ck.objectives = obj;
      ck.front = res.front;
      ck.complete = gen >= opt.generations;
      save_checkpoint(path, ck, prob.palette);
    }
  };
  if (gen == 0) report();
  while (gen < opt.generations) {
    if (opt.stop_after >= 0 && bred >= opt.stop_after) return res;  // "interrupted": complete = false
    pop = breed(prob, opt, pop, obj, rng);
    obj = evaluate_all(prob, pop, threads, cache, &res.evaluations);
    res.front = update_front(std::move(res.front), pop, obj);
    ++gen;
    ++bred;
    report();
  }
  res.complete = true;
  return res;
}

RestartResult search(const Problem& prob, const SearchOptions& opt) {
  EvalCache cache;
  RestartResult all;
  all.complete = true;
  std::vector<std::vector<Point>> fronts;
  for (int r = 0; r < opt.restarts; ++r) {
    RestartResult one = run_restart(prob, opt, r, cache);
    all.evaluations += one.evaluations;
    all.complete = all.complete && one.complete;
    fronts.push_back(std::move(one.front));
    if (!all.complete) break;
  }
  all.front = merge_fronts(fronts);
  return all;
}

}  // namespace bl::tuner
