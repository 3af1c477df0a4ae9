#include "gl/egl_runner.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <sstream>

#include "gl/egl_display.hpp"
#include "gl/shader_log.hpp"

namespace bl::gl {

struct Program::Owner {
  std::function<void(unsigned)> release;
};

namespace {

// One triangle covering the viewport; the vertex ids give (-1,-1), (3,-1), (-1,3) in clip space.
constexpr const char* kVertexShader = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

std::string gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "GL error " + std::to_string(e);
  }
}

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw Error(std::string("GL: ") + what + ": " + gl_error_name(e));
}

GLuint compile_stage(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  glDeleteShader(shader);
  const char* name = stage == GL_VERTEX_SHADER ? "vertex" : "fragment";
  throw ShaderError(std::string(name) + " shader failed to compile:\n" + annotate_shader_log(log, source),
                    log);
}

// The GLSL type a Uniform alternative must meet.
GLenum expected_type(const UniformValue& v) {
  static constexpr GLenum kTypes[] = {GL_FLOAT,      GL_INT,        GL_FLOAT_VEC2, GL_FLOAT_VEC3,
                                      GL_FLOAT_VEC4, GL_FLOAT_MAT3, GL_SAMPLER_2D};
  return kTypes[v.index()];
}

const char* glsl_type_name(GLenum t) {
  switch (t) {
    case GL_FLOAT:
      return "float";
    case GL_INT:
      return "int";
    case GL_FLOAT_VEC2:
      return "vec2";
    case GL_FLOAT_VEC3:
      return "vec3";
    case GL_FLOAT_VEC4:
      return "vec4";
    case GL_FLOAT_MAT3:
      return "mat3";
    case GL_BOOL:
      return "bool";
    case GL_INT_VEC2:
      return "ivec2";
    case GL_FLOAT_MAT4:
      return "mat4";
    case GL_SAMPLER_2D:
      return "sampler2D";
    default:
      return "another type";
  }
}

struct ActiveUniform {
  GLint location;
  GLenum type;
  GLint size;
};

}  // namespace

struct Context::Impl {
  detail::EglContext egl;
  GLuint vao = 0, fbo = 0, color = 0;
  int fbo_width = 0, fbo_height = 0;
  GLint max_size = 0;
  std::map<GLuint, std::map<std::string, ActiveUniform>> uniforms;  // per program

  void ensure_target(int width, int height) {
    if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
      throw Error("GL: render size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is outside 1.." + std::to_string(max_size));
    }
    if (width == fbo_width && height == fbo_height) return;
    if (color != 0) glDeleteTextures(1, &color);
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA32F, width, height);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw Error("GL: the RGBA32F framebuffer is incomplete");
    check_gl("creating the RGBA32F target");
    fbo_width = width;
    fbo_height = height;
  }
};

Program::Program(Program&& o) noexcept : owner_(std::move(o.owner_)), id_(o.id_) {
  o.id_ = 0;
}
Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    reset();
    owner_ = std::move(o.owner_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}
Program::~Program() {
  reset();
}
void Program::reset() {
  if (id_ != 0) {
    if (auto owner = owner_.lock()) owner->release(id_);
  }
  id_ = 0;
  owner_.reset();
}

Availability Context::availability() {
  static std::once_flag once;
  static Availability result;
  std::call_once(once, [] {
    try {
      Context probe;
      result = {true, probe.renderer() + ", OpenGL " + probe.version()};
    } catch (const std::exception& e) {
      result = {false, e.what()};
    }
  });
  return result;
}

Context::Context() : impl_(std::make_unique<Impl>()) {
  impl_->egl = detail::create_egl_context();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    const std::string have = version();
    detail::destroy_egl_context(impl_->egl);
    throw Error("GL: need OpenGL 4.5 core, the driver gives " + have);
  }
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &impl_->max_size);
  glCreateVertexArrays(1, &impl_->vao);
  glCreateFramebuffers(1, &impl_->fbo);
  check_gl("creating the vertex array and framebuffer");
  Impl* impl = impl_.get();
  owner_ = std::make_shared<Program::Owner>();
  owner_->release = [impl](unsigned id) {
    detail::make_current(impl->egl);
    glDeleteProgram(id);
    impl->uniforms.erase(id);
  };
}

Context::~Context() {
  owner_.reset();  // programs still alive become no-ops; the context deletes their GL objects
  try {
    detail::make_current(impl_->egl);
  } catch (...) {
  }
  for (auto& [id, _] : impl_->uniforms) glDeleteProgram(id);
  if (impl_->color != 0) glDeleteTextures(1, &impl_->color);
  glDeleteFramebuffers(1, &impl_->fbo);
  glDeleteVertexArrays(1, &impl_->vao);
  detail::destroy_egl_context(impl_->egl);
}

std::string Context::renderer() const {
  detail::make_current(impl_->egl);
  const GLubyte* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "?";
}

std::string Context::version() const {
  detail::make_current(impl_->egl);
  const GLubyte* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "?";
}

Program Context::compile(const std::string& fragment_source) {
  detail::make_current(impl_->egl);
  const GLuint vs = compile_stage(GL_VERTEX_SHADER, kVertexShader);
  GLuint fs = 0;
  try {
    fs = compile_stage(GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);  // program_binary()
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    glDeleteProgram(program);
    throw ShaderError("program failed to link:\n" + annotate_shader_log(log, fragment_source), log);
  }

  // Record the active uniforms so that set-up errors name the uniform and its declared type.
  auto& table = impl_->uniforms[program];
  GLint count = 0;
  glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(program, static_cast<GLuint>(i), sizeof(name), &length, &size, &type, name);
    std::string key(name, static_cast<size_t>(length));
    table[key] = {glGetUniformLocation(program, name), type, size};
  }
  check_gl("linking the program");
  return Program(owner_, program);
}

std::string Context::program_binary(const Program& program) {
  detail::make_current(impl_->egl);
  GLint length = 0;
  glGetProgramiv(program.id_, GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) return {};
  std::string bytes(static_cast<size_t>(length), '\0');
  GLenum format = 0;
  GLsizei written = 0;
  glGetProgramBinary(program.id_, length, &written, &format, bytes.data());
  check_gl("glGetProgramBinary");
  bytes.resize(static_cast<size_t>(written));
  return bytes;
}

void Context::draw(const Program& program, int width, int height, const std::vector<Uniform>& uniforms) {
  if (!program.valid() || program.owner_.lock() != owner_) {
    throw Error("GL: the program is empty or belongs to another context");
  }
  detail::make_current(impl_->egl);
  impl_->ensure_target(width, height);
  const GLuint id = program.id_;
  const auto& table = impl_->uniforms.at(id);
  GLuint unit = 0;  // samplers take texture units in the order given
  for (const Uniform& u : uniforms) {
    auto it = table.find(u.name);
    if (it == table.end()) {
      if (unknown_uniform_ == UnknownUniform::kIgnore) continue;
      std::ostringstream msg;
      msg << "GL: uniform '" << u.name
          << "' is not an active uniform of the program (undeclared, misspelled, or unused and "
             "optimized away); active uniforms:";
      if (table.empty()) msg << " none";
      for (const auto& [name, info] : table) msg << ' ' << name << " (" << glsl_type_name(info.type) << ')';
      throw Error(msg.str());
    }
    const ActiveUniform& a = it->second;
    if (a.type != expected_type(u.value)) {
      throw Error("GL: uniform '" + u.name + "' is declared " + glsl_type_name(a.type) + " but was given a " +
                  glsl_type_name(expected_type(u.value)));
    }
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, float>) glProgramUniform1f(id, a.location, v);
          if constexpr (std::is_same_v<T, int>) glProgramUniform1i(id, a.location, v);
          if constexpr (std::is_same_v<T, Vec2>) glProgramUniform2fv(id, a.location, 1, v.data());
          if constexpr (std::is_same_v<T, Vec3>) glProgramUniform3fv(id, a.location, 1, v.data());
          if constexpr (std::is_same_v<T, Vec4>) glProgramUniform4fv(id, a.location, 1, v.data());
          if constexpr (std::is_same_v<T, Mat3>) {
            glProgramUniformMatrix3fv(id, a.location, 1, GL_FALSE, v.m.data());
          }
          if constexpr (std::is_same_v<T, Sampler>) {
            glBindTextureUnit(unit, v.texture);
            glProgramUniform1i(id, a.location, static_cast<GLint>(unit++));
          }
        },
        u.value);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(id);
  glBindVertexArray(impl_->vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  check_gl("drawing");
}

std::vector<float> Context::render(const Program& program, int width, int height,
                                   const std::vector<Uniform>& uniforms) {
  draw(program, width, height, uniforms);
  std::vector<float> pixels(static_cast<size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  // GL's bottom row comes first in memory; we keep that order and call it the top (file comment).
  glNamedFramebufferReadBuffer(impl_->fbo, GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
  check_gl("reading the pixels back");
  return pixels;
}

std::vector<float> Context::render(const std::string& fragment_source, int width, int height,
                                   const std::vector<Uniform>& uniforms) {
  const Program program = compile(fragment_source);
  return render(program, width, height, uniforms);
}

unsigned Context::upload(const TextureLevels& t) {
  detail::make_current(impl_->egl);
  if (t.channels < 1 || t.channels > 4 || t.width < 1 || t.height < 1)
    throw Error("GL: texture of " + std::to_string(t.width) + "x" + std::to_string(t.height) + "x" +
                std::to_string(t.channels) + " (channels must be 1..4)");
  const int count = static_cast<int>(t.levels.size());
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, count, GL_RGBA32F, t.width, t.height);
  for (int k = 0; k < count; ++k) {
    const int w = std::max(1, t.width >> k), h = std::max(1, t.height >> k);
    if (t.levels[k].size() != static_cast<std::size_t>(w) * h * t.channels) {
      glDeleteTextures(1, &tex);
      throw Error("GL: texture level " + std::to_string(k) + " has " + std::to_string(t.levels[k].size()) +
                  " floats, expected " + std::to_string(w * h * t.channels));
    }
    std::vector<float> rgba(static_cast<std::size_t>(w) * h * 4, 0.0f);  // padded to RGBA
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
      for (int c = 0; c < t.channels; ++c) rgba[i * 4 + c] = t.levels[k][i * t.channels + c];
    glTextureSubImage2D(tex, k, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
  }
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, count - 1);
  check_gl("uploading a texture");
  return tex;
}

void Context::release(unsigned texture) {
  detail::make_current(impl_->egl);
  const GLuint tex = texture;
  glDeleteTextures(1, &tex);
}

double Context::time_ms(const Program& program, int width, int height, const std::vector<Uniform>& uniforms,
                        int repeats) {
  if (repeats < 1) throw Error("GL: time_ms needs repeats >= 1");
  draw(program, width, height, uniforms);  // warm-up: shader JIT, target allocation
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < repeats; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  const auto stop = std::chrono::steady_clock::now();
  check_gl("timing");
  return std::chrono::duration<double, std::milli>(stop - start).count() / repeats;
}

}  // namespace bl::gl
