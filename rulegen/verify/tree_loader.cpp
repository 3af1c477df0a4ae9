#include "tree_loader.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "clamped/verify_clamped.hpp"
#include "tree_api.hpp"
#include "tree_hash.hpp"

namespace blv {
namespace fs = std::filesystem;

namespace {

const TreeApi* g_api = nullptr;

// Opens a plugin; nullptr (and *why) when it cannot be opened or has another ABI.
const TreeApi* open_plugin(const std::string& path, std::string* why) {
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    *why = dlerror();
    return nullptr;
  }
  auto fn = reinterpret_cast<const TreeApi* (*)()>(dlsym(h, "blv_tree_api"));
  const TreeApi* api = fn ? fn() : nullptr;
  if (!api || api->abi != kTreeAbi) {
    *why = path + ": not a blverify tree plugin of ABI " + std::to_string(kTreeAbi);
    dlclose(h);
    return nullptr;
  }
  return api;  // kept open: EntryView holds its function pointers
}

std::string cache_dir() {
  if (const char* c = std::getenv("BLVERIFY_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/bandlimit/blverify";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.cache/bandlimit/blverify";
  return (fs::temp_directory_path() / "bandlimit-blverify").string();
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Compiles the plugin sources against dir into `out` (through a temporary name, renamed at the end,
// so a concurrent blverify never loads half a file). The translation units compile in parallel.
bool compile_plugin(const std::string& dir, const std::string& hash, const std::string& out,
                    std::string* error) {
  const std::string src = BLVERIFY_SOURCE_DIR, tmpl = BLVERIFY_TEMPLATES_DIR;
  const std::string work = out + ".build." + std::to_string(getpid());
  fs::create_directories(work);
  const std::string flags = std::string(BLVERIFY_PLUGIN_FLAGS) +
                            " -DBLVERIFY_HAVE_REGISTRY=1 -DBLVERIFY_TREE_HASH='\"" + hash + "\"' -I" +
                            quote(src) + " -I" + quote(dir) + " -I" + quote(tmpl);
  std::string script = "set -u; pids=''; ";
  std::string objs;
  int k = 0;
  for (const char* s : {"reference_mp.cpp", "registry_view.cpp", "clamped/verify_clamped.cpp",
                        "bivariate_check.cpp", "mode_check.cpp", "tree_plugin.cpp"}) {
    const std::string obj = quote(work + "/" + std::to_string(k++) + ".o");
    script += std::string(BLVERIFY_CXX) + " " + flags + " -c " + quote(src + "/" + s) + " -o " + obj +
              " & pids=\"$pids $!\"; ";
    objs += " " + obj;
  }
  script += "rc=0; for p in $pids; do wait $p || rc=1; done; [ $rc = 0 ] && " + std::string(BLVERIFY_CXX) +
            " " + BLVERIFY_PLUGIN_FLAGS + " -shared" + objs + " -o " +
            quote(out + ".tmp." + std::to_string(getpid())) + " && mv -f " +
            quote(out + ".tmp." + std::to_string(getpid())) + " " + quote(out);
  const std::string log = work + "/log.txt";
  std::fprintf(stderr, "blverify: compiling the tree %s (hash %s) into %s ...\n", dir.c_str(), hash.c_str(),
               out.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(("bash -c " + quote(script) + " > " + quote(log) + " 2>&1").c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::error_code ec;
  if (rc != 0) {
    const std::string text = file_bytes(log);
    fs::remove_all(work, ec);
    *error = "compiling the tree " + dir + " failed (" + std::to_string(s) + " s); compiler output:\n" +
             text.substr(0, 4000);
    return false;
  }
  std::fprintf(stderr, "blverify: compiled in %.1f s\n", s);
  fs::remove_all(work, ec);
  return true;
}

}  // namespace

bool load_tree(const std::string& dir, std::string* error) {
  if (!fs::exists(fs::path(dir) / "bandlimit" / "registry.hpp")) {
    *error = dir + "/bandlimit/registry.hpp not found: --generated needs a tree written by `rulegen emit`";
    return false;
  }
  const std::string hash = tree_hash(dir, BLVERIFY_SOURCE_DIR, BLVERIFY_TEMPLATES_DIR, kTreeAbi);
  std::string why;
  if (const TreeApi* api = open_plugin(BLVERIFY_DEFAULT_PLUGIN, &why); api && hash == api->tree_hash) {
    g_api = api;  // the tree CMake built against: nothing to compile
    return true;
  }
  const std::string out = cache_dir() + "/tree-" + hash + ".so";
  std::error_code ec;
  fs::create_directories(cache_dir(), ec);
  if (!fs::exists(out) && !compile_plugin(dir, hash, out, error)) return false;
  g_api = open_plugin(out, &why);
  if (!g_api) *error = "cannot load " + out + ": " + why;
  return g_api != nullptr;
}

// Forwarders: what blverify calls, answered by the loaded tree.
bool registry_compiled_in() {
  return g_api && g_api->registry_compiled_in();
}
std::vector<EntryView> load_registry(std::string* error) {
  if (!g_api) {
    *error = "no generated tree loaded (--generated DIR)";
    return {};
  }
  return g_api->load_registry(error);
}
std::vector<StatView> load_stats(std::string* error) {
  if (!g_api) {
    *error = "no generated tree loaded (--generated DIR)";
    return {};
  }
  return g_api->load_stats(error);
}
bool mp_registry_matches(const std::vector<EntryView>& entries, std::string* error) {
  return g_api && g_api->mp_registry_matches(entries, error);
}
void mp_warm_up() {
  if (g_api) g_api->mp_warm_up();
}
MpResult mp_check(int index, const Spec& spec, double x, double sigma) {
  if (!g_api) return MpResult{};
  return g_api->mp_check(index, spec, x, sigma);
}
bool rules_compiled_in() {
  return g_api && g_api->rules_compiled_in();
}
std::vector<RuleCheck> check_bivariate() {
  return g_api ? g_api->check_bivariate() : std::vector<RuleCheck>{};
}
std::vector<RuleCheck> check_rule2() {
  return g_api ? g_api->check_rule2() : std::vector<RuleCheck>{};
}

namespace clamped {
int run(const std::string& manifest_path, bool record, std::FILE* out) {
  return g_api ? g_api->clamped_run(manifest_path, record, out) : 0;
}
}  // namespace clamped

}  // namespace blv
