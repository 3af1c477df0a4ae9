// Timed loops and their registration; see timing.hpp.
#include "timing.hpp"

#include <map>

#include "accuracy.hpp"
#include "entry_view.hpp"
#include "inputs.hpp"

namespace blb {
namespace {

template <class T>
const std::vector<EntryView<T>>& views();
template <>
const std::vector<EntryView<double>>& views<double>() {
  return double_entries();
}
template <>
const std::vector<EntryView<float>>& views<float>() {
  return float_entries();
}

const std::vector<Input<double>>& inputs_for(const bl::registry::AtomicInfo* a) {
  static std::map<const bl::registry::AtomicInfo*, std::vector<Input<double>>> cache;
  auto it = cache.find(a);
  if (it == cache.end()) it = cache.emplace(a, make_inputs(*a)).first;
  return it->second;
}

template <class T>
const std::vector<Input<T>>& typed_inputs(const bl::registry::AtomicInfo* a);
template <>
const std::vector<Input<double>>& typed_inputs<double>(const bl::registry::AtomicInfo* a) {
  return inputs_for(a);
}
template <>
const std::vector<Input<float>>& typed_inputs<float>(const bl::registry::AtomicInfo* a) {
  static std::map<const bl::registry::AtomicInfo*, std::vector<Input<float>>> cache;
  auto it = cache.find(a);
  if (it == cache.end()) it = cache.emplace(a, to_float(inputs_for(a))).first;
  return it->second;
}

template <class T, class F>
void timed_loop(benchmark::State& st, const std::vector<Input<T>>& in, F f) {
  for (auto _ : st) {
    for (const Input<T>& p : in) {
      T r = f(p.x, p.sigma);
      benchmark::DoNotOptimize(r);
    }
  }
}

template <class T>
void run_benchmark(benchmark::State& st, const BenchId& id) {
  const EntryView<T>& v = views<T>()[id.entry];
  const std::vector<Input<T>>& in = typed_inputs<T>(v.entry->atomic);
  const double err = cached_error(id);  // before the timed region
  Rng rng{0xC0FFEEull + static_cast<unsigned>(id.entry)};
  switch (id.method) {
    case Method::Plain:
      timed_loop(st, in, [&](T x, T s) { return eval_plain(v, x, s); });
      break;
    case Method::Smoothed:
      timed_loop(st, in, [&](T x, T s) { return eval_smoothed(v, x, s); });
      break;
    case Method::MC4:
      timed_loop(st, in, [&](T x, T s) { return eval_mc(v, x, s, 4, rng); });
      break;
    case Method::MC16:
      timed_loop(st, in, [&](T x, T s) { return eval_mc(v, x, s, 16, rng); });
      break;
    case Method::MC64:
      timed_loop(st, in, [&](T x, T s) { return eval_mc(v, x, s, 64, rng); });
      break;
  }
  st.counters["per_call"] = benchmark::Counter(
      static_cast<double>(in.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (err == err) st.counters["rms_err"] = err;
}

}  // namespace

std::string BenchId::name() const {
  const std::string& entry_name =
      is_float ? float_entries()[entry].name : double_entries()[entry].name;
  return std::string(is_float ? "float/" : "") + entry_name + "/" + method_name(method);
}

std::vector<BenchId> all_benchmarks() {
  std::vector<BenchId> ids;
  const int n = static_cast<int>(double_entries().size());
  for (bool is_float : {false, true})
    for (int i = 0; i < n; ++i)
      for (Method m : kMethods) ids.push_back({is_float, i, m});
  return ids;
}

std::vector<benchmark::internal::Benchmark*> register_benchmarks(const std::vector<BenchId>& ids) {
  std::vector<benchmark::internal::Benchmark*> out;
  for (const BenchId& id : ids) {
    auto fn = [id](benchmark::State& st) {
      if (id.is_float)
        run_benchmark<float>(st, id);
      else
        run_benchmark<double>(st, id);
    };
    out.push_back(benchmark::RegisterBenchmark(id.name().c_str(), fn));
  }
  return out;
}

double cached_error(const BenchId& id) {
  static std::map<std::string, double> cache;
  const std::string key = id.name();
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const EntryView<double>& ref = double_entries()[id.entry];
  const std::vector<Input<double>>& in = inputs_for(ref.entry->atomic);
  const double e = id.is_float ? rms_error(float_entries()[id.entry], ref, in, id.method)
                               : rms_error(ref, ref, in, id.method);
  cache.emplace(key, e);
  return e;
}

}  // namespace blb
