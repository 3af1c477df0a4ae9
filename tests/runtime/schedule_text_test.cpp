// Schedules as text (compiler/schedule_text) and loaded from a bltune front.csv by label
// (compiler/schedule_csv): round trips and the errors a user can meet.
#include "compiler/schedule_text.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "compiler/schedule_csv.hpp"
#include "scene/scene.hpp"
#include "shaders/shader.hpp"

using namespace bl;

namespace {

ir::Graph graph_of(const std::string& scene) {
  const scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/suite/") + scene + ".json");
  return shaders::trace(shaders::find_shader(s.shader), s.effects());
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

#define EXPECT_HAS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

// A mixed schedule: every rule kind somewhere, with sd scales that are not round in binary.
compiler::Schedule mixed(const ir::Graph& g) {
  const std::vector<std::string> texts{
      "none",       "dorn@0.54", "gaussian", "gaussian:rho=grad@1.28",  "gaussian:rho=0.30000000000000004",
      "mc2",        "mc32@0.25", "box",      "tent@0.3333333333333333", "rule1:tent",
      "rule2@0.54", "rule3"};
  compiler::Schedule s(g.size());
  int k = 0;
  for (int n : g.depth_first_order())
    if (g.node(n).op != ir::Op::Const) s[n] = rules::parse_rule(texts[k++ % texts.size()]);
  return s;
}

std::string temp_file(const std::string& name, const std::string& text) {
  const auto d = std::filesystem::temp_directory_path() / "bl_schedule_text_test";
  std::filesystem::create_directories(d);
  const std::string p = (d / name).string();
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST(ScheduleText, RoundTripsOnEverySuitePattern) {
  for (const char* scene : {"checkerboard_none", "bricks_bumps", "circles_ripples", "color_circles_none",
                            "fire_none", "quadratic_sine_none", "zigzag_bumps"}) {
    const ir::Graph g = graph_of(scene);
    const compiler::Schedule s = mixed(g);
    const std::string text = compiler::schedule_to_text(g, s);
    EXPECT_TRUE(compiler::parse_schedule(g, text) == s) << scene;
    // A uniform schedule also sets constants: nothing is lost either.
    const compiler::Schedule u = compiler::uniform_schedule(g, rules::parse_rule("mc4@1.5"));
    EXPECT_TRUE(compiler::parse_schedule(g, compiler::schedule_to_text(g, u)) == u) << scene;
  }
}

TEST(ScheduleText, ReadsHandWrittenTextWithDefaults) {
  const ir::Graph g = graph_of("checkerboard_none");
  int a = -1, b = -1;
  for (int n : g.depth_first_order())
    if (g.node(n).op != ir::Op::Const) (a < 0 ? a : b) = n;
  const compiler::Schedule s =
      compiler::parse_schedule(g, "  " + std::to_string(a) + ":mc2   " + std::to_string(b) + ":rule2@0.54\n");
  for (int n = 0; n < g.size(); ++n) {
    const std::string want = n == a ? "mc2" : n == b ? "rule2@0.54" : "none";
    EXPECT_EQ(rules::to_string(s[n]), want) << "node " << n;
  }
}

TEST(ScheduleText, ErrorsNameTheEntryAndTheProblem) {
  const ir::Graph g = graph_of("checkerboard_none");
  const std::string big = std::to_string(g.size());
  std::string e = error_of([&] { compiler::parse_schedule(g, "1:none " + big + ":dorn", "front.csv x"); });
  EXPECT_HAS(e, "front.csv x");
  EXPECT_HAS(e, "entry 2 '" + big + ":dorn'");
  EXPECT_HAS(e, "not in the graph (" + big + " nodes)");
  e = error_of([&] { compiler::parse_schedule(g, "1:gaussain"); });
  EXPECT_HAS(e, "entry 1 '1:gaussain'");
  EXPECT_HAS(e, "unknown rule 'gaussain'");
  e = error_of([&] { compiler::parse_schedule(g, "1:dorn 1:box"); });
  EXPECT_HAS(e, "listed twice");
  EXPECT_HAS(error_of([&] { compiler::parse_schedule(g, "1:none gaussian"); }), "expected node:rule");
  EXPECT_HAS(error_of([&] { compiler::parse_schedule(g, "-1:none"); }), "'-1' is not a node index");
  EXPECT_HAS(error_of([&] { compiler::parse_schedule(g, "x1:none"); }), "'x1' is not a node index");
  EXPECT_HAS(error_of([&] { compiler::parse_schedule(g, "1:mc3"); }), "2, 4, 8, 16 or 32");
  EXPECT_HAS(error_of([&] { compiler::parse_schedule(g, "  "); }), "empty");
}

TEST(ScheduleCsv, LoadsByLabelAndRefusesAnotherGraph) {
  const ir::Graph g = graph_of("checkerboard_none"), other = graph_of("bricks_none");
  ASSERT_NE(g.hash(), other.hash());
  const compiler::Schedule s = mixed(g);
  const std::string hash = compiler::graph_hash_text(g);
  const std::string header = "kind,label,model_ns_per_pixel,rms_display,rule_mix,schedule,graph_hash\n";
  const std::string csv =
      temp_file("front.csv", header + "front,front00,10,0.1,\"none 50%, mc 50%\",\"" +
                                 compiler::schedule_to_text(g, s) + "\"," + hash +
                                 "\nbaseline,msaa16,99,0.05,\"none 100%\",\"plain x 16 jittered samples\"," +
                                 hash + "\nbaseline,dorn,12,0.2,\"dorn 100%\",\"all dorn\"," + hash + "\n");
  const compiler::LoadedSchedule l = compiler::load_schedule(csv + ":front00", g);
  EXPECT_TRUE(l.schedule == s);
  EXPECT_EQ(l.label, "front00");
  EXPECT_TRUE(compiler::load_schedule(csv + ":dorn", g).schedule ==
              compiler::uniform_schedule(g, rules::parse_rule("dorn")));

  std::string e = error_of([&] { compiler::load_schedule(csv + ":front07", g); });
  EXPECT_HAS(e, csv);
  EXPECT_HAS(e, "no row labelled 'front07'");
  EXPECT_HAS(e, "known labels: front00, msaa16, dorn");
  e = error_of([&] { compiler::load_schedule(csv + ":front00", other); });
  EXPECT_HAS(e, csv + ":2 (front00)");
  EXPECT_HAS(e, "tuned for graph " + hash);
  EXPECT_HAS(e, compiler::graph_hash_text(other));
  EXPECT_HAS(error_of([&] { compiler::load_schedule(csv + ":msaa16", g); }), "MSAA baseline");
  // Files from stop 35 on name the baselines' sample counts in columns: those decide, not the text.
  const std::string counted = temp_file(
      "counted.csv", "kind,label,schedule,graph_hash,msaa,supersample\nbaseline,ss8,\"eight stratified\"," +
                         hash + ",0,8\nbaseline,msaa4,\"four\"," + hash +
                         ",4,0\nbaseline,dorn,\"all dorn\"," + hash + ",0,0\n");
  EXPECT_HAS(error_of([&] { compiler::load_schedule(counted + ":ss8", g); }), "--supersample N");
  EXPECT_HAS(error_of([&] { compiler::load_schedule(counted + ":msaa4", g); }), "MSAA baseline");
  EXPECT_TRUE(compiler::load_schedule(counted + ":dorn", g).schedule ==
              compiler::uniform_schedule(g, rules::parse_rule("dorn")));
  EXPECT_HAS(error_of([&] { compiler::load_schedule(csv, g); }), "expected FILE.csv:LABEL");
  EXPECT_HAS(error_of([&] { compiler::load_schedule("/nonexistent/front.csv:front00", g); }),
             "/nonexistent/front.csv: cannot open");
  const std::string old = temp_file("old.csv", "kind,label,schedule\nfront,front00,\"1:none\"\n");
  EXPECT_HAS(error_of([&] { compiler::load_schedule(old + ":front00", g); }), "no 'graph_hash' column");
  const std::string bad = temp_file(
      "bad.csv", header + "front,front00,10,0.1,\"none 100%\",\"1:none 2:gaussain\"," + hash + "\n");
  e = error_of([&] { compiler::load_schedule(bad + ":front00", g); });
  EXPECT_HAS(e, bad + ":2 (front00): entry 2 '2:gaussain'");
}
