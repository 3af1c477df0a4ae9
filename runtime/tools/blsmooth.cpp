// blsmooth: convert a GLSL pattern (or a scene, with its parallax and lighting) into the smoothed
// function, as self-contained GLSL or C++, without rendering.
//
//   blsmooth scenes/glsl/circles.glsl --rules gaussian --out circles_smooth.glsl
//   blsmooth scenes/glsl/stripes.json --out stripes_smooth.hpp
//   blsmooth scenes/glsl/stripes.json --schedule out/tune/stripes/front.csv:front02 --out s.glsl
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "compiler/schedule_csv.hpp"
#include "glsl/prelude.hpp"
#include "glsl/shader.hpp"
#include "scene/scene.hpp"

using namespace bl;

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// What is smoothed: the traced graph and a line naming it for the banner.
struct Source {
  ir::Graph graph;
  std::string label;
};

Source load(const std::string& input) {
  if (ends_with(input, ".json")) {
    const scene::Scene s = scene::load_scene(input);
    return {shaders::trace(s.shader_def(), s.effects()), "scene " + s.name + " (" + s.shader + ")"};
  }
  if (ends_with(input, ".glsl")) {
    const auto def = glsl::load_shader(input);
    shaders::Effects fx;
    fx.animated = true;  // the pattern alone: time stays an input when the pattern reads it
    return {shaders::trace(*def, fx), "GLSL pattern " + input};
  }
  throw std::invalid_argument(input + ": expected a .glsl pattern or a .json scene");
}

// Writes via a temporary file and a rename: an error leaves no half-written output.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(path + ": cannot write");
    out << text;
    if (!out) throw std::runtime_error(path + ": write failed");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blsmooth: a GLSL pattern or a scene -> smoothed GLSL or C++ (no rendering)"};
  std::string input, rules_text = "gaussian", schedule_spec, out_path, name = "shade";
  bool print_prelude = false;
  app.add_option("input", input, "pattern (.glsl, defines vec3 shade(vec2 uv, float time)) or scene (.json)");
  auto* rules_opt = app.add_option(
      "--rules", rules_text, "rule for every node (none, dorn, gaussian, mc8, box, tent, rule1:box, ...)");
  app.add_option("--schedule", schedule_spec,
                 "a tuned schedule instead of --rules: FRONT.csv:LABEL from bltune (give the scene file "
                 "it was tuned on as input)")
      ->excludes(rules_opt);
  app.add_option("--out", out_path, "output: .glsl (GLSL function) or .hpp/.h (C++ header)");
  app.add_option("--name", name, "name of the emitted function");
  app.add_flag("--prelude", print_prelude,
               "print the GLSL prelude (saturate, triangle, square, pow2..pow8, inv, inv2) and exit");
  CLI11_PARSE(app, argc, argv);
  if (print_prelude) {
    std::fputs(glsl::prelude().c_str(), stdout);
    return 0;
  }
  try {
    if (input.empty() || out_path.empty())
      throw std::invalid_argument("give an input file and --out (see --help)");
    const bool to_glsl = ends_with(out_path, ".glsl");
    if (!to_glsl && !ends_with(out_path, ".hpp") && !ends_with(out_path, ".h"))
      throw std::invalid_argument(out_path + ": the output must end in .glsl, .hpp or .h");
    const Source src = load(input);
    // One rule for every node (--rules), or a tuned front point (--schedule CSV:LABEL, which must
    // have been tuned on this graph: the scene file, not the bare pattern, when the scene adds
    // parallax, lighting or a fixed time).
    const compiler::ChosenSchedule chosen = compiler::choose_schedule(src.graph, rules_text, schedule_spec);
    const compiler::Program prog = compiler::lower(src.graph, chosen.schedule);
    const std::string banner =
        src.label + " / " + (schedule_spec.empty() ? "rules " : "schedule ") + chosen.what;
    write_atomically(
        out_path, to_glsl ? compiler::emit_glsl(prog, name, banner) : compiler::emit_cpp(prog, name, banner));
    std::string inputs, outputs;
    for (const auto& n : prog.input_names) inputs += (inputs.empty() ? "" : ", ") + n;
    for (const auto& n : prog.output_names) outputs += (outputs.empty() ? "" : ", ") + n;
    std::printf("%s: %d nodes, %zu instructions; inputs [%s], outputs [%s]%s\n", out_path.c_str(),
                src.graph.size(), prog.insts.size(), inputs.c_str(), outputs.c_str(),
                prog.uses_gradients() ? "; reads screen gradients" : "");
    for (const auto& note : prog.notes) std::printf("  note: %s\n", note.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blsmooth: %s\n", e.what());
    return 1;
  }
  return 0;
}
