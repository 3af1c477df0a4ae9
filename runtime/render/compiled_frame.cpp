#include "render/compiled_frame.hpp"

#include <algorithm>
#include <ctime>
#include <limits>
#include <memory>
#include <stdexcept>

#include "camera/plane_batch.hpp"
#include "render/frame.hpp"
#include "render/jitter.hpp"

namespace bl::render {

namespace {

// CPU time of the calling thread in ms: time the thread was not scheduled does not count, so a
// slow program's minimum is not inflated by other load (a wall-clock minimum over whole frames of
// a 50 ms program was preempted in every trial on a loaded machine, a 1 ms plain frame was not).
double thread_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

// The bound inputs of every pixel of a frame for sample k (k < 0: pixel centres).
struct SampleInputs {
  camera::PlaneBatch trace;
  InputStorage storage;
  compiler::Batch batch;
  std::vector<float> offsets;
};

void bind_sample(const scene::Scene& s, const Frame& f, const compiler::Program& p, int k, std::uint64_t seed,
                 SampleInputs& in) {
  const float* offsets = nullptr;
  if (k >= 0) {
    const std::uint64_t key = frame_key(seed, f.view, f.time);
    const std::size_t n = static_cast<std::size_t>(s.width) * s.height;
    in.offsets.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const Offset o = gaussian_jitter(key, i, static_cast<std::uint32_t>(k), s.sigma_px);
      in.offsets[2 * i] = static_cast<float>(o.x);
      in.offsets[2 * i + 1] = static_cast<float>(o.y);
    }
    offsets = in.offsets.data();
  }
  camera::trace_plane(make_camera(s, f.view), footprint_options(s), in.trace, {}, offsets);
  in.batch = bind_inputs(p, in.trace, s, f, in.storage);
}

}  // namespace

BatchRunner compiled_runner(const jit::CompiledProgram& cp) {
  return [&cp](const compiler::Batch& b, const std::vector<float*>& out) { cp.run(b, out); };
}

BatchRunner evaluator_runner(const compiler::Program& p) {
  auto ev = std::make_shared<compiler::Evaluator>(p);
  return [ev](const compiler::Batch& b, const std::vector<float*>& out) { ev->run(b, out); };
}

Image render_program(const scene::Scene& s, const Frame& f, const compiler::Program& p,
                     const BatchRunner& run, int samples, std::uint64_t seed) {
  if (p.outputs.size() != 3)
    throw std::invalid_argument("render_program: the program has " + std::to_string(p.outputs.size()) +
                                " outputs, a colour needs 3");
  const int n = s.width * s.height, count = samples > 0 ? samples : 1;
  std::vector<double> acc(3 * static_cast<std::size_t>(n), 0.0);
  std::vector<std::vector<float>> out(3, std::vector<float>(n));
  SampleInputs in;
  for (int k = 0; k < count; ++k) {
    bind_sample(s, f, p, samples > 0 ? k : -1, seed, in);
    run(in.batch, {out[0].data(), out[1].data(), out[2].data()});
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) acc[3 * i + c] += covered(in.trace, i, out[c][i], s.background[c]);
  }
  Image img(s.width, s.height);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      img.at(i % s.width, i / s.width, c) = static_cast<float>(acc[3 * i + c] / count);
  return img;
}

FrameTiming time_program(const scene::Scene& s, const Frame& f, const compiler::Program& p,
                         const BatchRunner& run, int samples, int trials, std::uint64_t seed) {
  const int n = s.width * s.height, count = samples > 0 ? samples : 1;
  std::vector<std::vector<float>> store(p.outputs.size(), std::vector<float>(n));
  std::vector<float*> out;
  for (auto& o : store) out.push_back(o.data());
  // Per sample: bind its inputs, warm up, keep the fastest of `trials`; the frame is their sum.
  double total_ms = 0;
  SampleInputs in;
  for (int k = 0; k < count; ++k) {
    bind_sample(s, f, p, samples > 0 ? k : -1, seed, in);
    run(in.batch, out);
    double best = std::numeric_limits<double>::infinity();
    for (int t = 0; t < trials; ++t) {
      const double t0 = thread_ms();
      run(in.batch, out);
      best = std::min(best, thread_ms() - t0);
    }
    total_ms += best;
  }
  FrameTiming r;
  r.trials = trials;
  r.ms_per_frame = total_ms;
  r.ns_per_pixel = total_ms * 1e6 / n;
  return r;
}

}  // namespace bl::render
