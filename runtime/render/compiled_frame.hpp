// Frames through compiled code (jit::CompiledProgram) and the timings the reports quote: a program
// run over every pixel of a frame at the pixel centres (plain or smoothed), or n times per pixel at
// counter-based jittered positions (MSAA of the plain program), on exactly the inputs the evaluator
// gets (bind_inputs). Times are single-threaded: ns per pixel (all samples of a pixel) and ms per
// frame = ns x pixels.
#pragma once

#include <cstdint>
#include <functional>

#include "compiler/lir.hpp"
#include "image/image.hpp"
#include "jit/compiled_program.hpp"
#include "render/render.hpp"

namespace bl::render {

// Runs a program over a batch: a CompiledProgram's or an Evaluator's run.
using BatchRunner = std::function<void(const compiler::Batch&, const std::vector<float*>&)>;
BatchRunner compiled_runner(const jit::CompiledProgram& cp);
BatchRunner evaluator_runner(const compiler::Program& p);  // one Evaluator, not thread-safe

// The image of `run` (a 3-output program) with `samples` = 0: one evaluation at each pixel centre;
// otherwise `samples` per pixel at the offsets render_native(s, f, samples, seed) uses, averaged.
Image render_program(const scene::Scene& s, const Frame& f, const compiler::Program& p,
                     const BatchRunner& run, int samples = 0, std::uint64_t seed = 1);

struct FrameTiming {
  double ns_per_pixel = 0;  // minimum over trials, all samples of a pixel
  double ms_per_frame = 0;  // ns_per_pixel x pixels
  int trials = 0;
};

// Times `run` over the frame's inputs (as render_program feeds them; input tracing is not timed):
// a warm-up, then `trials` runs, the minimum kept (least disturbed by other load), each timed in
// the thread's CPU time (time spent descheduled does not count).
FrameTiming time_program(const scene::Scene& s, const Frame& f, const compiler::Program& p,
                         const BatchRunner& run, int samples = 0, int trials = 5, std::uint64_t seed = 1);

}  // namespace bl::render
