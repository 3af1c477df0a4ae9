// blgpu_time: times a blgpu_pack pack on this machine's OpenGL driver (EGL device platform on a
// GPU, llvmpipe elsewhere) and writes the per-program times and the report. Links only bl_gl and
// the report, so it runs where our other dependencies are not installed (docs/gpu_timing.md).
//
//   blgpu_time PACK --out OUT                       one process: compile and time everything
//   blgpu_time PACK --out OUT --shard K/N           (N processes) compile program i with i % N == K,
//                                                   then time them holding OUT/.timing.lock, so
//                                                   compiles run in parallel and timings never overlap
//   blgpu_time PACK --out OUT --merge               join OUT/shard_*.json into the report
//   blgpu_time --compare A.json B.json [--names a,b] two runs' gpu_times.json, scene by scene
//
// Each program is also drawn once per frame of its scene at the scene's size (OUT/images, raw RGB
// floats); the merge measures every image against the scene's GPU truth (the pack's "truth"
// program, drawn but never timed) in display space, as bltune measures against the CPU truth, and
// counts non-finite and out-of-range pixels: the errors on this driver, beside bltune's.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gl/egl_runner.hpp"
#include "gpu_timing/gpu_report.hpp"
#include "image/metrics.hpp"
#include "image/pixel_check.hpp"

using namespace bl;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error(p.string() + ": cannot read");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

void write_text(const fs::path& p, const std::string& text) {
  {
    std::ofstream out(p.string() + ".tmp");
    out << text;
    if (!out) throw std::runtime_error(p.string() + ": write failed");
  }
  fs::rename(p.string() + ".tmp", p);
}

// `uniforms`: a manifest uniform list (a scene's first frame, or one of its "frames").
std::vector<gl::Uniform> uniform_list(const json& uniforms) {
  std::vector<gl::Uniform> u;
  for (const json& j : uniforms) {
    const std::string name = j.at("name");
    if (j.contains("float")) {
      u.push_back({name, j["float"].get<float>()});
    } else if (j.contains("int")) {
      u.push_back({name, j["int"].get<int>()});
    } else {
      const auto v = j.at("vec").get<std::vector<float>>();
      if (v.size() == 2)
        u.push_back({name, gl::Vec2{v[0], v[1]}});
      else if (v.size() == 3)
        u.push_back({name, gl::Vec3{v[0], v[1], v[2]}});
      else if (v.size() == 4)
        u.push_back({name, gl::Vec4{v[0], v[1], v[2], v[3]}});
      else
        throw std::invalid_argument("manifest: uniform " + name + " has " + std::to_string(v.size()) +
                                    " components");
    }
  }
  return u;
}

std::vector<gl::Uniform> uniforms_of(const json& scene) {
  return uniform_list(scene.at("uniforms"));
}

// Every frame's uniforms (a pack from before stop 41 has the first frame only).
std::vector<json> frames_of(const json& scene) {
  if (scene.contains("frames")) return scene["frames"].get<std::vector<json>>();
  return {json{{"uniforms", scene.at("uniforms")}}};
}

int frame_count(const json& scene) {
  return scene.contains("frames") ? static_cast<int>(scene["frames"].size()) : 1;
}

fs::path image_path(const fs::path& out, const std::string& scene, const std::string& label, int frame) {
  return out / "images" / (scene + "__" + label + "__f" + std::to_string(frame) + ".f32");
}

// Draws `program` at the scene's own size for each frame (the tiled target's first tile) and writes
// the RGB floats, row 0 = top (bl::Image's layout).
void write_images(gl::Context& ctx, const gl::Program& program, const json& sc, const fs::path& out,
                  const std::string& label) {
  const int w = sc.at("scene_width"), h = sc.at("scene_height");
  const std::vector<json> frames = frames_of(sc);
  for (int f = 0; f < static_cast<int>(frames.size()); ++f) {
    const std::vector<float> rgba = ctx.render(program, w, h, uniform_list(frames[f].at("uniforms")));
    std::vector<float> rgb(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < rgb.size() / 3; ++i)
      for (int c = 0; c < 3; ++c) rgb[3 * i + c] = rgba[4 * i + c];
    const fs::path p = image_path(out, sc.at("scene"), label, f);
    {
      std::ofstream o(p.string() + ".tmp", std::ios::binary);
      o.write(reinterpret_cast<const char*>(rgb.data()),
              static_cast<std::streamsize>(rgb.size() * sizeof(float)));
      if (!o) throw std::runtime_error(p.string() + ": write failed");
    }
    fs::rename(p.string() + ".tmp", p);
  }
}

// The images write_images wrote, or none when any frame is missing (not drawn, or failed).
std::vector<Image> read_images(const fs::path& out, const json& sc, const std::string& label) {
  const int w = sc.at("scene_width"), h = sc.at("scene_height");
  std::vector<Image> images;
  for (int f = 0; f < frame_count(sc); ++f) {
    std::ifstream in(image_path(out, sc.at("scene"), label, f), std::ios::binary);
    if (!in) return {};
    Image img(w, h);
    in.read(reinterpret_cast<char*>(img.pixels.data()),
            static_cast<std::streamsize>(img.pixels.size() * sizeof(float)));
    if (!in) return {};
    images.push_back(std::move(img));
  }
  return images;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Best of 3 timings, each of enough draws to last ~budget_ms (one of 2 draws when a draw is longer).
double time_program(gl::Context& ctx, const gl::Program& prog, int w, int h,
                    const std::vector<gl::Uniform>& u, double budget_ms) {
  const double first = ctx.time_ms(prog, w, h, u, 2);
  if (first > budget_ms) return first;  // a slow program: 2 draws say enough, and more would cost seconds
  const int reps = static_cast<int>(std::clamp(budget_ms / std::max(first, 1e-3), 3.0, 500.0));
  double best = first;
  for (int t = 0; t < 3; ++t) best = std::min(best, ctx.time_ms(prog, w, h, u, reps));
  return best;
}

// One program of the pack: where it is and what is known of it.
struct Job {
  int scene = 0;  // index into the manifest's scenes
  json entry;     // the manifest's program entry
  gpu_timing::ProgramTime time;
  gl::Program program;
};

gpu_timing::ProgramTime from_entry(const json& pj) {
  gpu_timing::ProgramTime p;
  p.label = pj.at("label");
  p.kind = pj.at("kind");
  p.msaa = pj.at("msaa");
  p.error = pj.at("error").is_number() ? pj["error"].get<double>() : INFINITY;  // null: infeasible
  p.compiled_ns = pj.value("compiled_ns", -1.0);
  return p;
}

// Merged runs' gpu_times.json as the report's scenes (their pixel count from the records' ms and ns);
// `paths` comma-separated, a later file's scene replacing an earlier file's (a scene re-timed).
std::vector<gpu_timing::SceneTimes> read_times(const std::string& paths) {
  std::map<std::string, json> latest;  // scene -> its records from the last file that has it
  std::vector<std::string> order;
  for (std::size_t from = 0; from <= paths.size();) {
    const std::size_t comma = std::min(paths.find(',', from), paths.size());
    const std::string path = paths.substr(from, comma - from);
    from = comma + 1;
    if (path.empty()) continue;
    const json j = json::parse(read_text(path));
    std::map<std::string, json> here;
    for (const json& r : j.at("programs")) {
      const std::string scene = r.at("scene");
      if (!here.count(scene)) here[scene] = json::array();
      here[scene].push_back(r);
    }
    for (auto& [scene, records] : here) {
      if (!latest.count(scene)) order.push_back(scene);
      latest[scene] = std::move(records);
    }
  }
  std::vector<gpu_timing::SceneTimes> scenes;
  for (const std::string& scene : order) {
    gpu_timing::SceneTimes& st = scenes.emplace_back(gpu_timing::SceneTimes{scene, 0, 1, {}});
    for (const json& r : latest.at(scene)) {
      gpu_timing::ProgramTime p = from_entry(r);
      p.gpu_ms = r.at("gpu_ms");
      p.compile_ms = r.value("compile_ms", -1.0);
      p.failure = r.value("failure", std::string());
      p.gpu_error = r.value("gpu_error", json(nullptr)).is_number() ? r["gpu_error"].get<double>() : -1.0;
      p.nonfinite = r.value("nonfinite_pixels", 0L);
      p.out_of_range = r.value("out_of_range_pixels", 0L);
      const double ns = r.value("gpu_ns_per_pixel", -1.0);
      if (st.width == 0 && p.gpu_ms > 0 && ns > 0)
        st.width = static_cast<int>(std::lround(p.gpu_ms * 1e6 / ns));
      st.programs.push_back(p);
    }
    if (st.width == 0) throw std::runtime_error(paths + ": scene " + scene + " has no timed program");
  }
  return scenes;
}

json time_json(const std::string& scene, const gpu_timing::ProgramTime& p, double pixels) {
  return {{"scene", scene},
          {"label", p.label},
          {"gpu_ms", p.gpu_ms},
          {"gpu_ns_per_pixel", p.gpu_ms >= 0 ? p.gpu_ms * 1e6 / pixels : -1.0},
          {"compile_ms", p.compile_ms},
          {"failure", p.failure}};
}

// Holds an exclusive flock on a file for its lifetime (released by close, also if we crash).
class FileLock {
 public:
  explicit FileLock(const fs::path& p) : fd_(::open(p.c_str(), O_CREAT | O_RDWR, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) throw std::runtime_error(p.string() + ": cannot lock");
  }
  ~FileLock() { ::close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

// Compiles and times this shard's jobs; returns the shard's records.
json run_shard(const fs::path& pack, const json& manifest, const fs::path& out, int shard, int shards,
               const std::string& only, double budget_ms, double compile_seconds, const fs::path& binaries,
               std::string& renderer) {
  std::vector<Job> jobs;
  int index = 0;
  const json& scenes = manifest.at("scenes");
  for (int s = 0; s < static_cast<int>(scenes.size()); ++s) {
    if (scenes[s].at("scene").get<std::string>().find(only) == std::string::npos) continue;
    for (const json& pj : scenes[s].at("programs"))
      if (index++ % shards == shard) jobs.push_back({s, pj, from_entry(pj), {}});
  }
  const gl::Availability a = gl::Context::availability();
  if (!a.ok) throw std::runtime_error("no OpenGL context: " + a.reason);
  gl::Context ctx;
  ctx.set_unknown_uniform(gl::UnknownUniform::kIgnore);  // drivers drop uniforms a shader does not read
  renderer = ctx.renderer() + " (OpenGL " + ctx.version() + ")";
  const auto start = std::chrono::steady_clock::now();
  std::size_t compiled = 0;
  for (Job& j : jobs) {  // compiles: in parallel across shards
    if (seconds_since(start) > compile_seconds) {
      std::fprintf(stderr, "[shard %d] compile time (%.0f s) spent: %zu of %zu programs left untimed\n",
                   shard, compile_seconds, jobs.size() - compiled, jobs.size());
      break;
    }
    ++compiled;
    const std::string scene = scenes[j.scene].at("scene");
    try {
      const auto t0 = std::chrono::steady_clock::now();
      j.program = ctx.compile(read_text(pack / j.entry.at("frag").get<std::string>()));
      j.time.compile_ms = 1e3 * seconds_since(t0);
      if (!binaries.empty())
        write_text(binaries / (scene + "__" + j.time.label + ".bin"), ctx.program_binary(j.program));
    } catch (const gl::Error& e) {
      j.time.failure = e.what();
      std::fprintf(stderr, "blgpu_time: %s/%s: %s\n", scene.c_str(), j.time.label.c_str(), e.what());
    }
    std::fprintf(stderr, "[shard %d, %6.1f s] compiled %s/%s in %.0f ms\n", shard, seconds_since(start),
                 scene.c_str(), j.time.label.c_str(), j.time.compile_ms);
  }
  json records = json::array();
  jobs.resize(compiled);
  const FileLock lock(out / ".timing.lock");  // timings: one process at a time
  // The GPU idles while the shards compile and drops its clocks: the first program a shard timed
  // read 4-12x slow (plain at 1.3 ns/px instead of the 0.284 floor; the bricks rows, each shard's
  // first, in every run of docs/gpu_timing.md). Draw for a while before the first timing.
  for (const Job& j : jobs)
    if (j.program.valid() && j.time.kind != "truth") {
      const json& sc = scenes[j.scene];
      const auto t0 = std::chrono::steady_clock::now();
      try {
        for (int k = 0; k < 200 && seconds_since(t0) < 0.3; ++k)
          ctx.time_ms(j.program, sc.at("width"), sc.at("height"), uniforms_of(sc), 1);
      } catch (const gl::Error&) {
      }  // a program that cannot draw is reported by its own timing below
      break;
    }
  for (Job& j : jobs) {
    const json& sc = scenes[j.scene];
    const int w = sc.at("width"), h = sc.at("height");
    // An earlier run's images must not stand for a program that fails to draw now.
    for (int f = 0; f < frame_count(sc); ++f) fs::remove(image_path(out, sc.at("scene"), j.time.label, f));
    if (j.program.valid()) {
      try {
        if (j.time.kind != "truth")
          j.time.gpu_ms = time_program(ctx, j.program, w, h, uniforms_of(sc), budget_ms);
        write_images(ctx, j.program, sc, out, j.time.label);
      } catch (const gl::Error& e) {
        j.time.failure = e.what();
      }
    }
    records.push_back(time_json(sc.at("scene"), j.time, static_cast<double>(w) * h));
    // After every program: a shard cut off by a time limit still leaves what it measured.
    write_text(out / ("shard_" + std::to_string(shard) + ".json"),
               json{{"renderer", renderer}, {"programs", records}}.dump(1));
    std::fprintf(stderr, "[shard %d, %6.1f s] %s/%s: %.4f ms per %dx%d frame\n", shard, seconds_since(start),
                 sc.at("scene").get<std::string>().c_str(), j.time.label.c_str(), j.time.gpu_ms, w, h);
  }
  return records;
}

// The report from every shard's records, in the manifest's order.
void merge(const json& manifest, const fs::path& out, const std::vector<json>& shard_files) {
  std::map<std::pair<std::string, std::string>, json> by_key;
  std::string renderer;
  for (const json& f : shard_files) {
    renderer = f.at("renderer");
    for (const json& r : f.at("programs")) by_key[{r.at("scene"), r.at("label")}] = r;
  }
  std::vector<gpu_timing::SceneTimes> scenes;
  json all = json::array();
  for (const json& sc : manifest.at("scenes")) {
    // The scene's GPU truth and the range its pixels may take, as bltune's (render/value_range.hpp):
    // the declared bounds, else [0, 1] widened to what the truth and the plain program reach.
    const std::vector<Image> truth = read_images(out, sc, "truth");
    std::vector<Image> seen = truth;
    for (Image& img : read_images(out, sc, "plain")) seen.push_back(std::move(img));
    DeclaredBounds declared;
    if (sc.contains("declared_range"))
      for (int c = 0; c < Image::kChannels; ++c) {
        const json& b = sc["declared_range"].at(c);
        if (b.at(0).is_number()) declared.lo[c] = b[0].get<float>();
        if (b.at(1).is_number()) declared.hi[c] = b[1].get<float>();
      }
    const ValueRange range = bounded(ValueRange::of(seen), declared);
    gpu_timing::SceneTimes st;
    st.scene = sc.at("scene");
    st.width = sc.at("width");
    st.height = sc.at("height");
    for (const json& pj : sc.at("programs")) {
      const auto it = by_key.find({st.scene, pj.at("label")});
      if (it == by_key.end()) continue;  // not timed (--only, or a shard that did not finish)
      gpu_timing::ProgramTime p = from_entry(pj);
      p.gpu_ms = it->second.at("gpu_ms");
      p.compile_ms = it->second.at("compile_ms");
      p.failure = it->second.at("failure");
      const std::vector<Image> images = read_images(out, sc, p.label);
      if (!truth.empty() && !images.empty() && p.kind != "truth") {
        // As bltune: the RMS over frames of each frame's display-space RMS, NaN counting as 1.
        double sq = 0;
        for (std::size_t f = 0; f < images.size(); ++f) {
          const double e = rms_display(images[f], truth[f]);
          sq += e * e;
          const PixelCounts c = check_pixels(images[f], range);
          p.nonfinite += static_cast<long>(c.nonfinite);
          p.out_of_range += static_cast<long>(c.out_of_range);
        }
        p.gpu_error = std::sqrt(sq / images.size());
      }
      st.programs.push_back(p);
      json r = it->second;
      r["kind"] = p.kind, r["msaa"] = p.msaa, r["error"] = pj.at("error"), r["compiled_ns"] = p.compiled_ns;
      r["gpu_error"] = p.gpu_error >= 0 ? json(p.gpu_error) : json(nullptr);
      r["nonfinite_pixels"] = p.nonfinite, r["out_of_range_pixels"] = p.out_of_range;
      all.push_back(r);
    }
    if (!st.programs.empty()) scenes.push_back(st);
  }
  const int tile = manifest.at("tile");
  write_text(out / "gpu_times.json", json{{"renderer", renderer}, {"tile", tile}, {"programs", all}}.dump(1));
  const std::string md = gpu_timing::report_markdown(scenes, renderer, tile);
  write_text(out / "report.md", md);
  std::fputs(md.c_str(), stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blgpu_time: a blgpu_pack pack timed on this machine's OpenGL driver"};
  std::string pack, out, only, binaries, shard_text = "0/1";
  double budget_ms = 40, compile_seconds = 1e9;
  bool merge_only = false;
  std::vector<std::string> compare;
  std::string names = "A,B";
  app.add_option("pack", pack, "the directory blgpu_pack wrote (manifest.json)");
  app.add_option("--out", out, "where shard_<K>.json, gpu_times.json and report.md go");
  app.add_option(
         "--compare", compare,
         "A.json B.json: two merged runs' gpu_times.json (two tunings of the same scenes), scene by scene "
         "by the GPU's own errors and by bltune's; prints markdown and exits. A side may list files "
         "a.json,b.json: a later "
         "file's scene replaces an earlier one's")
      ->expected(2);
  app.add_option("--names", names, "with --compare: the two runs' names, comma-separated");
  app.add_option("--only", only, "time only scenes whose name contains this");
  app.add_option("--shard", shard_text, "K/N: this process's share of the programs (see the file comment)");
  app.add_flag("--merge", merge_only, "only join OUT/shard_*.json into gpu_times.json and report.md");
  app.add_option("--compile-seconds", compile_seconds,
                 "stop compiling new programs after this long and time those compiled (a time-limited GPU)");
  app.add_option("--binaries", binaries,
                 "also write each program's driver binary to DIR/<scene>__<label>.bin (NVIDIA's holds its "
                 "assembly as text: instruction counts, local memory)");
  app.add_option("--budget-ms", budget_ms, "draw time per timing run (3 runs per program)")
      ->check(CLI::Range(1.0, 10000.0));
  CLI11_PARSE(app, argc, argv);
  try {
    if (!compare.empty()) {
      const auto comma = names.find(',');
      if (comma == std::string::npos) throw std::invalid_argument("--names " + names + ": expected A,B");
      std::fputs(gpu_timing::comparison_markdown(read_times(compare[0]), read_times(compare[1]),
                                                 names.substr(0, comma), names.substr(comma + 1))
                     .c_str(),
                 stdout);
      return 0;
    }
    if (pack.empty() || out.empty())
      throw std::invalid_argument("give PACK and --out (or --compare A.json B.json)");
    const json manifest = json::parse(read_text(fs::path(pack) / "manifest.json"));
    fs::create_directories(out);
    int shard = 0, shards = 1;
    if (std::sscanf(shard_text.c_str(), "%d/%d", &shard, &shards) != 2 || shards < 1 || shard < 0 ||
        shard >= shards)
      throw std::invalid_argument("--shard " + shard_text + ": expected K/N with 0 <= K < N");
    if (!merge_only) {
      std::string renderer;
      if (!binaries.empty()) fs::create_directories(binaries);
      fs::create_directories(fs::path(out) / "images");
      run_shard(pack, manifest, out, shard, shards, only, budget_ms, compile_seconds, binaries, renderer);
      if (shards > 1) return 0;  // the caller merges when every shard is done
    }
    std::vector<json> files;
    for (const auto& e : fs::directory_iterator(out))
      if (e.path().filename().string().rfind("shard_", 0) == 0 && e.path().extension() == ".json")
        files.push_back(json::parse(read_text(e.path())));
    if (files.empty()) throw std::runtime_error(out + ": no shard_*.json to merge");
    merge(manifest, out, files);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blgpu_time: %s\n", e.what());
    return 1;
  }
  return 0;
}
