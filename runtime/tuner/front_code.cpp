#include "tuner/front_code.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "compiler/emit.hpp"
#include "compiler/schedule_text.hpp"
#include "compiler/supersample.hpp"

namespace bl::tuner {

int write_front_code(const SceneTuner& t, const SceneResult& r, const std::string& dir) {
  const std::string out = dir + "/front";
  std::filesystem::create_directories(out);
  int n = 0;
  for (const Measured& m : r.front) {
    const compiler::Schedule s = compiler::parse_schedule(t.graph(), m.schedule, "front point " + m.label);
    const auto p = t.lower(s);
    if (!p) throw std::logic_error("write_front_code: front point " + m.label + " no longer lowers");
    char measured[256];
    std::snprintf(
        measured, sizeof measured,
        "measured: RMS %.5f (display space, every pixel of %d frame(s) vs ground truth), PSNR %.2f dB, "
        "cost model %.1f ns/pixel",
        m.error, r.frames, m.psnr, m.model_ns);
    const std::string banner = "bltune front point " + m.label + " of scene " + t.scene().name + " (shader " +
                               t.scene().shader + ", graph " + r.graph_hash + ")\n// " + measured +
                               "\n// schedule (node:rule; blrender SCENE --schedule front.csv:" + m.label +
                               " renders it): " + m.schedule;
    std::ofstream(out + "/" + m.label + ".glsl") << compiler::emit_glsl(*p, "shade", banner);
    std::ofstream(out + "/" + m.label + ".hpp") << compiler::emit_cpp(*p, "shade", banner);
    ++n;
  }
  if (r.lod) {  // the footprint-LOD pair as one function of each language
    auto program = [&](const std::string& text, const std::string& label, int samples) {
      auto p = t.lower(compiler::parse_schedule(t.graph(), text, "footprint LOD point " + label));
      if (!p) throw std::logic_error("write_front_code: footprint LOD point " + label + " no longer lowers");
      return compiler::stratified_samples(*p, samples, t.scene().sigma_px);
    };
    const compiler::Program near = program(r.lod->near_schedule, r.lod->near, r.lod->near_samples),
                            far = program(r.lod->far_schedule, r.lod->far, r.lod->far_samples);
    char banner[320];
    std::snprintf(
        banner, sizeof banner,
        "bltune footprint LOD of scene %s: %s below footprint %.6g, %s above\n// measured: RMS %.5f "
        "(every pixel of %d frame(s) vs ground truth), cost model %.1f ns/pixel",
        t.scene().name.c_str(), r.lod->near.c_str(), r.lod->limit, r.lod->far.c_str(), r.lod->error, r.frames,
        r.lod->model_ns);
    std::ofstream(out + "/lod.hpp") << compiler::emit_cpp_lod(near, far, r.lod->limit, "shade", banner);
    std::ofstream(out + "/lod.glsl") << compiler::emit_glsl_lod(near, far, r.lod->limit, "shade", banner);
  }
  return n;
}

}  // namespace bl::tuner
