#include "jit/jit.hpp"

#include <dlfcn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "ir/hash.hpp"

namespace bl::jit {

namespace fs = std::filesystem;

namespace {

std::mutex g_mutex;       // one compile at a time per process
std::mutex g_memo_mutex;  // the memo maps below

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

std::string quote(const std::string& s) {  // for /bin/sh
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// stdout + stderr of a shell command, and its exit status.
std::pair<int, std::string> run(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::array<char, 4096> buf;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

// `<cxx> --version`, memoized: part of the key, and the check that the compiler exists.
const std::string& compiler_identity(const std::string& cxx) {
  static std::map<std::string, std::string> ids;
  const std::lock_guard<std::mutex> lock(g_memo_mutex);
  auto it = ids.find(cxx);
  if (it != ids.end()) return it->second;
  if (run("command -v " + quote(cxx)).first != 0)
    throw Error("jit: the C++ compiler '" + cxx +
                "' was not found (install g++, or set BL_JIT_CXX to a compiler); compiled-code timing "
                "needs one at run time");
  const auto [rc, text] = run(quote(cxx) + " --version");
  if (rc != 0) throw Error("jit: '" + cxx + " --version' failed (exit " + std::to_string(rc) + "): " + text);
  return ids.emplace(cxx, text).first->second;
}

// Contents of the headers the emitted code can include (memoized per directory list).
std::uint64_t headers_hash(const std::vector<std::string>& dirs) {
  static std::map<std::vector<std::string>, std::uint64_t> memo;
  const std::lock_guard<std::mutex> lock(g_memo_mutex);
  auto it = memo.find(dirs);
  if (it != memo.end()) return it->second;
  std::vector<fs::path> files;
  for (const std::string& d : dirs) {
    std::error_code ec;
    if (!fs::is_directory(d, ec)) continue;
    for (auto e = fs::recursive_directory_iterator(d, ec); !ec && e != fs::recursive_directory_iterator();
         e.increment(ec)) {
      const auto ext = e->path().extension();
      if (e->is_regular_file() && (ext == ".hpp" || ext == ".h")) files.push_back(e->path());
    }
  }
  std::sort(files.begin(), files.end());
  std::uint64_t h = ir::kFnvOffset;
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    h = ir::fnv1a(f.string(), h);
    h = ir::fnv1a(ss.str(), h);
  }
  return memo.emplace(dirs, h).first->second;
}

std::string hex(std::uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

}  // namespace

std::string flags_text(const Options& opt) {
  std::string out;
  for (const std::string& f : resolved(opt).flags) out += (out.empty() ? "" : " ") + f;
  return out;
}

Options resolved(const Options& opt) {
  Options o = opt;
  if (o.compiler.empty()) o.compiler = env_or("BL_JIT_CXX", env_or("CXX", "g++"));
  if (o.flags.empty()) {
    // -fno-math-errno: emitted code never reads errno, and without it GCC may not merge two exp
    // calls of one argument (a smoothed sin node's mean and variance share e^{-sigma^2/2}).
    // -march=native: the program runs where it is compiled, as a renderer's JIT targets its host. On
    // x86-64's baseline (SSE2) floorf is a library call: plain floor 1.17 -> 0.48 ns, box square
    // 6.4 -> 4.2 ns with the host's roundss (docs/tuning.md, stop 28).
    std::istringstream in(env_or("BL_JIT_FLAGS", kDefaultFlags));
    for (std::string f; in >> f;) o.flags.push_back(f);
  }
  if (o.include_dirs.empty()) o.include_dirs = {BL_JIT_INCLUDE_GENERATED, BL_JIT_INCLUDE_RUNTIME};
  if (o.cache_dir.empty()) o.cache_dir = env_or("BL_JIT_CACHE", "build/jit_cache");
  return o;
}

std::string cache_key(const std::string& source, const Options& opt) {
  const Options o = resolved(opt);
  std::uint64_t h = ir::fnv1a(source);
  h = ir::fnv1a(compiler_identity(o.compiler), h);
  h = ir::fnv1a(o.compiler, h);
  for (const std::string& f : o.flags) h = ir::fnv1a(f + '\0', h);
  for (const std::string& d : o.include_dirs) h = ir::fnv1a(d + '\0', h);
  // The headers of the generated table (other subdirectories of the include dirs do not matter to
  // emitted code: runtime/texture is the only runtime header it includes).
  std::vector<std::string> dirs;
  for (const std::string& d : o.include_dirs) {
    for (const char* sub : {"bandlimit", "texture"})
      if (fs::is_directory(fs::path(d) / sub)) dirs.push_back((fs::path(d) / sub).string());
  }
  h ^= headers_hash(dirs) * ir::kFnvPrime;
  return hex(h);
}

bool compiler_available(const Options& opt) {
  try {
    compiler_identity(resolved(opt).compiler);
    return true;
  } catch (const Error&) {
    return false;
  }
}

Library::~Library() {
  if (handle_) dlclose(handle_);
}

void* Library::symbol(const std::string& name) const {
  dlerror();
  void* s = dlsym(handle_, name.c_str());
  if (const char* err = dlerror())
    throw Error("jit: symbol '" + name + "' not found in " + path_ + ": " + err);
  return s;
}

std::shared_ptr<Library> compile(const std::string& source, const Options& opt) {
  const std::lock_guard<std::mutex> lock(g_mutex);
  const Options o = resolved(opt);
  const std::string key = cache_key(source, o);
  std::error_code ec;
  fs::create_directories(o.cache_dir, ec);
  if (ec) throw Error("jit: cannot create the cache directory " + o.cache_dir + ": " + ec.message());
  const fs::path dir = fs::absolute(o.cache_dir);
  const fs::path src = dir / ("jit_" + key + ".cpp"), so = dir / ("jit_" + key + ".so");
  std::shared_ptr<Library> lib(new Library());
  lib->path_ = so.string();
  lib->from_cache_ = fs::exists(so);
  if (!lib->from_cache_) {
    {
      const fs::path tmp_src = src.string() + ".tmp" + std::to_string(getpid());
      std::ofstream(tmp_src) << source;
      fs::rename(tmp_src, src, ec);
      if (ec) throw Error("jit: cannot write " + src.string() + ": " + ec.message());
    }
    const std::string tmp_so = so.string() + ".tmp" + std::to_string(getpid());
    std::string cmd = quote(o.compiler);
    for (const std::string& f : o.flags) cmd += " " + quote(f);
    cmd += " -fPIC -shared";
    for (const std::string& d : o.include_dirs) cmd += " -I" + quote(d);
    cmd += " " + quote(src.string()) + " -o " + quote(tmp_so);
    const auto t0 = std::chrono::steady_clock::now();
    const auto [rc, output] = run(cmd);
    lib->compile_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (rc != 0) {
      fs::remove(tmp_so, ec);
      std::string shown = output.size() > 8000 ? output.substr(0, 8000) + "\n[... truncated]" : output;
      throw Error("jit: compiling " + src.string() + " failed (exit " + std::to_string(rc) +
                  ")\ncommand: " + cmd + "\ncompiler output:\n" + shown);
    }
    fs::rename(tmp_so, so, ec);
    if (ec) throw Error("jit: cannot move the compiled object to " + so.string() + ": " + ec.message());
  }
  lib->handle_ = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib->handle_) throw Error(std::string("jit: dlopen of ") + so.string() + " failed: " + dlerror());
  return lib;
}

}  // namespace bl::jit
