// The GLSL front end: each construct traces to the values (and, where the mapping is fixed, the graph)
// written independently in C++; errors name file:line:col; a scene naming a .glsl file renders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "dsl/math.hpp"
#include "glsl/native.hpp"
#include "glsl/shader.hpp"
#include "glsl/trace.hpp"
#include "ir/atomics.hpp"

namespace bl {
namespace {

using V3 = std::array<double, 3>;

glsl::Pattern trace(const std::string& body) {
  return glsl::trace_source(body, "test.glsl");
}

// The traced pattern evaluated natively against `want` (plain C++ written from GLSL's definitions)
// on a grid of u, v (no point on a discontinuity) and two times.
void expect_values(const std::string& src, const std::function<V3(double, double, double)>& want,
                   double tol = 2e-5) {
  const glsl::Pattern p = trace(src);
  const glsl::NativeProgram prog(p.graph);
  for (double u = -2.93; u < 3; u += 0.71)
    for (double v = -2.87; v < 3; v += 0.67)
      for (double t : {0.0, 1.3}) {
        float out[3];
        prog.run(static_cast<float>(u), static_cast<float>(v), static_cast<float>(t), nullptr, out);
        const V3 w = want(u, v, t);
        for (int k = 0; k < 3; ++k)
          ASSERT_NEAR(out[k], w[k], tol * std::max(1.0, std::fabs(w[k])))
              << "channel " << k << " at u=" << u << " v=" << v << " t=" << t << "\n"
              << src;
      }
}

std::string error_of(const std::string& src, const std::string& file = "test.glsl") {
  try {
    glsl::trace_source(src, file);
  } catch (const glsl::Error& e) {
    return e.what();
  }
  return "(no error)";
}

int count_calls(const ir::Graph& g, const char* atomic) {
  int n = 0;
  for (const auto& node : g.nodes()) n += node.op == ir::Op::Call && node.atomic == ir::atomic_index(atomic);
  return n;
}

double fract(double x) {
  return x - std::floor(x);
}
double smooth01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

TEST(GlslFrontEnd, ArithmeticSwizzlesAndVectors) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  vec3 a = vec3(uv, time);
  a.xy += vec2(1.0, 2.0) * 0.5;
  a.zx = a.xz;              // swizzle write
  vec4 b = vec4(a, 1.0);
  b.w *= 3.0;
  b[1] -= 1.0;
  vec3 c = b.wzy / 2.0 - vec3(a.x) + a * a;
  c -= 1.0;
  return -c * vec3(1.0, 2.0, 0.5);
})",
                [](double u, double v, double t) {
                  double ax = u + 0.5, ay = v + 1.0, az = t;
                  std::swap(ax, az);
                  const double bx = ax, by = ay - 1, bz = az, bw = 3;
                  (void)bx;
                  const double cx = bw / 2 - ax + ax * ax - 1, cy = bz / 2 - ax + ay * ay - 1,
                               cz = by / 2 - ax + az * az - 1;
                  return V3{-cx, -cy * 2, -cz * 0.5};
                });
}

TEST(GlslFrontEnd, FunctionsConstantsGlobalsAndOutParameters) {
  expect_values(R"(
const float K = 2.0;
float g = 0.25;
float twice(float x) { return K * x; }
void split(in vec2 p, out float s, inout float acc) { s = p.x + p.y; acc += s; }
vec2 rot(vec2 p) { return vec2(-p.y, p.x); }
vec3 shade(vec2 uv, float time) {
  float s, acc = g;
  split(rot(uv), s, acc);
  split(uv, s, acc);
  return vec3(twice(s), acc, twice(twice(time)));
})",
                [](double u, double v, double t) {
                  const double s1 = -v + u, s2 = u + v;
                  return V3{2 * s2, 0.25 + s1 + s2, 4 * t};
                });
}

TEST(GlslFrontEnd, LoopsUnrollWithBreakAndContinue) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  float a = 0.0;
  for (int i = 0; i < 5; i++) {
    if (i == 1) continue;          // constant condition
    if (float(i) > uv.x + 3.0) break;  // traced condition: masks the rest
    a += float(i) * uv.y;
  }
  int j = 0;
  float b = 0.0;
  while (j < 3) { b += uv.x; j += 1; }
  do { b *= 0.5; j--; } while (j > 1);
  float c = 0.0;
  for (float x = 0.0; x < 1.0; x += 0.25) {
    if (uv.y > x * 4.0 - 2.0) continue;
    c += 1.0;
  }
  return vec3(a, b, c);
})",
                [](double u, double v, double) {
                  double a = 0;
                  for (int i = 0; i < 5; i++) {
                    if (i == 1) continue;
                    if (i > u + 3) break;
                    a += i * v;
                  }
                  double b = 3 * u * 0.5 * 0.5;
                  double c = 0;
                  for (double x = 0; x < 1; x += 0.25)
                    if (!(v > x * 4 - 2)) c += 1;
                  return V3{a, b, c};
                });
}

// Nested loops after a traced break or continue of the outer loop: the inner loop's counter is
// declared in the outer body (written unmasked, so it stays constant and the loop unrolls), and
// lanes that left the outer loop do not run the inner one.
TEST(GlslFrontEnd, InnerLoopsAfterATracedBreakOfTheOuterLoop) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  float acc = 0.0, hits = 0.0;
  for (int i = 0; i < 4; i++) {
    if (uv.x < float(i) - 1.5) break;
    if (uv.y < float(i) - 2.0) continue;
    for (int j = 0; j < 3; j++) {
      float t = float(i * 3 + j);
      if (uv.y > t * 0.5 - 2.0) break;
      acc += t;
    }
    hits += 1.0;
  }
  return vec3(acc, hits, 0.0);
})",
                [](double u, double v, double) {
                  double acc = 0, hits = 0;
                  for (int i = 0; i < 4; i++) {
                    if (u < i - 1.5) break;
                    if (v < i - 2.0) continue;
                    for (int j = 0; j < 3; j++) {
                      const double t = i * 3 + j;
                      if (v > t * 0.5 - 2) break;
                      acc += t;
                    }
                    hits += 1;
                  }
                  return V3{acc, hits, 0};
                });
}

TEST(GlslFrontEnd, BranchesSelectsAndEarlyReturn) {
  expect_values(R"(
float f(float x) {
  if (x < 0.0) return -1.0;
  if (x > 1.0) { return 2.0; } else { x *= 3.0; }
  return x;
}
vec3 shade(vec2 uv, float time) {
  float r = uv.x > 0.5 ? uv.y : -uv.y;
  vec2 p = uv;
  if (uv.y < 0.0 && uv.x < 1.0) { p.x = 5.0; p.y += 1.0; }
  else if (!(uv.y < 1.0) || uv.x >= 2.0) p = vec2(7.0);
  bool on = uv.x <= uv.y;
  if (on) return vec3(r, p.x + f(uv.x), p.y);
  return vec3(f(uv.y), p);
})",
                [](double u, double v, double) {
                  auto f = [](double x) { return x < 0 ? -1.0 : x > 1 ? 2.0 : 3 * x; };
                  const double r = u > 0.5 ? v : -v;
                  double px = u, py = v;
                  if (v < 0 && u < 1)
                    px = 5, py += 1;
                  else if (!(v < 1) || u >= 2)
                    px = py = 7;
                  if (u <= v) return V3{r, px + f(u), py};
                  return V3{f(v), px, py};
                });
}

TEST(GlslFrontEnd, BuiltInsWithTracedArguments) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  float x = uv.x, y = uv.y;
  float a = sin(x) + cos(y) + tan(x * 0.3) + exp(y * 0.2) + log(x * x + 1.0) + exp2(y * 0.5) +
            log2(abs(x) + 1.0) + sqrt(abs(y)) + inversesqrt(x * x + 2.0);
  float b = pow(abs(x) + 0.5, 3.0) + pow(abs(y) + 0.5, 2.5) + pow(abs(x) + 1.0, -2.0) + pow(abs(y) + 1.0, abs(x)) +
            sign(x) + floor(y) + ceil(x) + fract(y) + trunc(x) + mod(x, 1.5) + mod(y, abs(x) + 0.5);
  float c = min(x, y) + max(x, 0.2) + clamp(x, -1.0, 0.5) + clamp(y, x, x + 1.0) + mix(x, y, 0.3) +
            step(0.1, x) + smoothstep(-1.0, 2.0, y) + smoothstep(x, x + 2.0, y);
  vec3 p = vec3(x, y, 1.0), q = vec3(y, 0.5, x);
  vec3 n = normalize(p) + cross(p, q);
  float d = length(uv) + distance(uv, vec2(1.0, -1.0)) + dot(p, q) + length(x);
  return vec3(a, b + d, c + n.x + 2.0 * n.y + 3.0 * n.z) + mix(p, q, vec3(0.1, 0.2, time));
})",
                [](double x, double y, double t) {
                  const double a = std::sin(x) + std::cos(y) + std::tan(x * 0.3) + std::exp(y * 0.2) +
                                   std::log(x * x + 1) + std::exp2(y * 0.5) + std::log2(std::fabs(x) + 1) +
                                   std::sqrt(std::fabs(y)) + 1 / std::sqrt(x * x + 2);
                  const auto mod = [](double a, double b) { return a - b * std::floor(a / b); };
                  const double b = std::pow(std::fabs(x) + 0.5, 3) + std::pow(std::fabs(y) + 0.5, 2.5) +
                                   std::pow(std::fabs(x) + 1, -2) + std::pow(std::fabs(y) + 1, std::fabs(x)) +
                                   (x > 0 ? 1 : -1) + std::floor(y) + std::ceil(x) + fract(y) +
                                   std::trunc(x) + mod(x, 1.5) + mod(y, std::fabs(x) + 0.5);
                  const double c = std::min(x, y) + std::max(x, 0.2) + std::clamp(x, -1.0, 0.5) +
                                   std::clamp(y, x, x + 1) + (x + (y - x) * 0.3) + (x >= 0.1 ? 1 : 0) +
                                   smooth01((y + 1) / 3) + smooth01((y - x) / 2);
                  const double px = x, py = y, pz = 1, qx = y, qy = 0.5, qz = x;
                  const double len = std::sqrt(px * px + py * py + pz * pz);
                  const double nx = px / len + (py * qz - pz * qy), ny = py / len + (pz * qx - px * qz),
                               nz = pz / len + (px * qy - py * qx);
                  const double d = std::hypot(x, y) + std::hypot(x - 1, y + 1) +
                                   (px * qx + py * qy + pz * qz) + std::fabs(x);
                  return V3{a + px + (qx - px) * 0.1, b + d + py + (qy - py) * 0.2,
                            c + nx + 2 * ny + 3 * nz + pz + (qz - pz) * t};
                },
                5e-5);
}

// Matrices as GLSL lays them out (column-major: mat2(a, b, c, d) has columns (a, b) and (c, d)), the
// references written out by hand from the GLSL specification's definitions.
TEST(GlslFrontEnd, MatricesMultiplyColumnMajor) {
  expect_values(R"(
mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
vec3 shade(vec2 uv, float time) {
  vec2 p = rot(0.5 + time) * uv;       // matrix * column vector
  vec2 q = uv * rot(0.3);              // row vector * matrix: the transpose's product
  mat2 m = rot(0.2) * mat2(1.0, 2.0, 3.0, 4.0);
  m += mat2(uv.x);                     // uv.x on the diagonal
  m = m * 0.5 - mat2(0.0, 1.0, 0.0, 0.0);
  vec2 r = uv;
  r *= rot(-0.4);                      // vector *= matrix
  m *= rot(0.1);                       // matrix *= matrix
  m[1][0] += uv.y;                     // column 1, row 0
  m[0] = m[0].yx;
  return vec3(p.x + 2.0 * q.y, m[0][0] + 3.0 * m[0][1] + 5.0 * m[1][0] + 7.0 * m[1][1], r.x - r.y + p.y);
})",
                [](double u, double v, double t) {
                  // rot(a) has columns (c, s) and (-s, c): M v = (c x - s y, s x + c y).
                  using M2 = std::array<double, 4>;  // column-major
                  const auto rot = [](double a) {
                    return M2{std::cos(a), std::sin(a), -std::sin(a), std::cos(a)};
                  };
                  const auto mv = [](const M2& m, double x, double y) {
                    return std::array<double, 2>{m[0] * x + m[2] * y, m[1] * x + m[3] * y};
                  };
                  const auto vm = [](double x, double y, const M2& m) {  // (v . column 0, v . column 1)
                    return std::array<double, 2>{x * m[0] + y * m[1], x * m[2] + y * m[3]};
                  };
                  const auto mm = [](const M2& a, const M2& b) {
                    return M2{a[0] * b[0] + a[2] * b[1], a[1] * b[0] + a[3] * b[1], a[0] * b[2] + a[2] * b[3],
                              a[1] * b[2] + a[3] * b[3]};
                  };
                  const auto p = mv(rot(0.5 + t), u, v);
                  const auto q = vm(u, v, rot(0.3));
                  M2 m = mm(rot(0.2), M2{1, 2, 3, 4});
                  m[0] += u;
                  m[3] += u;
                  for (double& e : m) e *= 0.5;
                  m[1] -= 1;
                  const auto r = vm(u, v, rot(-0.4));
                  m = mm(m, rot(0.1));
                  m[2] += v;
                  std::swap(m[0], m[1]);
                  return V3{p[0] + 2 * q[1], m[0] + 3 * m[1] + 5 * m[2] + 7 * m[3], r[0] - r[1] + p[1]};
                });
}

TEST(GlslFrontEnd, MatrixConstructorsAndBuiltIns) {
  expect_values(
      R"(
vec3 shade(vec2 uv, float time) {
  mat3 m = mat3(vec3(2.0, uv.x, 0.5), vec3(0.25, 3.0, uv.y), 1.0, 0.5, 4.0);  // columns, then scalars
  mat2 a = mat2(m);                    // upper-left 2x2
  mat3 b = mat3(a);                    // a, the identity elsewhere
  mat2x3 n = mat2x3(1.0, 0.5, -0.5, 0.25, 1.0, 0.75);  // 2 columns of 3 rows
  vec3 o = n * uv + outerProduct(vec3(1.0, 2.0, 3.0), vec2(0.1, 0.2))[1];
  mat3 i = inverse(m);
  mat2 c = matrixCompMult(a, mat2(1.0, 2.0, 3.0, 4.0));
  mat3 tr = transpose(m);
  float d = determinant(m) + determinant(a);
  return vec3(i[0][1] + 2.0 * i[2][0] + 3.0 * i[1][2] + d, b[2][2] + 2.0 * b[0][1] + c[1][0] + tr[0][1],
              o.x + 2.0 * o.y + 3.0 * o.z + (m * i)[1][1]);
})",
      [](double u, double v, double) {
        // m's columns: (2, u, 0.5), (0.25, 3, v), (1, 0.5, 4); M[r][c] row-major here.
        const double M[3][3] = {{2, 0.25, 1}, {u, 3, 0.5}, {0.5, v, 4}};
        const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                           M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                           M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
        // The inverse by Cramer's rule: inv[r][c] = cofactor(c, r) / det.
        const auto cof = [&](int r, int c) {
          int rs[2], cs[2], k = 0, l = 0;
          for (int i = 0; i < 3; ++i) {
            if (i != r) rs[k++] = i;
            if (i != c) cs[l++] = i;
          }
          const double mnr = M[rs[0]][cs[0]] * M[rs[1]][cs[1]] - M[rs[0]][cs[1]] * M[rs[1]][cs[0]];
          return (r + c) % 2 ? -mnr : mnr;
        };
        const auto inv = [&](int r, int c) { return cof(c, r) / det; };
        // GLSL i[col][row]: i[0][1] = inv row 1 col 0, i[2][0] = row 0 col 2, i[1][2] = row 2 col 1.
        const double x = inv(1, 0) + 2 * inv(0, 2) + 3 * inv(2, 1) + det + (2 * 3 - 0.25 * u);
        // b = mat3(a): b[2][2] = 1, b[0][1] = a row 1 col 0 = u; c[1][0] = a(row 0, col 1) * 3 = 0.75;
        // transpose(m)[0][1] = m[1][0] = 0.25.
        const double y = 1 + 2 * u + 0.25 * 3 + 0.25;
        // n's columns (1, 0.5, -0.5), (0.25, 1, 0.75); outerProduct(c, r)[1] = c * r[1] = c * 0.2.
        const double o[3] = {1 * u + 0.25 * v + 0.2, 0.5 * u + 1 * v + 0.4, -0.5 * u + 0.75 * v + 0.6};
        return V3{x, y, o[0] + 2 * o[1] + 3 * o[2] + 1};  // (m * inverse(m))[1][1] = 1
      },
      1e-4);
}

// A traced (whole-number) index reads and writes the element it names; out of range it reads the
// nearest end (GLSL leaves that undefined).
TEST(GlslFrontEnd, TracedIndicesPickTheElementTheyName) {
  expect_values(
      R"(
const vec3 palette[4] = vec3[](vec3(0.9, 0.1, 0.1), vec3(0.1, 0.8, 0.2), vec3(0.2, 0.3, 0.9), vec3(0.7, 0.7, 0.1));
vec3 shade(vec2 uv, float time) {
  int i = int(mod(floor(uv.x), 4.0));
  float a[3] = float[](10.0, 20.0, 30.0);
  int j = int(clamp(floor(uv.y + 1.0), 0.0, 2.0));
  a[j] = uv.x;
  a[2 - j] += 5.0;
  vec4 v = vec4(uv, 7.0, 8.0);
  int k = int(floor(uv.y)) + 1;                 // -2 .. 3: the ends read v[0] and v[3]
  return palette[i] + vec3(a[0], a[1] + 100.0 * a[2], v[k]);
})",
      [](double u, double v, double) {
        const double pal[4][3] = {{0.9, 0.1, 0.1}, {0.1, 0.8, 0.2}, {0.2, 0.3, 0.9}, {0.7, 0.7, 0.1}};
        const int i = static_cast<int>(std::fmod(std::fmod(std::floor(u), 4.0) + 4.0, 4.0));
        double a[3] = {10, 20, 30};
        const int j = static_cast<int>(std::clamp(std::floor(v + 1), 0.0, 2.0));
        a[j] = u;
        a[2 - j] += 5;
        const double vv[4] = {u, v, 7, 8};
        const int k = std::clamp(static_cast<int>(std::floor(v)) + 1, 0, 3);
        return V3{pal[i][0] + a[0], pal[i][1] + a[1] + 100 * a[2], pal[i][2] + vv[k]};
      },
      1e-5);
}

// A traced index inside an assignment target: a[i].x = y, m[i][j] += y, s.items[i].w++ write every
// element the index may name, each where the index names it.
TEST(GlslFrontEnd, TracedIndicesInsideAssignmentTargets) {
  expect_values(
      R"(
struct Item { float w; vec2 p; };
struct Bag { Item items[3]; };
vec3 shade(vec2 uv, float time) {
  vec2 a[3] = vec2[](vec2(1.0, 2.0), vec2(3.0, 4.0), vec2(5.0, 6.0));
  int i = int(clamp(floor(uv.x + 1.5), 0.0, 2.0));
  a[i].x = uv.y;
  mat2 m = mat2(1.0);
  int j = int(clamp(floor(uv.y + 1.0), 0.0, 1.0));
  m[j][1 - j] += 10.0 * uv.x;
  Bag b = Bag(Item[3](Item(0.5, vec2(0.0)), Item(1.5, vec2(1.0)), Item(2.5, vec2(2.0))));
  b.items[i].w++;
  b.items[2 - i].p.y -= 3.0;
  return vec3(a[0].x + 10.0 * a[1].x + 100.0 * a[2].x + a[i].y, m[0][1] + 2.0 * m[1][0] + m[0][0],
              b.items[0].w + 2.0 * b.items[1].w + 4.0 * b.items[2].w + b.items[1].p.y);
})",
      [](double u, double v, double) {
        double a[3][2] = {{1, 2}, {3, 4}, {5, 6}};
        const int i = static_cast<int>(std::clamp(std::floor(u + 1.5), 0.0, 2.0));
        a[i][0] = v;
        double m[2][2] = {{1, 0}, {0, 1}};  // m[column][row]
        const int j = static_cast<int>(std::clamp(std::floor(v + 1), 0.0, 1.0));
        m[j][1 - j] += 10 * u;
        double w[3] = {0.5, 1.5, 2.5}, py[3] = {0, 1, 2};
        w[i] += 1;
        py[2 - i] -= 3;
        return V3{a[0][0] + 10 * a[1][0] + 100 * a[2][0] + a[i][1], m[0][1] + 2 * m[1][0] + m[0][0],
                  w[0] + 2 * w[1] + 4 * w[2] + py[1]};
      },
      1e-5);
}

// int() of a whole number (a floor, a step, their sums and products) is the number itself: no trunc
// node on top of the floor (one jump to smooth, not two); of anything else it is trunc.
TEST(GlslFrontEnd, IntOfAWholeNumberIsItself) {
  const glsl::Pattern p = trace(R"(
vec3 shade(vec2 uv, float time) {
  int i = int(floor(uv.x)) + 2 * int(step(0.5, uv.y)) - int(mod(floor(uv.y), 3.0));
  int j = int(uv.x * 0.5);
  return vec3(float(i), float(j), 0.0);
})");
  EXPECT_EQ(count_calls(p.graph, "trunc"), 1);  // j's only
  EXPECT_EQ(count_calls(p.graph, "floor"), 2);
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  int i = int(floor(uv.x)) + 2 * int(step(0.5, uv.y)) - int(mod(floor(uv.y), 3.0));
  int j = int(uv.x * 0.5);
  return vec3(float(i), float(j), 0.0);
})",
                [](double u, double v, double) {
                  const double m = std::floor(v) - 3 * std::floor(std::floor(v) / 3);
                  return V3{std::floor(u) + 2 * (v >= 0.5 ? 1 : 0) - m, std::trunc(u * 0.5), 0};
                });
}

// atan (the catalog atomic), atan(y, x) in every quadrant, asin and acos, against <cmath>.
TEST(GlslFrontEnd, InverseTrigonometry) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  float a = atan(uv.x * 3.0) + atan(uv.y, uv.x);
  float b = atan(uv.x, -uv.y) + 2.0 * atan(-uv.y * 0.1, uv.x * 10.0);
  float c = asin(uv.x / 3.0) + acos(uv.y / 3.0) + acos(-1.0) + asin(1.0);
  return vec3(a, b, c);
})",
                [](double u, double v, double) {
                  return V3{std::atan(u * 3) + std::atan2(v, u),
                            std::atan2(u, -v) + 2 * std::atan2(-v * 0.1, u * 10),
                            std::asin(u / 3) + std::acos(v / 3) + M_PI + M_PI / 2};
                },
                2e-6);
  const glsl::Pattern p = trace("vec3 shade(vec2 uv, float time) { return vec3(atan(uv.y, uv.x)); }");
  EXPECT_EQ(count_calls(p.graph, "atan"), 1);
}

// asinh (both signs, large |x|), acosh (x >= 1) and atanh (|x| < 1), against <cmath>.
TEST(GlslFrontEnd, InverseHyperbolicFunctions) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  return vec3(asinh(uv.x * 40.0) + asinh(-0.3), acosh(1.0 + uv.y * uv.y), atanh(uv.x / 3.1) + atanh(0.5));
})",
                [](double u, double v, double) {
                  return V3{std::asinh(u * 40) + std::asinh(-0.3), std::acosh(1 + v * v),
                            std::atanh(u / 3.1) + std::atanh(0.5)};
                },
                2e-5);
}

// Structs: members one after another, nested, in arrays, as parameters and return values.
TEST(GlslFrontEnd, StructsCarryTheirMembers) {
  expect_values(R"(
struct Layer { vec2 scale; float weight; mat2 turn; };
struct Stack { Layer layers[2]; vec3 tint; };
Layer make(float s, float w) { return Layer(vec2(s, 2.0 * s), w, mat2(1.0)); }
float apply(Layer l, vec2 uv) { vec2 p = l.turn * (uv * l.scale); return l.weight * (p.x + p.y); }
vec3 shade(vec2 uv, float time) {
  Stack st = Stack(Layer[2](make(1.0, 0.5), make(3.0, 0.25)), vec3(0.1, 0.2, 0.3));
  st.layers[1].turn[0] = vec2(0.0, 1.0);   // column 0 of layer 1's matrix
  st.layers[0].weight += uv.x;
  Layer l = st.layers[1];
  l.scale.y = -1.0;
  bool same = l == st.layers[1];
  return st.tint + vec3(apply(st.layers[0], uv), apply(st.layers[1], uv), apply(l, uv) + float(same));
})",
                [](double u, double v, double) {
                  // layer 0: scale (1, 2), weight 0.5 + u, identity; layer 1: scale (3, 6), weight 0.25,
                  // columns (0, 1) and (0, 1): p = (0, sx + sy) for s = (3u, 6v).
                  const double a0 = (0.5 + u) * (u + 2 * v);
                  const double a1 = 0.25 * (3 * u + 6 * v);
                  const double a2 = 0.25 * (3 * u - v);  // scale (3, -1)
                  return V3{0.1 + a0, 0.2 + a1, 0.3 + a2};
                });
}

// switch on a traced selector (fall-through, default, break) and on a constant one, also with a
// continue of the enclosing loop.
TEST(GlslFrontEnd, SwitchFallsThroughUntilBreak) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  int i = int(mod(floor(uv.x), 4.0));
  float a = 0.0, b = 0.0;
  switch (i) {
    case 0: a = 1.0; break;
    case 1: a = 2.0;          // falls through
    case 2: b = 5.0 + uv.y; break;
    default: a = -1.0; b = -1.0;
  }
  float c = 0.0;
  switch (2) { case 1: c = 10.0; break; case 2: c = 20.0; case 3: c += 1.0; break; default: c = -5.0; }
  for (int k = 0; k < 3; k++) {
    switch (k) { case 1: continue; default: c += 100.0; }
    c += 1000.0;
  }
  return vec3(a, b, c);
})",
                [](double u, double v, double) {
                  const int i = static_cast<int>(std::floor(u) - 4 * std::floor(std::floor(u) / 4));
                  const double a[4] = {1, 2, 0, -1}, b[4] = {0, 5 + v, 5 + v, -1};
                  return V3{a[i], b[i], 2221};
                });
}

// Lanes that left a loop under a traced condition stay out of a switch later in its body: their
// writes there are masked (a break inside the switch ends the switch only).
TEST(GlslFrontEnd, SwitchInsideALoopKeepsItsMasks) {
  expect_values(R"(
vec3 shade(vec2 uv, float time) {
  float b = 0.0, c = 0.0;
  for (int i = 0; i < 3; i++) {
    if (uv.x > float(i) - 1.0) break;       // u > -1 leaves at i = 0, u > 0 at i = 1, ...
    switch (i) { case 0: b += 10.0; break; default: b += 1.0; }
    c += 1.0;
  }
  return vec3(b, c, 0.0);
})",
                [](double u, double, double) {
                  int n = 0;  // iterations before the break
                  while (n < 3 && !(u > n - 1.0)) ++n;
                  return V3{n >= 1 ? 10.0 + (n - 1) : 0.0, double(n), 0.0};
                });
}

TEST(GlslFrontEnd, SineHashAndPreludeAtomics) {
  expect_values(
      R"(
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
vec3 shade(vec2 uv, float time) {
  vec2 cell = floor(uv * 0.5);
  return vec3(hash(cell), triangle(uv.x) + square(uv.y), saturate(uv.x) + pow2(uv.y) + inv(uv.x + 4.0));
})",
      [](double u, double v, double) {
        const double cx = std::floor(u * 0.5), cy = std::floor(v * 0.5);
        // The hash of whole cells: float sin of a whole-number argument, then * 43758.
        // The same float operations the graph runs (the hash amplifies their rounding).
        const float h = static_cast<float>(cx) * 127.1f + static_cast<float>(cy) * 311.7f;
        const float m = std::sin(h) * 43758.5453f;
        const double hash = m - std::floor(m);
        const double tri = std::fabs(u - 2 * std::floor(u / 2) - 1);  // 1 - |t - 1| with t = mod(u,2)
        return V3{hash, (1 - tri) + (fract(v) < 0.5 ? 1 : 0), std::clamp(u, 0.0, 1.0) + v * v + 1 / (u + 4)};
      },
      1e-5);
}

TEST(GlslFrontEnd, GraphsMatchTheDslAndUseTheCatalogAtomics) {
  // The same pattern written in the DSL gives the same graph (structure hash).
  const glsl::Pattern p = trace(R"(
vec3 shade(vec2 uv, float time) {
  return vec3(sin(uv.x * 3.0), fract(uv.y), step(0.5, uv.x) * saturate(time));
})");
  ir::Graph want;
  {
    dsl::Tracer t(want);
    using dsl::Var;
    const Var u = Var::input("u", true), v = Var::input("v", true), time = Var::input("time", false);
    want.add_output("r", dsl::sin(u * 3.0).id());
    want.add_output("g", dsl::fract(v).id());
    const Var edge = dsl::step(u - 0.5);  // GLSL evaluates left to right
    want.add_output("b", (edge * dsl::saturate(time)).id());
  }
  EXPECT_EQ(p.graph.to_string(), want.to_string());
  EXPECT_TRUE(p.uses_time);
  // pow with a constant integer exponent -> powN; x * x -> pow2; clamp(x, 0, 1) -> saturate; general
  // pow -> exp(y log x); a user function is inlined, a prelude one is the atomic.
  const glsl::Pattern q = trace(R"(
float sq(float x) { return x * x; }
vec3 shade(vec2 uv, float time) {
  return vec3(pow(uv.x, 3.0) + pow(uv.y, 12.0), sq(uv.y) + clamp(uv.x, 0.0, 1.0), pow(uv.x, uv.y) + triangle(uv.y));
})");
  EXPECT_EQ(count_calls(q.graph, "pow3"), 1);
  EXPECT_EQ(count_calls(q.graph, "pow8"), 1);
  EXPECT_EQ(count_calls(q.graph, "pow4"), 1);
  EXPECT_EQ(count_calls(q.graph, "pow2"), 1);
  EXPECT_EQ(count_calls(q.graph, "saturate"), 1);
  EXPECT_EQ(count_calls(q.graph, "triangle"), 1);
  EXPECT_EQ(count_calls(q.graph, "exp"), 1);
  EXPECT_EQ(count_calls(q.graph, "log"), 1);
  EXPECT_FALSE(q.uses_time);
  // A constant condition leaves no select; a traced one merges with exactly one per changed value.
  const glsl::Pattern s = trace(R"(
vec3 shade(vec2 uv, float time) {
  vec3 c = vec3(0.5);
  if (1.0 > 2.0) c = vec3(uv, 1.0);
  if (uv.x < 0.3) c = vec3(1.0, 0.0, 0.25);
  return c;
})");
  int selects = 0;
  for (const auto& n : s.graph.nodes()) selects += n.op == ir::Op::Select;
  EXPECT_EQ(selects, 3);
}

TEST(GlslFrontEnd, ErrorsNameFileLineAndColumn) {
  // Syntax: glslang's message with file:line.
  EXPECT_NE(error_of("vec3 shade(vec2 uv, float time) {\n  float a = 1.0\n  return vec3(a);\n}\n", "my.glsl")
                .find("my.glsl:3:"),
            std::string::npos);
  const std::string head = "vec3 shade(vec2 uv, float time) {\n";
  struct Case {
    std::string body, want;
  };
  const Case cases[] = {
      {"  if (uv.x < 0.0) discard;\n  return vec3(0.0);\n}\n", "test.glsl:2:19: unsupported discard"},
      {"  float a = 0.0;\n  for (int i = 0; float(i) < uv.x; i++) a += 1.0;\n  return vec3(a);\n}\n",
       "test.glsl:3:28: unsupported loop with a variable bound"},
      {"  int i = int(uv.x);\n  return vec3(float(i % 3));\n}\n",
       "test.glsl:3:23: unsupported integer modulo"},
      {"  int i = int(uv.x);\n  return vec3(float(i & 3));\n}\n", "test.glsl:3:23: unsupported integer bit"},
      {"  return vec3(dFdx(uv.x));\n}\n", "test.glsl:2:23: unsupported screen-space derivatives"},
      {"  dmat2 m = dmat2(1.0);\n  return vec3(float(m[0][0]));\n}\n", "unsupported double precision"},
  };
  for (const auto& c : cases)
    EXPECT_NE(error_of(head + c.body).find(c.want), std::string::npos) << error_of(head + c.body);
  EXPECT_NE(error_of("void set1(out float x) { x = 1.0; }\n" + head +
                     "  float a[3] = float[](1.0, 2.0, 3.0);\n  int i = int(uv.x);\n  set1(a[i]);\n"
                     "  return vec3(a[1]);\n}\n")
                .find("test.glsl:5:10: unsupported traced index in an out or inout argument"),
            std::string::npos);
  EXPECT_NE(error_of("float f(float x) { return x < 0.0 ? 0.0 : f(x - 1.0); }\n" + head +
                     "  return vec3(f(uv.x));\n}\n")
                .find("test.glsl:1:52: unsupported recursion ('f' calls itself)"),
            std::string::npos)
      << error_of("float f(float x) { return x < 0.0 ? 0.0 : f(x - 1.0); }\n" + head +
                  "  return vec3(f(uv.x));\n}\n");
  EXPECT_NE(error_of("uniform sampler3D vol;\n" + head + "  return texture(vol, vec3(uv, 0.0)).rgb;\n}\n")
                .find("test.glsl:3:"),
            std::string::npos);
  EXPECT_NE(error_of("uniform float k;\n" + head + "  return vec3(k);\n}\n")
                .find("test.glsl:3:15: unsupported uniform 'k'"),
            std::string::npos)
      << error_of("uniform float k;\n" + head + "  return vec3(k);\n}\n");
  // shade missing or mis-typed.
  EXPECT_NE(
      error_of("vec3 colour(vec2 uv) { return vec3(uv, 0.0); }\n").find("test.glsl: no function vec3 shade"),
      std::string::npos);
  EXPECT_NE(error_of("\nvec3 shade(vec2 uv) { return vec3(uv, 0.0); }\n").find("test.glsl:2:"),
            std::string::npos);
  EXPECT_NE(
      error_of("vec4 shade(vec2 uv, float time) { return vec4(uv, 0.0, 1.0); }\n").find("shade returns"),
      std::string::npos);
}

TEST(GlslFrontEnd, TextureSlotsTrace) {
  const glsl::Pattern p = trace(R"(
uniform sampler2D albedo;
vec3 shade(vec2 uv, float time) { return texture(albedo, uv * 2.0).rgb * 0.5; })");
  ASSERT_EQ(p.textures, std::vector<std::string>{"albedo"});
  int lookups = 0;
  for (const auto& n : p.graph.nodes()) lookups += n.op == ir::Op::Texture;
  EXPECT_EQ(lookups, 3);
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// ir::Graph folds a select of constants as the lowering computes it: c a + (1 - c) b.
TEST(GlslFrontEnd, ConstantSelectFoldsToTheChosenValue) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var r = dsl::select(dsl::Var(1.0), dsl::Var(2.0), dsl::Var(3.0));
  const dsl::Var s = dsl::select(dsl::Var(0.0), dsl::Var(2.0), dsl::Var(3.0));
  EXPECT_EQ(g.node(r.id()).op, ir::Op::Const);
  EXPECT_EQ(g.node(r.id()).value, 2.0);
  EXPECT_EQ(g.node(s.id()).value, 3.0);
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// The DSL's vector and variable-edge helpers trace to what the GLSL front end produces.
TEST(GlslFrontEnd, DslVariableEdgesAndVectorsMatchTheFrontEnd) {
  const glsl::Pattern p = trace(R"(
vec3 shade(vec2 uv, float time) {
  vec2 f = fract(uv) + floor(uv);
  return vec3(smoothstep(uv.x, uv.y, time) + clamp(time, uv.x, uv.y), mod(uv.x, uv.y) + length(f),
              mix(uv, f, time).y);
})");
  ir::Graph want;
  {
    dsl::Tracer t(want);
    using dsl::Var;
    const Var u = Var::input("u", true), v = Var::input("v", true), time = Var::input("time", false);
    const dsl::Vec2<Var> uv{u, v};
    const dsl::Vec2<Var> fr = dsl::fract(uv), fl = dsl::floor(uv);
    const dsl::Vec2<Var> f = fr + fl;
    const Var s = dsl::smoothstep(u, v, time);
    const Var r = s + dsl::clamp(time, u, v);
    const Var m = dsl::mod(u, v);
    const Var g = m + dsl::length(f);
    const Var b = dsl::mix(uv, f, time).y;
    want.add_output("r", r.id());
    want.add_output("g", g.id());
    want.add_output("b", b.id());
  }
  // Values agree (node order may differ with evaluation order): evaluate both natively.
  const glsl::NativeProgram a(p.graph), b(want);
  for (float u : {-1.3f, 0.2f, 2.7f})
    for (float v : {-0.6f, 1.1f, 3.4f}) {
      float x[3], y[3];
      a.run(u, v, 0.4f, nullptr, x);
      b.run(u, v, 0.4f, nullptr, y);
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(x[k], y[k]) << k << " " << u << " " << v;
    }
  // Float instantiations compile and agree with GLSL's definitions.
  EXPECT_FLOAT_EQ(dsl::mod(-1.25f, 0.5f + 0.25f), 0.25f);
  EXPECT_FLOAT_EQ(dsl::clamp(3.0f, 0.5f, 2.0f), 2.0f);
  EXPECT_FLOAT_EQ(dsl::smoothstep(1.0f, 3.0f, 2.0f), 0.5f);
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// return inside an unrolled loop under a traced condition: the first hit wins, later code is masked.
TEST(GlslFrontEnd, ReturnInsideALoopUnderATracedCondition) {
  expect_values(R"(
vec3 hit(vec2 p) {
  for (int i = 0; i < 4; i++) {
    float r = 0.5 + float(i);
    if (length(p) < r) return vec3(float(i), r, p.x);
    p *= 0.9;
  }
  return vec3(-1.0, 0.0, p.y);
}
vec3 shade(vec2 uv, float time) { return hit(uv); })",
                [](double u, double v, double) {
                  double px = u, py = v;
                  for (int i = 0; i < 4; i++) {
                    const double r = 0.5 + i;
                    if (std::hypot(px, py) < r) return V3{double(i), r, px};
                    px *= 0.9, py *= 0.9;
                  }
                  return V3{-1, 0, py};
                });
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// A while loop whose counter is updated after a conditional return still unrolls; a global and an
// out parameter written after that return keep their value in the lanes that returned.
TEST(GlslFrontEnd, WhileLoopWithAnEarlyReturn) {
  expect_values(R"(
float g = 0.0;
float first_below(float x, out float steps) {
  int j = 0;
  steps = 0.0;
  while (j < 4) {
    if (x < float(j) - 1.0) return float(j);
    j += 1;
    g += 1.0;
    steps += 1.0;
  }
  return -1.0;
}
vec3 shade(vec2 uv, float time) {
  float steps;
  float k = first_below(uv.x, steps);
  return vec3(k, steps, g);
})",
                [](double u, double, double) {
                  double steps = 0, g = 0;
                  for (int j = 0; j < 4; ++j) {
                    if (u < j - 1.0) return V3{double(j), steps, g};
                    g += 1, steps += 1;
                  }
                  return V3{-1, steps, g};
                });
}

}  // namespace
}  // namespace bl
