// What every shader in the suite sees and returns. A shader is written once as a template over the
// scalar type S: with float it runs natively (ground truth, MSAA, plain), with bl::dsl::Var it traces
// the DAG the compiler smooths. Effects are plain C++ flags read at trace time, so an effect a scene
// does not name leaves no node in the DAG.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dsl/vec.hpp"
#include "ir/graph.hpp"
#include "texture/texture.hpp"

namespace bl::shaders {

using dsl::Vec2;
using dsl::Vec3;

enum class Parallax { None, Bumps, Ripples };
enum class Lighting { None, Phong };

struct Effects {
  Parallax parallax = Parallax::None;
  Lighting lighting = Lighting::None;
  bool animated = false;  // false: time is the constant 0 (folds away)
};

// Inputs. u, v: surface coordinates, random (mean and footprint sd per pixel). view: unit vector
// from the surface point towards the eye in the tangent frame (z = surface normal); per pixel but not
// smoothed. light: unit direction towards the light (uniform). time: seconds (uniform). textures:
// the scene's loaded textures, read natively by texture lookups (a traced lookup records a node).
template <class S>
struct Inputs {
  S u, v;
  S time;
  Vec3<S> view;
  Vec3<S> light;
  const texture::Bindings* textures = nullptr;
};

// A texture a shader reads: the slot name scene files bind a file to, and how many channels.
struct TextureSlot {
  std::string name;
  int channels = 3;
  texture::Encoding encoding = texture::Encoding::Srgb;
};

// Input slots of a traced shader (names as in the compiled program).
inline const char* const kInputNames[] = {"u",      "v",       "time",    "view_x", "view_y",
                                          "view_z", "light_x", "light_y", "light_z"};

struct ShaderDef {
  std::string name;
  std::string description;
  bool uses_time = false;             // animation has an effect only for these
  std::vector<TextureSlot> textures;  // empty for procedural shaders
  std::function<Vec3<float>(const Inputs<float>&, const Effects&)> native;
  std::function<Vec3<dsl::Var>(const Inputs<dsl::Var>&, const Effects&)> traced;
};

// The suite: the 7 base shaders of Yang & Barnes' Table 1 (our implementations) plus the first
// paper's simple ones and the second checkerboard (Dorn et al. Listings 1-2).
const std::vector<ShaderDef>& suite();
std::vector<std::string> base_shader_names();  // the 7 combined with 3 parallax modes
// Throws std::invalid_argument naming the unknown shader and listing the known ones.
const ShaderDef& find_shader(const std::string& name);

// Traces shader + effects into a graph with outputs r, g, b. Inputs an effect does not read do not
// appear (time only when animated and used; view and light only with parallax or lighting).
ir::Graph trace(const ShaderDef& s, const Effects& fx);
// Native evaluation (float) of the same shader.
Vec3<float> shade(const ShaderDef& s, const Effects& fx, const Inputs<float>& in);

}  // namespace bl::shaders
