#include "tuner/pixel_sample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include "camera/plane_batch.hpp"
#include "compiler/evaluator.hpp"
#include "image/display.hpp"
#include "render/frame.hpp"
#include "render/render.hpp"
#include "render/value_range.hpp"

namespace bl::tuner {

PixelSample::PixelSample(const scene::Scene& s, const std::string& cache_dir, int pixels, std::uint64_t seed)
    : PixelSample(s, shaders::trace(s.shader_def(), s.effects()), cache_dir, pixels, seed) {}

PixelSample::PixelSample(const scene::Scene& s, const ir::Graph& g, const std::string& cache_dir, int pixels,
                         std::uint64_t seed)
    : scene_(s) {
  const std::vector<render::Frame> fr = render::frames(s);
  const int all = s.width * s.height;
  const int per_frame =
      pixels <= 0 ? all
                  : std::min(all, (pixels + static_cast<int>(fr.size()) - 1) / static_cast<int>(fr.size()));
  std::mt19937_64 rng(seed);
  std::vector<Image> truths;
  for (const render::Frame& f : fr) truths.push_back(render::render_truth(s, f, cache_dir));
  range_ = render::valid_range(s, g, truths);
  for (std::size_t fi = 0; fi < fr.size(); ++fi) {
    const render::Frame& f = fr[fi];
    const Image& truth = truths[fi];
    camera::PlaneBatch b;
    camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), b);
    // A partial Fisher-Yates shuffle: the first per_frame entries are the sample (sorted for locality).
    std::vector<int> idx(all);
    std::iota(idx.begin(), idx.end(), 0);
    for (int i = 0; i < per_frame && per_frame < all; ++i)
      std::swap(idx[i], idx[i + static_cast<int>(rng() % static_cast<std::uint64_t>(all - i))]);
    idx.resize(per_frame);
    std::sort(idx.begin(), idx.end());
    FrameData d;
    d.time = f.time;
    std::vector<int> hit;
    for (int i : idx) {
      const int x = i % s.width, y = i / s.width;
      if (!b.hit[i]) {
        for (int c = 0; c < 3; ++c) {
          const double e = display_error(static_cast<float>(s.background[c]), truth.at(x, y, c));
          d.miss_sq += e * e;
        }
        continue;
      }
      hit.push_back(i);
      for (int c = 0; c < 3; ++c) d.truth.push_back(truth.at(x, y, c));
    }
    d.n = static_cast<int>(hit.size());
    d.hits = b.gather(hit);
    total_ += per_frame;
    frames_.push_back(std::move(d));
  }
}

double PixelSample::error(const compiler::Program& p) const {
  const Score s = score(p);
  return s.counts.nonfinite > 0 ? std::numeric_limits<double>::infinity() : s.rms;
}

PixelSample::Score PixelSample::score(const compiler::Program& p) const {
  Score score;
  double sum = miss_sq();
  for (double e : hit_sq(p, &score.counts)) sum += e;
  score.rms = total_ > 0 ? std::sqrt(sum / (3.0 * total_)) : 0.0;
  return score;
}

std::vector<double> PixelSample::pixel_sq(const compiler::Program& p) const {
  PixelCounts unused;
  return hit_sq(p, &unused);
}

double PixelSample::miss_sq() const {
  double sum = 0;
  for (const FrameData& d : frames_) sum += d.miss_sq;
  return sum;
}

namespace {

// Hit pixel i's footprint: what footprints() lists and subset() splits on.
float footprint(const camera::PlaneBatch& b, int i) {
  return std::max(b.sigma_u[i], b.sigma_v[i]);
}

}  // namespace

std::vector<float> PixelSample::footprints() const {
  std::vector<float> fp;
  for (const FrameData& d : frames_)
    for (int i = 0; i < d.n; ++i) fp.push_back(footprint(d.hits, i));
  return fp;
}

PixelSample PixelSample::subset(float limit, bool below) const {
  PixelSample out;
  out.scene_ = scene_;
  out.range_ = range_;
  for (const FrameData& d : frames_) {
    FrameData e;
    e.time = d.time;
    std::vector<int> keep;
    for (int i = 0; i < d.n; ++i)
      if ((footprint(d.hits, i) < limit) == below) {
        keep.push_back(i);
        for (int c = 0; c < 3; ++c) e.truth.push_back(d.truth[3 * i + c]);
      }
    e.n = static_cast<int>(keep.size());
    e.hits = d.hits.gather(keep);
    out.total_ += e.n;
    out.frames_.push_back(std::move(e));
  }
  return out;
}

std::vector<double> PixelSample::hit_sq(const compiler::Program& p, PixelCounts* counts) const {
  if (p.outputs.size() != 3)
    throw std::invalid_argument("PixelSample: the program has " + std::to_string(p.outputs.size()) +
                                " outputs, a colour needs 3");
  compiler::Evaluator ev(p);
  std::vector<double> sq;
  for (std::size_t fi = 0; fi < frames_.size(); ++fi) {
    const FrameData& d = frames_[fi];
    if (d.n == 0) continue;
    render::Frame f;
    f.time = d.time;
    render::InputStorage storage;
    const compiler::Batch batch = render::bind_inputs(p, d.hits, scene_, f, storage);
    std::vector<std::vector<float>> out(3, std::vector<float>(d.n));
    ev.run(batch, {out[0].data(), out[1].data(), out[2].data()});
    for (int i = 0; i < d.n; ++i) {
      const float rgb[3] = {out[0][i], out[1][i], out[2][i]};
      *counts += check_pixel(rgb, range_);
      double e2 = 0;
      // The shade on the plane's share of the pixel (the horizon), as render_smoothed.
      for (int c = 0; c < 3; ++c) {
        const float shown = static_cast<float>(render::covered(d.hits, i, rgb[c], scene_.background[c]));
        const double e = display_error(shown, d.truth[3 * i + c]);
        e2 += e * e;
      }
      sq.push_back(e2);
    }
  }
  return sq;
}

std::vector<std::vector<float>> PixelSample::outputs(const compiler::Program& p) const {
  compiler::Evaluator ev(p);
  std::vector<std::vector<float>> all(p.outputs.size());
  for (const FrameData& d : frames_) {
    if (d.n == 0) continue;
    render::Frame f;
    f.time = d.time;
    render::InputStorage storage;
    const compiler::Batch batch = render::bind_inputs(p, d.hits, scene_, f, storage);
    std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(d.n));
    std::vector<float*> ptr;
    for (auto& o : out) ptr.push_back(o.data());
    ev.run(batch, ptr);
    for (std::size_t k = 0; k < out.size(); ++k) all[k].insert(all[k].end(), out[k].begin(), out[k].end());
  }
  return all;
}

}  // namespace bl::tuner
