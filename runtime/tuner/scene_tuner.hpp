// One scene as a tuning problem: the traced graph, the search space and palette, the cost model and
// the pixel sample; evaluation of schedules (search error on the sample, final error on full images)
// and the Nelder-Mead refinement of sd scale factors (Yang & Barnes 4.7).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "tuner/cost_model.hpp"
#include "tuner/genetic.hpp"
#include "tuner/pixel_sample.hpp"

namespace bl::tuner {

struct TuneOptions {
  SearchOptions search;
  std::vector<std::string> rules = Palette::default_names();
  int sample_pixels = 2000;  // search error: this many pixels over all frames
  std::uint64_t sample_seed = 7;
  std::string cache_dir = "build/truth_cache";
  bool estimate_rho = true;  // Appendix B.1 constants for "gaussian:rho=const"
  int nm_evals = 60;         // Nelder-Mead evaluations per front point (0: no refinement)
  int nm_groups = 12;        // at most this many sd factors (adjacent smoothed nodes share one)
};

class SceneTuner {
 public:
  SceneTuner(const scene::Scene& s, const CostModel& cm, const TuneOptions& opt);

  const scene::Scene& scene() const { return scene_; }
  const ir::Graph& graph() const { return graph_; }
  const Problem& problem() const { return problem_; }
  const CostModel& cost_model() const { return cm_; }
  const TuneOptions& options() const { return opt_; }

  // Lowered program, or nullptr when lowering needs a function the generated table lacks (a rule
  // not available yet for some node: "infeasible"). Other lowering errors propagate.
  std::unique_ptr<compiler::Program> lower(const compiler::Schedule& s) const;
  // The plain schedule (rule none on every node) and its program: MSAA-n is n of it, and speed-ups are
  // read against it.
  compiler::Schedule plain_schedule() const;
  std::unique_ptr<compiler::Program> lower_plain() const;
  // Model time and sample error. Infeasible: both +inf when lowering lacks a function; error +inf
  // when any sampled pixel has a NaN or infinite channel (counted in nonfinite_rejections()).
  Objectives evaluate(const compiler::Schedule& s) const;
  // RMS (display_error) and NaN/out-of-range pixel counts over every pixel of every frame.
  PixelSample::Score full_score(const compiler::Program& p) const;
  double full_error(const compiler::Program& p) const { return full_score(p).rms; }
  const PixelSample& search_sample() const { return *sample_; }  // the search error's pixels
  // Every pixel of every frame (what full_score measures on), built on first use.
  const PixelSample& full_sample() const;
  // The cost model with the argument profiles (band_share, joint_share) taken over `sample` instead
  // of the scene's pixel sample: a program's price on part of the image (a footprint LOD's near or
  // far pixels, whose arguments and sigmas differ: fire_none's far pixels cost its accurate program
  // ~1.5x its all-pixel average).
  CostModel cost_model_over(const PixelSample& sample) const;
  // Evaluations (distinct or not) that were infeasible because of NaN/inf on the sampled pixels.
  long nonfinite_rejections() const { return nonfinite_.load(); }
  const ValueRange& value_range() const { return sample_->range(); }
  compiler::Schedule schedule(const Genome& x) const;

  // Nelder-Mead (NLopt LN_NELDERMEAD) over log2 sd factors of the smoothed nodes, grouped into at
  // most nm_groups runs of adjacent genes, bounded to [1/4, 4] and nm_evals evaluations. Returns the
  // better of the refined and the given schedule (by sample error) and its objectives.
  compiler::Schedule refine_sigma(const compiler::Schedule& s, Objectives* obj) const;

 private:
  scene::Scene scene_;
  ir::Graph graph_;
  CostModel cm_;
  TuneOptions opt_;
  std::unique_ptr<PixelSample> sample_;
  // The plain and all-Gaussian programs (nullptr where lowering lacks a function): cost_model_over's
  // argument profiles (band_share, joint_share) come from them.
  std::unique_ptr<compiler::Program> profile_plain_, profile_gaussian_;
  mutable std::once_flag full_once_;
  mutable std::unique_ptr<PixelSample> full_;
  mutable std::atomic<long> nonfinite_{0};
  Problem problem_;
};

}  // namespace bl::tuner
