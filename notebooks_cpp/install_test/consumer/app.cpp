// Consumer of the installed package: calls the table in float and double and finds the GLSL file
// through the path the package exports. Exits non-zero on anything unexpected.
#include <bandlimit/registry.hpp>
#include <bandlimit/table.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

int main() {
  int bad = 0;
  // sigma = 0 returns f(x); a wide Gaussian averages fract to 1/2 (true for any x).
  const double f0 = bl::gaussian::fract(2.25, 0.0);
  const double wide = bl::gaussian::fract(0.1, 3.0);
  const float ff = bl::tent::fract(0.25f, 0.05f);
  std::printf(
      "gaussian::fract(2.25, 0) = %.17g\ngaussian::fract(0.1, 3) = %.17g\ntent::fract(0.25f, 0.05f) = %.9g\n",
      f0, wide, ff);
  bad += f0 != 0.25;
  bad += std::fabs(wide - 0.5) > 1e-12;
  bad += !(ff > 0.0f && ff < 1.0f);
  const size_t n = sizeof(bl::registry::kAtomics) / sizeof(bl::registry::kAtomics[0]);
  std::printf("registry atomics: %zu\n", n);
  bad += n == 0;
  std::ifstream glsl(BANDLIMIT_GLSL);
  std::stringstream text;
  text << glsl.rdbuf();
  const bool has = text.str().find("bl_gaussian_fract(") != std::string::npos;
  std::printf("GLSL include %s: %s\n", BANDLIMIT_GLSL, has ? "found, defines bl_gaussian_fract" : "MISSING");
  bad += !has;
  return bad ? 1 : 0;
}
