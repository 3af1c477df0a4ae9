// A minimal JIT for emitted C++: write the source, compile it into a shared object with the system
// C++ compiler, dlopen it and look symbols up. Objects are cached on disk under a key that hashes
// the source, the compiler's identity (`<cxx> --version`), the flags and the contents of the
// headers the emitted code includes (generated/bandlimit, runtime/texture), so a second run (or a
// second process) loads the object without compiling.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace bl::jit {

// Every failure: the compiler missing or failing (the message names the source file and carries the
// compiler's output), dlopen or dlsym failing, the cache directory not writable.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The flags when neither Options::flags nor $BL_JIT_FLAGS gives them.
inline constexpr const char* kDefaultFlags = "-O3 -fno-math-errno -march=native -std=c++17";

struct Options {
  std::string compiler;                   // empty: $BL_JIT_CXX, else $CXX, else "g++"
  std::vector<std::string> flags;         // empty: $BL_JIT_FLAGS (split at spaces), else kDefaultFlags
  std::vector<std::string> include_dirs;  // empty: the source tree's generated/ and runtime/
  std::string cache_dir;                  // empty: $BL_JIT_CACHE, else "build/jit_cache"
};

class Library {
 public:
  ~Library();
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
  // The symbol's address; throws Error naming the symbol and the object when it is absent.
  void* symbol(const std::string& name) const;
  const std::string& path() const { return path_; }  // the shared object
  bool from_cache() const { return from_cache_; }    // loaded without compiling
  double compile_seconds() const { return compile_s_; }

 private:
  friend std::shared_ptr<Library> compile(const std::string&, const Options&);
  Library() = default;
  void* handle_ = nullptr;
  std::string path_;
  bool from_cache_ = false;
  double compile_s_ = 0;
};

// Compiles `source` (or loads the cached object). Thread-safe and safe across processes (the object
// is written under a temporary name and renamed into place).
std::shared_ptr<Library> compile(const std::string& source, const Options& opt = {});

// The cache key of `source` under `opt` (16 hex digits): what names the files in the cache.
std::string cache_key(const std::string& source, const Options& opt = {});

// Whether opt's compiler (resolved) exists and answers --version.
bool compiler_available(const Options& opt = {});

// Options with every default filled in (compiler, include dirs, cache dir).
Options resolved(const Options& opt);
// The resolved flags as one line (what a cost model records: times depend on them).
std::string flags_text(const Options& opt = {});

}  // namespace bl::jit
