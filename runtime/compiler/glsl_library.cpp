#include "compiler/glsl_library.hpp"

#include <cctype>
#include <map>
#include <set>
#include <stdexcept>

namespace bl::compiler {

extern const char* const kEmbeddedGlsl[];  // embed_glsl.cmake: chunks, null-terminated

const std::string& glsl_library() {
  static const std::string text = [] {
    std::string s;
    for (int i = 0; kEmbeddedGlsl[i]; ++i) s += kEmbeddedGlsl[i];
    return s;
  }();
  return text;
}

namespace {

struct Item {
  std::string name;
  std::string text;
  std::set<std::string> idents;
};

bool ident_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool ident_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Splits the library into top-level definitions (comments dropped).
std::vector<Item> split(const std::string& src) {
  std::string code;  // the source without comments
  for (std::size_t i = 0; i < src.size();) {
    if (src.compare(i, 2, "//") == 0) {
      while (i < src.size() && src[i] != '\n') ++i;
    } else if (src.compare(i, 2, "/*") == 0) {
      const auto e = src.find("*/", i + 2);
      i = e == std::string::npos ? src.size() : e + 2;
    } else {
      code += src[i++];
    }
  }
  std::vector<Item> items;
  std::string cur;
  int depth = 0;
  auto finish = [&] {
    Item it;
    it.text = cur;
    cur.clear();
    std::vector<std::string> words;
    std::size_t paren = std::string::npos;
    for (std::size_t i = 0; i < it.text.size();) {
      if (ident_start(it.text[i])) {
        std::size_t j = i;
        while (j < it.text.size() && ident_char(it.text[j])) ++j;
        const std::string w = it.text.substr(i, j - i);
        it.idents.insert(w);
        words.push_back(w);
        i = j;
      } else {
        if (paren == std::string::npos && (it.text[i] == '(' || it.text[i] == '=' || it.text[i] == '[' ||
                                           it.text[i] == '{' || it.text[i] == ';'))
          paren = words.size();
        ++i;
      }
    }
    if (words.empty()) return;
    // struct S {...};  |  type name(...) {...}  |  const type NAME = ...;
    it.name = words[0] == "struct" && words.size() > 1
                  ? words[1]
                  : words[paren == std::string::npos ? words.size() - 1 : paren - 1];
    it.idents.erase(it.name);
    items.push_back(std::move(it));
  };
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (depth == 0 && cur.find_first_not_of(" \t\r\n") == std::string::npos && c == '#') {
      // Preprocessor line: its own item, always kept (there are none today).
      const auto e = code.find('\n', i);
      cur = code.substr(i, e - i);
      Item it;
      it.name = "#";
      it.text = cur + "\n";
      items.push_back(it);
      cur.clear();
      i = e == std::string::npos ? code.size() : e;
      continue;
    }
    cur += c;
    if (c == '{' || c == '(') ++depth;
    if (c == '}' || c == ')') --depth;
    if (depth == 0 && c == ';') {
      cur += '\n';
      finish();
    } else if (depth == 0 && c == '}') {
      std::size_t j = i + 1;
      while (j < code.size() && std::isspace(static_cast<unsigned char>(code[j]))) ++j;
      if (j >= code.size() || code[j] != ';') {
        cur += '\n';
        finish();
      }
    }
  }
  return items;
}

}  // namespace

std::string precise_declarations(const std::string& text) {
  static const std::set<std::string> types{"float", "vec2", "vec3", "vec4", "mat2", "mat3", "mat4"};
  std::string out;
  int braces = 0, parens = 0;
  bool statement_start = false;  // after '{', ';' or '}' inside braces, outside parentheses
  bool in_struct = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (ident_start(c)) {
      std::size_t j = i;
      while (j < text.size() && ident_char(text[j])) ++j;
      const std::string w = text.substr(i, j - i);
      if (braces == 0 && w == "struct") in_struct = true;
      if (statement_start && !in_struct && types.count(w) != 0) out += "precise ";
      out += w;
      statement_start = false;
      i = j;
      continue;
    }
    out += c;
    ++i;
    if (c == '(') ++parens;
    if (c == ')') --parens;
    if (c == '{') ++braces;
    if (c == '}' && --braces == 0) in_struct = false;
    if (c == '{' || c == '}' || c == ';')
      statement_start = braces > 0 && parens == 0;
    else if (!std::isspace(static_cast<unsigned char>(c)))
      statement_start = false;
  }
  return out;
}

std::string glsl_library_slice(const std::vector<std::string>& roots,
                               const std::vector<std::string>& precise_roots) {
  static const std::vector<Item> items = split(glsl_library());
  std::map<std::string, std::vector<int>> by_name;
  for (std::size_t i = 0; i < items.size(); ++i) by_name[items[i].name].push_back(static_cast<int>(i));
  // The items reachable from `from`.
  auto reach = [&](const std::vector<std::string>& from) {
    std::set<int> keep;
    std::vector<std::string> todo;
    for (const auto& r : from) {
      if (!by_name.count(r)) throw std::invalid_argument("GLSL library has no definition of '" + r + "'");
      todo.push_back(r);
    }
    std::set<std::string> done;
    while (!todo.empty()) {
      const std::string n = todo.back();
      todo.pop_back();
      if (!done.insert(n).second) continue;
      for (int i : by_name[n]) {
        keep.insert(i);
        for (const auto& id : items[i].idents)
          if (by_name.count(id) && !done.count(id)) todo.push_back(id);
      }
    }
    return keep;
  };
  const std::set<int> keep = reach(roots), precise = reach(precise_roots);
  std::string out = "// ---- bandlimit library (sliced from generated/bandlimit*.glsl) ----\n";
  for (std::size_t i = 0; i < items.size(); ++i)
    if (keep.count(static_cast<int>(i)) || items[i].name == "#")
      out += precise.count(static_cast<int>(i)) ? precise_declarations(items[i].text) : items[i].text;
  return out;
}

std::string glsl_texture_library(std::size_t slots) {
  std::string s;
  for (std::size_t k = 0; k < slots; ++k)
    s += "uniform sampler2D bl_tex" + std::to_string(k) + "_mean;\nuniform sampler2D bl_tex" +
         std::to_string(k) + "_sq;\n";
  s += R"(float bl_tex_plain(sampler2D m, float u, float v, int c) {
  return textureLod(m, vec2(u, v), 0.0)[c];
}
vec2 bl_tex_stat(sampler2D m, sampler2D q, float u, float v, float su, float sv, int c) {
  vec2 size = vec2(textureSize(m, 0));
  float tu = su * size.x, tv = sv * size.y;
  float s_long = max(tu, tv), s_short = min(tu, tv);
  float mean = 0.0, sq = 0.0;
  if (!(s_long > 2.0 * s_short)) {
    float lod = 0.5 * log2(4.0 * s_long * s_long + 0.666666667);
    mean = textureLod(m, vec2(u, v), lod)[c];
    sq = textureLod(q, vec2(u, v), lod)[c];
  } else {
    float s_level = max(s_short, s_long / 16.0);
    float lod = 0.5 * log2(4.0 * s_level * s_level + 0.666666667);
    float rest = sqrt(s_long * s_long - s_level * s_level);
    vec2 d = tu > tv ? vec2(rest / size.x, 0.0) : vec2(0.0, rest / size.y);
    const float node[2] = float[2](0.741960677, 2.33441422);
    const float weight[2] = float[2](0.454124578, 0.0458758548);
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j) {
        vec2 p = vec2(u, v) + (j == 0 ? -1.0 : 1.0) * node[k] * d;
        mean += weight[k] * textureLod(m, p, lod)[c];
        sq += weight[k] * textureLod(q, p, lod)[c];
      }
  }
  float var = sq - mean * mean;
  return vec2(mean, var > 0.0 ? var : 0.0);
}
)";
  return s;
}

}  // namespace bl::compiler
