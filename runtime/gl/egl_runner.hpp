// Headless OpenGL 4.5 core runner: compiles a fragment shader, draws it over a whole RGBA32F
// framebuffer and reads the pixels back as floats. No window system: EGL's surfaceless platform
// (Mesa llvmpipe on a CPU-only machine), or EGL's device platform where a GPU driver offers one.
//
// Pixel convention (the same as bl::Image): the returned buffer is row-major with row 0 = TOP, and
// the fragment at row r, column c sees gl_FragCoord.xy = (c + 0.5, r + 0.5). In other words
// gl_FragCoord.y grows downward in the returned image, exactly like the CPU pixel coordinates of
// runtime/camera, so a shader and its CPU twin see identical (x, y) for the same output pixel.
// (This is simply GL's framebuffer memory order read without a flip; dFdy therefore points down.)
//
// Contexts are bound to the calling thread: use a Context from one thread at a time.
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace bl::gl {

struct Availability {
  bool ok = false;
  std::string reason;  // why not (ok == false), or the driver's renderer/version string (ok == true)
};

using Vec2 = std::array<float, 2>;
using Vec3 = std::array<float, 3>;
using Vec4 = std::array<float, 4>;
// Column-major, as GLSL stores mat3: m[3 * column + row].
struct Mat3 {
  std::array<float, 9> m;
};
// A sampler2D uniform: a texture made by Context::upload (bound to a texture unit at draw time).
struct Sampler {
  unsigned texture = 0;
};
using UniformValue = std::variant<float, int, Vec2, Vec3, Vec4, Mat3, Sampler>;

// A mipmapped float texture: level k is max(1, width >> k) x max(1, height >> k) texels of
// `channels` (1..4) floats, row 0 first (texture coordinate t = 0). Every level down to 1x1.
struct TextureLevels {
  int width = 0, height = 0, channels = 0;
  std::vector<std::vector<float>> levels;
};

struct Uniform {
  std::string name;
  UniformValue value;
};

// Driver or usage failure (no context, bad uniform, bad size, GL error).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Compile or link failure. what() holds the stage, the driver's info log and the offending source
// lines (numbered as in the source given); log() is the raw info log.
class ShaderError : public Error {
 public:
  ShaderError(const std::string& message, std::string log) : Error(message), log_(std::move(log)) {}
  const std::string& log() const { return log_; }

 private:
  std::string log_;
};

// What to do with a uniform the program does not have (misspelled, or declared but unused and so
// removed by the compiler: the two cannot be told apart through GL).
enum class UnknownUniform { kThrow, kIgnore };

class Context;

// A linked program (fixed fullscreen-triangle vertex shader + the user's fragment shader).
// Move-only; releasing it after its Context is gone is safe (it becomes a no-op).
class Program {
 public:
  Program() = default;
  Program(Program&&) noexcept;
  Program& operator=(Program&&) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  ~Program();
  bool valid() const { return id_ != 0; }

 private:
  friend class Context;
  struct Owner;
  Program(std::shared_ptr<Owner> owner, unsigned id) : owner_(std::move(owner)), id_(id) {}
  void reset();
  std::weak_ptr<Owner> owner_;
  unsigned id_ = 0;
};

class Context {
 public:
  // Tries once per process to create a context; tests call this and GTEST_SKIP() << reason.
  static Availability availability();

  Context();  // throws Error with the failing EGL step
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  std::string renderer() const;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // e.g. "4.5 (Core Profile) Mesa 22.3.6"

  // `fragment_source` is a complete GLSL fragment shader (with its #version line) writing one vec4
  // output. Throws ShaderError on compile/link failure.
  Program compile(const std::string& fragment_source);

  // The driver's binary of a linked program (glGetProgramBinary; its format is the driver's own).
  // NVIDIA's holds the assembly it generated as text: instruction counts and local-memory arrays
  // ("lmem") read from it say why a shader is slow. Empty where the driver offers no binary.
  std::string program_binary(const Program& program);

  // RGBA32F pixels, width * height * 4 floats, row 0 = top (see the file comment).
  std::vector<float> render(const Program& program, int width, int height,
                            const std::vector<Uniform>& uniforms = {});
  std::vector<float> render(const std::string& fragment_source, int width, int height,
                            const std::vector<Uniform>& uniforms = {});

  // Milliseconds per frame: one warm-up draw, then `repeats` draws between two glFinish calls.
  double time_ms(const Program& program, int width, int height, const std::vector<Uniform>& uniforms,
                 int repeats = 20);

  void set_unknown_uniform(UnknownUniform policy) { unknown_uniform_ = policy; }

  // An RGBA32F texture with exactly the given levels (no glGenerateMipmap, so the GPU filters the
  // same pyramid the CPU does), GL_LINEAR_MIPMAP_LINEAR / GL_LINEAR, GL_REPEAT. Freed by release()
  // or with the context. Throws Error on a malformed level list.
  unsigned upload(const TextureLevels& t);
  void release(unsigned texture);

 private:
  struct Impl;
  void draw(const Program& program, int width, int height, const std::vector<Uniform>& uniforms);
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<Program::Owner> owner_;
  UnknownUniform unknown_uniform_ = UnknownUniform::kThrow;
};

}  // namespace bl::gl
