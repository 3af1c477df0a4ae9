// bandlimit runtime support, GLSL (float). Copied verbatim into the generated GLSL include by
// `rulegen emit`. The same routines, with the same stability tricks, as support.hpp (read the
// comments there); this file has no #version line: the includer supplies `#version 450` or
// `#version 320 es` (with `precision highp float;`). Valid in both.
//
// Conventions: sigma is the kernel's standard deviation (Gaussian N(0, sigma^2), box U[-h, h] with
// h = sqrt(3) sigma, tent on [-w, w] with w = sqrt(6) sigma); kernel(x, sigma) = E[f(x + U)];
// sigma == 0 returns f(x), right-continuous at a jump. A piece is sum_k c[k] t^k on [lo, hi) in the
// absolute coordinate t. Infinity is the sentinel 1.0e30: |lo| >= 1.0e30 means an infinite end.
// Piecewise routines take `int n, BlPiece p[4]` (n <= 4 pieces; unused entries are ignored).
//
// Written in the subset of GLSL that is also C++ (no array constructors, no swizzles beyond
// vec2 .x/.y, `out` only on arrays, no `const` on computed locals): the test suite compiles this
// file as C++ float code and runs it against the same references as support.hpp.

struct BlPiece {
  float lo;
  float hi;
  float c[8];
};

const float BL_INF = 1.0e30;
const float BL_PI = 3.14159265358979;
const float BL_INV_SQRT2 = 0.707106781186548;
const float BL_INV_SQRT_2PI = 0.398942280401433;
const float BL_SQRT3 = 1.73205080756888;
const float BL_SQRT6 = 2.44948974278318;
const float BL_LN2 = 0.693147180559945;
const float BL_SERIES_TOL = 1.0e-8;  // series_tol<float>()
const float BL_ZMAX = 40.0;          // phi(40) and Phic(40) are 0 in float
const float BL_TAIL_CUT = 9.0;       // tail_cut<float>(): a break beyond 9 sd is taken at 9 sd

bool bl_is_inf(float v) { return abs(v) >= BL_INF; }

// Highest index with a nonzero coefficient (loops stop there: no 0 * overflow).
// Loops here and below run a constant trip count with the bound as a guard, so a GPU compiler can
// unroll them and keep every array in registers (NVIDIA rejects large inlined programs whose arrays
// are indexed at run time: C5041, docs/gpu_timing.md).
int bl_degree(float c[8]) {
  int d = 0;
  for (int k = 1; k < 8; ++k)
    if (c[k] != 0.0) d = k;
  return d;
}

// Horner.
float bl_poly(float c[8], float t) {
  float r = c[7];
  for (int k = 6; k >= 0; --k) r = r * t + c[k];
  return r;
}

// erfc with relative error < 1.2e-7 on the whole line (Numerical Recipes' Chebyshev fit of
// erfc(z) e^{z^2}): GLSL has no erfc, and this keeps the Gaussian tails relatively accurate.
float bl_erfc(float x) {
  float z = min(abs(x), 10.0);  // erfc(10) = 2e-45: 0 in float
  float t = 1.0 / (1.0 + 0.5 * z);
  float r = t * exp(-z * z - 1.26551223 +
                    t * (1.00002368 +
                         t * (0.37409196 +
                              t * (0.09678418 +
                                   t * (-0.18628806 +
                                        t * (0.27886807 +
                                             t * (-1.13520398 +
                                                  t * (1.48851587 +
                                                       t * (-0.82215223 + t * 0.17087277)))))))));
  return x >= 0.0 ? r : 2.0 - r;
}

float bl_phi(float z) {
  float a = min(abs(z), BL_ZMAX);
  return BL_INV_SQRT_2PI * exp(-0.5 * a * a);
}
// Both tails through erfc of the small side.
float bl_Phi(float z) { return 0.5 * bl_erfc(-z * BL_INV_SQRT2); }
float bl_Phic(float z) { return 0.5 * bl_erfc(z * BL_INV_SQRT2); }
// phi(t) and Phic(t), t >= 0 (support.hpp: phi_Phic), one pair per break in the generated entries.
void bl_phi_Phic(float t, out float ph, out float pc) {
  ph = bl_phi(t);
  pc = bl_Phic(t);
}
// J_1(t) = phi(t) - t Phic(t), t >= 0 (normal_fast.hpp: normal_J1): a kink's break term.
float bl_J1(float t) { return bl_phi(t) - t * bl_Phic(t); }

// sin(t)/t: series for |t| < 1 (GPU sin has an absolute, not relative, error bound), quotient
// beyond.
float bl_sinc(float t) {
  float a = abs(t);
  if (a < 1.0) {
    float t2 = t * t;
    return 1.0 +
           t2 * (-1.0 / 6.0 +
                 t2 * (1.0 / 120.0 +
                       t2 * (-1.0 / 5040.0 + t2 * (1.0 / 362880.0 + t2 * (-1.0 / 39916800.0)))));
  }
  return sin(t) / t;
}

// sinh(t)/t: series for |t| < 1 (GPU sinh cancels near 0), quotient up to 20, then
// exp(|t| - log 2|t|) (overflows to +inf only when the true value does).
float bl_sinhc(float t) {
  float a = abs(t);
  if (a < 1.0) {
    float t2 = t * t;
    return 1.0 +
           t2 * (1.0 / 6.0 +
                 t2 * (1.0 / 120.0 +
                       t2 * (1.0 / 5040.0 + t2 * (1.0 / 362880.0 + t2 * (1.0 / 39916800.0)))));
  }
  if (a < 20.0) return sinh(a) / a;
  return exp(a - log(2.0 * a));
}

// exp(u) sinhc(v), v >= 0, merged exponent for v > 1 (no inf * 0).
float bl_exp_sinhc(float u, float v) {
  float a = abs(v);
  if (a <= 1.0) return exp(u) * bl_sinhc(a);
  return exp(u + a - log(2.0 * a)) * (1.0 - exp(-2.0 * a));
}

// exp(u) sinhc(v)^2, merged exponent for v > 1.
float bl_exp_sinhc2(float u, float v) {
  float a = abs(v);
  if (a <= 1.0) {
    float s = bl_sinhc(a);
    return exp(u) * s * s;
  }
  float e = 1.0 - exp(-2.0 * a);
  return exp(u + 2.0 * a - 2.0 * log(2.0 * a)) * e * e;
}

// log(1 + u) for u >= 0: series below 0.05 (GLSL has no log1p).
float bl_log1p(float u) {
  if (u < 0.05) return u * (1.0 - u * (0.5 - u * (1.0 / 3.0 - u * (0.25 - u * 0.2))));
  return log(1.0 + u);
}

// log(cosh x): log1p(2 sinh^2(x/2)) for |x| < 1, |x| + log1p(e^{-2|x|}) - log 2 beyond.
float bl_logcosh(float x) {
  float a = abs(x);
  if (a < 1.0) {
    float s = 0.5 * a * bl_sinhc(0.5 * a);
    return bl_log1p(2.0 * s * s);
  }
  return a + bl_log1p(exp(-2.0 * a)) - BL_LN2;
}

// Taylor coefficients g[k] = q^(k)(t0)/k! by repeated synthetic division.
void bl_taylor_shift(float c[8], int deg, float t0, out float g[8]) {
  for (int k = 0; k < 8; ++k) g[k] = c[k];
  for (int i = 0; i < 7; ++i)
    for (int j = 6; j >= 0; --j)
      if (i < deg && j >= i && j < deg) g[j] += t0 * g[j + 1];
}

// bl_poly of scalar coefficients c0..c7 (Horner, the same order).
float bl_horner8(float t, float c0, float c1, float c2, float c3, float c4, float c5, float c6, float c7) {
  return ((((((c7 * t + c6) * t + c5) * t + c4) * t + c3) * t + c2) * t + c1) * t + c0;
}

// One Gauss-Legendre node pair of bl_gauss_core_s: the piece's polynomial times phi at mid +- hr n.
float bl_gl_pair8(float mid, float hr, float cz, float hw, float n, float c0, float c1, float c2,
                  float c3, float c4, float c5, float c6, float c7) {
  return bl_horner8(mid + hr * n, c0, c1, c2, c3, c4, c5, c6, c7) * bl_phi(cz + hw * n) +
         bl_horner8(mid - hr * n, c0, c1, c2, c3, c4, c5, c6, c7) * bl_phi(cz - hw * n);
}

// Gaussian integral of one piece on offsets (see gauss_core in support.hpp): 20-point
// Gauss-Legendre for narrow pieces not deep in a tail, otherwise Taylor coefficients about the
// centre times partial moments built from non-negative tails. The piece's coefficients are scalars
// c0..c7 and its degree `deg` is a literal of each call where rulegen writes one (the piecewise
// entries' wide regime): no local array. NVIDIA's driver keeps a local array in local memory for
// every inlined call site; bricks_bumps' most accurate points, which called the array version 4-6
// times, drew at 143-179 ns/px (40x MSAA-16) and compiled in 35-40 s (docs/gpu_timing.md, stop 41).
float bl_gauss_core_s(float xq, float sigma, float dl, float dh, float lo, float hi, int deg, float c0,
                      float c1, float c2, float c3, float c4, float c5, float c6, float c7) {
  if (!(hi > lo) || (deg == 0 && c0 == 0.0)) return 0.0;  // empty piece or f = 0 on it
  bool loinf = bl_is_inf(lo);
  bool hiinf = bl_is_inf(hi);
  if (!loinf && !hiinf) {
    // A bounded piece 40 sd away carries no mass in float (support.hpp, gauss_core).
    if (dl >= 40.0 * sigma || dh <= -40.0 * sigma) return 0.0;
    float hw = (hi - lo) / (2.0 * sigma);
    float cz = (dl + dh) / (2.0 * sigma);
    if (hw <= 1.0 && abs(cz) * hw <= 10.0) {
      // 20-point Gauss-Legendre, the 10 node pairs written out (no node arrays).
      float mid = 0.5 * (lo + hi);
      float hr = 0.5 * (hi - lo);
      float s = 0.0;
      s += 0.15275338713072584 * bl_gl_pair8(mid, hr, cz, hw, 0.076526521133497338,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.14917298647260374 * bl_gl_pair8(mid, hr, cz, hw, 0.22778585114164507,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.14209610931838204 * bl_gl_pair8(mid, hr, cz, hw, 0.37370608871541955,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.13168863844917664 * bl_gl_pair8(mid, hr, cz, hw, 0.51086700195082713,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.11819453196151841 * bl_gl_pair8(mid, hr, cz, hw, 0.63605368072651502,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.10193011981724044 * bl_gl_pair8(mid, hr, cz, hw, 0.7463319064601508,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.083276741576704755 * bl_gl_pair8(mid, hr, cz, hw, 0.83911697182221878,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.062672048334109068 * bl_gl_pair8(mid, hr, cz, hw, 0.91223442825132595,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.040601429800386939 * bl_gl_pair8(mid, hr, cz, hw, 0.96397192727791381,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      s += 0.017614007139152118 * bl_gl_pair8(mid, hr, cz, hw, 0.99312859918509488,
                                              c0, c1, c2, c3, c4, c5, c6, c7);
      return hw * s;
    }
  }
  float a = loinf ? -BL_ZMAX : clamp(dl / sigma, -BL_ZMAX, BL_ZMAX);
  float b = hiinf ? BL_ZMAX : clamp(dh / sigma, -BL_ZMAX, BL_ZMAX);
  // Taylor coefficients about xq (bl_taylor_shift unrolled).
  float g0 = c0; float g1 = c1; float g2 = c2; float g3 = c3; float g4 = c4; float g5 = c5; float g6 = c6; float g7 = c7;
  if (0 < deg && 6 < deg) g6 += xq * g7;
  if (0 < deg && 5 < deg) g5 += xq * g6;
  if (0 < deg && 4 < deg) g4 += xq * g5;
  if (0 < deg && 3 < deg) g3 += xq * g4;
  if (0 < deg && 2 < deg) g2 += xq * g3;
  if (0 < deg && 1 < deg) g1 += xq * g2;
  if (0 < deg && 0 < deg) g0 += xq * g1;
  if (1 < deg && 6 < deg) g6 += xq * g7;
  if (1 < deg && 5 < deg) g5 += xq * g6;
  if (1 < deg && 4 < deg) g4 += xq * g5;
  if (1 < deg && 3 < deg) g3 += xq * g4;
  if (1 < deg && 2 < deg) g2 += xq * g3;
  if (1 < deg && 1 < deg) g1 += xq * g2;
  if (2 < deg && 6 < deg) g6 += xq * g7;
  if (2 < deg && 5 < deg) g5 += xq * g6;
  if (2 < deg && 4 < deg) g4 += xq * g5;
  if (2 < deg && 3 < deg) g3 += xq * g4;
  if (2 < deg && 2 < deg) g2 += xq * g3;
  if (3 < deg && 6 < deg) g6 += xq * g7;
  if (3 < deg && 5 < deg) g5 += xq * g6;
  if (3 < deg && 4 < deg) g4 += xq * g5;
  if (3 < deg && 3 < deg) g3 += xq * g4;
  if (4 < deg && 6 < deg) g6 += xq * g7;
  if (4 < deg && 5 < deg) g5 += xq * g6;
  if (4 < deg && 4 < deg) g4 += xq * g5;
  if (5 < deg && 6 < deg) g6 += xq * g7;
  if (5 < deg && 5 < deg) g5 += xq * g6;
  if (6 < deg && 6 < deg) g6 += xq * g7;
  // Moments on [a, b] from non-negative tails (bl_upper_moments at ta and tb, unrolled): the
  // branch (a < 0 < b, a >= 0, b <= 0) picks the tails and the signs as bl_gauss_core does.
  int br = (a < 0.0 && b > 0.0) ? 0 : (a >= 0.0 ? 1 : 2);
  float ta = min(br == 1 ? a : -a, BL_ZMAX);
  float tb = min(br == 2 ? -b : b, BL_ZMAX);
  float ea = bl_phi(ta);
  float Ua0 = bl_Phic(ta);
  float Ua1 = ea;
  ea *= ta;
  float Ua2 = (2 <= deg) ? ea + 1.0 * Ua0 : 0.0;
  ea *= ta;
  float Ua3 = (3 <= deg) ? ea + 2.0 * Ua1 : 0.0;
  ea *= ta;
  float Ua4 = (4 <= deg) ? ea + 3.0 * Ua2 : 0.0;
  ea *= ta;
  float Ua5 = (5 <= deg) ? ea + 4.0 * Ua3 : 0.0;
  ea *= ta;
  float Ua6 = (6 <= deg) ? ea + 5.0 * Ua4 : 0.0;
  ea *= ta;
  float Ua7 = (7 <= deg) ? ea + 6.0 * Ua5 : 0.0;
  float eb = bl_phi(tb);
  float Ub0 = bl_Phic(tb);
  float Ub1 = eb;
  eb *= tb;
  float Ub2 = (2 <= deg) ? eb + 1.0 * Ub0 : 0.0;
  eb *= tb;
  float Ub3 = (3 <= deg) ? eb + 2.0 * Ub1 : 0.0;
  eb *= tb;
  float Ub4 = (4 <= deg) ? eb + 3.0 * Ub2 : 0.0;
  eb *= tb;
  float Ub5 = (5 <= deg) ? eb + 4.0 * Ub3 : 0.0;
  eb *= tb;
  float Ub6 = (6 <= deg) ? eb + 5.0 * Ub4 : 0.0;
  eb *= tb;
  float Ub7 = (7 <= deg) ? eb + 6.0 * Ub5 : 0.0;
  float sum = 0.0;
  float sk = 1.0;
  if (0 <= deg) {
    float ik = br == 0 ? 1.0 - (Ua0) - Ub0 : (br == 1 ? Ua0 - Ub0 : Ub0 - Ua0);
    if (g0 != 0.0) sum += g0 * sk * ik;
    if (0 < deg) sk *= sigma;
  }
  if (1 <= deg) {
    float ik = br == 0 ? 0.0 - (-Ua1) - Ub1 : (br == 1 ? Ua1 - Ub1 : -(Ub1 - Ua1));
    if (g1 != 0.0) sum += g1 * sk * ik;
    if (1 < deg) sk *= sigma;
  }
  if (2 <= deg) {
    float ik = br == 0 ? 1.0 - (Ua2) - Ub2 : (br == 1 ? Ua2 - Ub2 : Ub2 - Ua2);
    if (g2 != 0.0) sum += g2 * sk * ik;
    if (2 < deg) sk *= sigma;
  }
  if (3 <= deg) {
    float ik = br == 0 ? 0.0 - (-Ua3) - Ub3 : (br == 1 ? Ua3 - Ub3 : -(Ub3 - Ua3));
    if (g3 != 0.0) sum += g3 * sk * ik;
    if (3 < deg) sk *= sigma;
  }
  if (4 <= deg) {
    float ik = br == 0 ? 3.0 - (Ua4) - Ub4 : (br == 1 ? Ua4 - Ub4 : Ub4 - Ua4);
    if (g4 != 0.0) sum += g4 * sk * ik;
    if (4 < deg) sk *= sigma;
  }
  if (5 <= deg) {
    float ik = br == 0 ? 0.0 - (-Ua5) - Ub5 : (br == 1 ? Ua5 - Ub5 : -(Ub5 - Ua5));
    if (g5 != 0.0) sum += g5 * sk * ik;
    if (5 < deg) sk *= sigma;
  }
  if (6 <= deg) {
    float ik = br == 0 ? 15.0 - (Ua6) - Ub6 : (br == 1 ? Ua6 - Ub6 : Ub6 - Ua6);
    if (g6 != 0.0) sum += g6 * sk * ik;
    if (6 < deg) sk *= sigma;
  }
  if (7 <= deg) {
    float ik = br == 0 ? 0.0 - (-Ua7) - Ub7 : (br == 1 ? Ua7 - Ub7 : -(Ub7 - Ua7));
    if (g7 != 0.0) sum += g7 * sk * ik;
    if (7 < deg) sk *= sigma;
  }
  return sum;
}

// bl_gauss_core_s of a piece table's coefficient array (the generic piecewise and periodic sums).
float bl_gauss_core(float xq, float sigma, float dl, float dh, float lo, float hi, float c[8]) {
  return bl_gauss_core_s(xq, sigma, dl, dh, lo, hi, bl_degree(c), c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]);
}

// Box integral of one piece on offsets: covered length from offsets, mean of t^k by divided
// differences S_k = b S_{k-1} + a^k.
float bl_box_core(float xq, float h, float dl, float dh, float lo, float hi, float c[8]) {
  if (!(dl < h) || !(dh > -h)) return 0.0;
  bool cl = dl > -h;
  bool cr = dh < h;
  float a = cl ? lo : xq - h;
  float b = cr ? hi : xq + h;
  float len = cl ? (cr ? hi - lo : h - dl) : (cr ? dh + h : 2.0 * h);
  int deg = bl_degree(c);
  float S = 1.0;
  float ak = 1.0;
  float mean = c[0];
  for (int k = 1; k < 8; ++k) {
    if (k > deg) break;
    ak *= a;
    S = b * S + ak;
    mean += c[k] * S / float(k + 1);
  }
  return len / (2.0 * h) * mean;
}

// One tent side, Taylor expansion about the interval end t0 nearest the centre (see support.hpp).
float bl_tent_side(float c[8], int deg, float t0, float G, float L, float w, bool left) {
  float g[8];
  bl_taylor_shift(c, deg, t0, g);
  float ell = L / w;
  float gam = G / w;
  float sum = 0.0;
  float Lk = 1.0;
  for (int k = 0; k < 8; ++k) {
    if (k > deg) break;
    if (g[k] != 0.0) {
      float term = g[k] * Lk * (gam / float(k + 1) - ell / float(k + 2));
      sum += (left && (k & 1) == 1) ? -term : term;
    }
    if (k < deg) Lk *= L;
  }
  return sum * ell;
}

float bl_tent_core(float xq, float w, float dl, float dh, float lo, float hi, float c[8]) {
  if (!(dl < w) || !(dh > -w)) return 0.0;
  int deg = bl_degree(c);
  float r = 0.0;
  if (dh > 0.0) {
    if (dl > 0.0) {
      float G = w - dl;
      r += bl_tent_side(c, deg, lo, G, min(hi - lo, G), w, false);
    } else {
      r += bl_tent_side(c, deg, xq, w, min(dh, w), w, false);
    }
  }
  if (dl < 0.0) {
    if (dh < 0.0) {
      float G = w + dh;
      r += bl_tent_side(c, deg, hi, G, min(hi - lo, G), w, true);
    } else {
      r += bl_tent_side(c, deg, xq, w, min(-dl, w), w, true);
    }
  }
  return r;
}

float bl_gauss_piece(float mu, float sigma, float lo, float hi, float c[8]) {
  return bl_gauss_core(mu, sigma, lo - mu, hi - mu, lo, hi, c);
}
float bl_box_piece(float x, float h, float lo, float hi, float c[8]) {
  return bl_box_core(x, h, lo - x, hi - x, lo, hi, c);
}
float bl_tent_piece(float x, float w, float lo, float hi, float c[8]) {
  return bl_tent_core(x, w, lo - x, hi - x, lo, hi, c);
}

// Whole-line piecewise polynomials: n sorted contiguous pieces, p[0].lo = -1e30, p[n-1].hi = 1e30.
float bl_pw_eval(float x, int n, BlPiece p[4]) {
  for (int i = 0; i < 3; ++i) {
    if (i >= n - 1) break;
    if (x < p[i].hi) return bl_poly(p[i].c, x);
  }
  return bl_poly(p[n - 1].c, x);
}

float bl_gauss_pw(float x, float sigma, int n, BlPiece p[4]) {
  if (sigma == 0.0) return bl_pw_eval(x, n, p);
  float s = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (i >= n) break;
    s += bl_gauss_core(x, sigma, p[i].lo - x, p[i].hi - x, p[i].lo, p[i].hi, p[i].c);
  }
  return s;
}

float bl_box_pw(float x, float sigma, int n, BlPiece p[4]) {
  if (sigma == 0.0) return bl_pw_eval(x, n, p);
  float h = BL_SQRT3 * sigma;
  float s = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (i >= n) break;
    float dl = p[i].lo - x;
    float dh = p[i].hi - x;
    if (!(dh > -h)) continue;
    if (!(dl < h)) break;
    s += bl_box_core(x, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
  }
  return s;
}

float bl_tent_pw(float x, float sigma, int n, BlPiece p[4]) {
  if (sigma == 0.0) return bl_pw_eval(x, n, p);
  float w = BL_SQRT6 * sigma;
  float s = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (i >= n) break;
    float dl = p[i].lo - x;
    float dh = p[i].hi - x;
    if (!(dh > -w)) continue;
    if (!(dl < w)) break;
    s += bl_tent_core(x, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
  }
  return s;
}

// ---- exp-polynomial terms (see support.hpp: ExpTerm, erfcx, tail_laplace, exp_moments) ----
// A term is e^{a s} sum_k c[k] s^k, s = t - ref, on [lo, hi); tables hold n <= 8 terms.
struct BlExpTerm {
  float lo;
  float hi;
  float a;
  float ref;
  float c[8];
};

// erfcx(t) = e^{t^2} erfc(t), t >= 0: the Chebyshev fit bl_erfc is built on (relative error
// < 1.2e-7), without its e^{-t^2} factor, so it stays finite for every t.
float bl_erfcx(float x) {
  float z = abs(x);
  float t = 1.0 / (1.0 + 0.5 * z);
  return t * exp(-1.26551223 +
                 t * (1.00002368 +
                      t * (0.37409196 +
                           t * (0.09678418 +
                                t * (-0.18628806 +
                                     t * (0.27886807 +
                                          t * (-1.13520398 +
                                               t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))));
}

// e^{lw} U_k(t), t >= 0 finite, lwt = lw - t^2/2 (upper_moments_scaled in support.hpp).
void bl_upper_moments_scaled(float t, float lwt, int deg, out float U[8]) {
  float e0 = exp(lwt);
  float e = BL_INV_SQRT_2PI * e0;
  U[0] = 0.5 * bl_erfcx(t * BL_INV_SQRT2) * e0;
  U[1] = e;
  for (int k = 2; k < 8; ++k) {
    e *= t;
    U[k] = (k <= deg) ? e + float(k - 1) * U[k - 2] : 0.0;
  }
}

// V_k(al) = int_0^inf u^k e^{-al u - u^2/2} du (tail_laplace in support.hpp): upwards for al < 2,
// Miller's backward ratios from K = 40 otherwise.
void bl_tail_laplace(float al, int deg, out float V[8]) {
  V[0] = 1.2533141373155003 * bl_erfcx(al * BL_INV_SQRT2);
  for (int k = 1; k < 8; ++k) V[k] = 0.0;
  if (deg == 0) return;
  if (al < 2.0) {
    V[1] = 1.0 - al * V[0];
    for (int k = 1; k < 7; ++k) {
      if (k >= deg) break;
      V[k + 1] = float(k) * V[k - 1] - al * V[k];
    }
    return;
  }
  // s_k = V_k/V_{k-1} = k/(s_{k+1} + al) from K = deg + n(al), started at the fixed point
  // (support.hpp: miller_start, tail_laplace, float levels)
  float inv[8];
  for (int k = 0; k < 8; ++k) inv[k] = 1.0;
  int n = al < 3.0 ? 24 : (al < 4.0 ? 16 : (al < 5.0 ? 12 : (al < 6.0 ? 10 : 8)));
  if (al >= 8.0) n = al < 12.0 ? 7 : (al < 20.0 ? 5 : (al < 30.0 ? 4 : 3));
  int K = deg + n;
  float ac = min(al, 1e15);  // ac^2 stays finite; the start is irrelevant that far out
  float sk = 2.0 * float(K) / (ac + sqrt(ac * ac + 4.0 * float(K)));
  for (int k = K - 1; k >= 1; --k) {
    sk = float(k) / (sk + al);
    if (k <= deg) inv[k] = sk;
  }
  for (int k = 1; k < 8; ++k) {
    if (k > deg) break;
    V[k] = V[k - 1] * inv[k];
  }
}

// I_k = int_0^L v^k e^{-b v} dv, k <= deg (exp_moments in support.hpp): the top moment by its
// series or closed form, the lower ones by I_{k-1} = (b I_k + L^k e^{-y})/k (non-negative terms).
void bl_exp_moments(float L, float b, int deg, out float I[9]) {
  float y = b * L;
  float ey = exp(-y);
  float Lk[9];
  Lk[0] = 1.0;
  for (int k = 0; k < 9; ++k) {
    I[k] = 0.0;
    if (k > 0) Lk[k] = k <= deg ? Lk[k - 1] * L : 0.0;
  }
  float top;
  if (y < float(2 * (deg + 1))) {
    float term = 1.0 / float(deg + 1);
    float sum = term;
    for (int n = 1; n < 100; ++n) {
      term *= y / float(deg + 1 + n);
      sum += term;
      if (term <= 3.0e-8 * sum) break;
    }
    float Ld = 0.0;  // Lk[deg], indexed by constants only (see bl_u_coefs)
    for (int k = 0; k < 9; ++k)
      if (k == deg) Ld = Lk[k];
    top = Ld * L * ey * sum;
  } else {
    float kfact = 1.0;
    float bk1 = b;
    float term = 1.0;
    float sum = 1.0;
    for (int j = 1; j <= 8; ++j) {
      if (j > deg) break;
      kfact *= float(j);
      bk1 *= b;
      term *= y / float(j);
      sum += term;
    }
    top = ey == 0.0 ? kfact / bk1 : kfact / bk1 * (1.0 - ey * sum);
  }
  for (int k = 8; k >= 0; --k) {
    if (k == deg) I[k] = top;
    if (k < deg) I[k] = (b * I[k + 1] + (ey == 0.0 ? 0.0 : Lk[k + 1] * ey)) / float(k + 1);
  }
}

float bl_exp_scaled(float pre, float s, float d) {
  if (pre < 30.0) return exp(pre) * s / d;
  return exp(pre - log(d)) * s;
}

// sum_k g_k dir^k int_0^len v^k (G + sw v) e^{-b v} dv, g the Taylor coefficients at s0.
float bl_exp_side(float c[8], int deg, float s0, float dir, float len, float b, float G, float sw) {
  float g[8];
  bl_taylor_shift(c, deg, s0, g);
  float I[9];
  bl_exp_moments(len, b, sw != 0.0 ? deg + 1 : deg, I);
  float sum = 0.0;
  float dk = 1.0;
  for (int k = 0; k < 8; ++k) {
    if (k > deg) break;
    if (g[k] != 0.0) sum += g[k] * dk * (sw != 0.0 ? G * I[k] + sw * I[k + 1] : I[k]);
    dk *= dir;
  }
  return sum;
}

float bl_ept_eval(float x, int n, BlExpTerm p[8]) {
  float s = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    if ((bl_is_inf(p[i].lo) || p[i].lo <= x) && (bl_is_inf(p[i].hi) || x < p[i].hi)) {
      float u = x - p[i].ref;
      s += bl_poly(p[i].c, u) * exp(p[i].a * u);
    }
  }
  return s;
}

// int from the end E of q(s) e^{a s} phi_sigma(t - x) over the side away from the shifted centre.
float bl_gauss_exp_end(BlExpTerm p, int deg, float E, float e, float f, float sigma, bool right) {
  float al = (right ? f : -f) / sigma;
  float g[8];
  float V[8];
  bl_taylor_shift(p.c, deg, E - p.ref, g);
  bl_tail_laplace(al, deg, V);
  float s = 0.0;
  float sk = 1.0;
  float step = right ? sigma : -sigma;
  for (int k = 0; k < 8; ++k) {
    if (k > deg) break;
    if (g[k] != 0.0) s += g[k] * sk * V[k];
    sk *= step;
  }
  float z = e / sigma;
  return BL_INV_SQRT_2PI * exp(p.a * (E - p.ref) - 0.5 * z * z) * s;
}

float bl_exp_lw(BlExpTerm p, float E, float e, float sigma) {
  float z = e / sigma;
  return p.a * (E - p.ref) - 0.5 * z * z;
}

// Gaussian of one term (gauss_exp_term in support.hpp).
float bl_gauss_exp_term(float x, float sigma, BlExpTerm p) {
  if (!(p.hi > p.lo)) return 0.0;
  bool loinf = bl_is_inf(p.lo);
  bool hiinf = bl_is_inf(p.hi);
  int deg = bl_degree(p.c);
  float a = p.a;
  float el = p.lo - x;
  float eh = p.hi - x;
  float as2 = a * sigma * sigma;
  float fl = el - as2;
  float fh = eh - as2;
  float two_sigma = 2.0 * sigma;
  if (!loinf && fl >= two_sigma) {
    float r = bl_gauss_exp_end(p, deg, p.lo, el, fl, sigma, true);
    if (!hiinf) r -= bl_gauss_exp_end(p, deg, p.hi, eh, fh, sigma, true);
    return r;
  }
  if (!hiinf && fh <= -two_sigma) {
    float r = bl_gauss_exp_end(p, deg, p.hi, eh, fh, sigma, false);
    if (!loinf) r -= bl_gauss_exp_end(p, deg, p.lo, el, fl, sigma, false);
    return r;
  }
  if (!loinf && !hiinf) {
    float width = p.hi - p.lo;
    float hw = width / two_sigma;
    float cz = (fl + fh) / two_sigma;
    if (hw <= 1.0 && abs(cz) * hw <= 10.0) {
      float gx[10];
      float gw[10];
      gx[0] = 0.076526521133497338;
      gx[1] = 0.22778585114164507;
      gx[2] = 0.37370608871541955;
      gx[3] = 0.51086700195082713;
      gx[4] = 0.63605368072651502;
      gx[5] = 0.7463319064601508;
      gx[6] = 0.83911697182221878;
      gx[7] = 0.91223442825132595;
      gx[8] = 0.96397192727791381;
      gx[9] = 0.99312859918509488;
      gw[0] = 0.15275338713072584;
      gw[1] = 0.14917298647260374;
      gw[2] = 0.14209610931838204;
      gw[3] = 0.13168863844917664;
      gw[4] = 0.11819453196151841;
      gw[5] = 0.10193011981724044;
      gw[6] = 0.083276741576704755;
      gw[7] = 0.062672048334109068;
      gw[8] = 0.040601429800386939;
      gw[9] = 0.017614007139152118;
      float half_ = 0.5 * width;
      float sm = 0.5 * ((p.lo - p.ref) + (p.hi - p.ref));
      float em = 0.5 * (el + eh);
      float s = 0.0;
      for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 2; ++j) {
          float xi = j == 0 ? gx[i] : -gx[i];
          float z = (em + half_ * xi) / sigma;
          s += gw[i] * bl_poly(p.c, sm + half_ * xi) * exp(a * (sm + half_ * xi) - 0.5 * z * z);
        }
      }
      return hw * BL_INV_SQRT_2PI * s;
    }
  }
  float g[8];
  bl_taylor_shift(p.c, deg, (x - p.ref) + as2, g);
  float L = a * (x - p.ref) + 0.5 * a * as2;
  float al = fl / sigma;
  float be = fh / sigma;
  float Ua[8];
  float Ub[8];
  for (int k = 0; k < 8; ++k) {
    Ua[k] = 0.0;
    Ub[k] = 0.0;
  }
  float sum = 0.0;
  float sk = 1.0;
  if ((loinf || al < 0.0) && (hiinf || be > 0.0)) {  // the shifted centre inside the piece
    if (!loinf) bl_upper_moments_scaled(-al, bl_exp_lw(p, p.lo, el, sigma), deg, Ua);
    if (!hiinf) bl_upper_moments_scaled(be, bl_exp_lw(p, p.hi, eh, sigma), deg, Ub);
    float eL = exp(L);
    float m[8];
    for (int k = 0; k < 8; ++k) {
      if (k > deg) break;
      m[k] = (k == 0) ? 1.0 : ((k == 1) ? 0.0 : float(k - 1) * m[k - 2]);
      float ik = eL * m[k] - (((k & 1) == 1) ? -Ua[k] : Ua[k]) - Ub[k];
      if (g[k] != 0.0) sum += g[k] * sk * ik;
      sk *= sigma;
    }
    return sum;
  }
  if (al >= 0.0) {
    bl_upper_moments_scaled(al, bl_exp_lw(p, p.lo, el, sigma), deg, Ua);
    if (!hiinf) bl_upper_moments_scaled(be, bl_exp_lw(p, p.hi, eh, sigma), deg, Ub);
    for (int k = 0; k < 8; ++k) {
      if (k > deg) break;
      if (g[k] != 0.0) sum += g[k] * sk * (Ua[k] - Ub[k]);
      sk *= sigma;
    }
    return sum;
  }
  bl_upper_moments_scaled(-be, bl_exp_lw(p, p.hi, eh, sigma), deg, Ub);
  if (!loinf) bl_upper_moments_scaled(-al, bl_exp_lw(p, p.lo, el, sigma), deg, Ua);
  for (int k = 0; k < 8; ++k) {
    if (k > deg) break;
    float ik = Ub[k] - Ua[k];
    if (g[k] != 0.0) sum += g[k] * sk * (((k & 1) == 1) ? -ik : ik);
    sk *= sigma;
  }
  return sum;
}

// Box of one term (box_exp_term in support.hpp).
float bl_box_exp_term(float x, float h, BlExpTerm p) {
  float el = p.lo - x;
  float eh = p.hi - x;
  if (!(el < h) || !(eh > -h) || !(p.hi > p.lo)) return 0.0;
  bool cl = el > -h && !bl_is_inf(p.lo);
  bool cr = eh < h && !bl_is_inf(p.hi);
  float len = cl ? (cr ? p.hi - p.lo : h - el) : (cr ? eh + h : 2.0 * h);
  int deg = bl_degree(p.c);
  bool left = !(p.a > 0.0);
  float s0 = left ? (cl ? p.lo - p.ref : (x - p.ref) - h) : (cr ? p.hi - p.ref : (x - p.ref) + h);
  float sum = bl_exp_side(p.c, deg, s0, left ? 1.0 : -1.0, len, abs(p.a), 1.0, 0.0);
  return bl_exp_scaled(p.a * s0, sum, 2.0 * h);
}

// One half [o0, o1] (offsets from x) of the tent of one term; e0/e1: o0/o1 is an end of the piece.
float bl_tent_exp_half(float x, float w, BlExpTerm p, int deg, float o0, bool e0, float o1, bool e1, bool right) {
  float len = (e0 && e1) ? p.hi - p.lo : o1 - o0;
  if (!(len > 0.0)) return 0.0;
  bool left_anchor = !(p.a > 0.0);
  float o = left_anchor ? o0 : o1;
  bool e = left_anchor ? e0 : e1;
  float s0 = e ? (left_anchor ? p.lo - p.ref : p.hi - p.ref) : (x - p.ref) + o;
  float G = right ? w - o : w + o;
  float sw = (right == left_anchor) ? -1.0 : 1.0;
  float sum = bl_exp_side(p.c, deg, s0, left_anchor ? 1.0 : -1.0, len, abs(p.a), G, sw);
  return bl_exp_scaled(p.a * s0, sum / w, w);
}

float bl_tent_exp_term(float x, float w, BlExpTerm p) {
  float el = p.lo - x;
  float eh = p.hi - x;
  if (!(el < w) || !(eh > -w) || !(p.hi > p.lo)) return 0.0;
  int deg = bl_degree(p.c);
  float r = 0.0;
  if (eh > 0.0) r += bl_tent_exp_half(x, w, p, deg, el > 0.0 ? el : 0.0, el > 0.0, eh < w ? eh : w, eh < w, true);
  if (el < 0.0) r += bl_tent_exp_half(x, w, p, deg, el > -w ? el : -w, el > -w, eh < 0.0 ? eh : 0.0, eh < 0.0, false);
  return r;
}

float bl_gauss_ept(float x, float sigma, int n, BlExpTerm p[8]) {
  if (sigma == 0.0) return bl_ept_eval(x, n, p);
  float s = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    s += bl_gauss_exp_term(x, sigma, p[i]);
  }
  return s;
}
float bl_box_ept(float x, float sigma, int n, BlExpTerm p[8]) {
  if (sigma == 0.0) return bl_ept_eval(x, n, p);
  float h = BL_SQRT3 * sigma;
  float s = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    s += bl_box_exp_term(x, h, p[i]);
  }
  return s;
}
float bl_tent_ept(float x, float sigma, int n, BlExpTerm p[8]) {
  if (sigma == 0.0) return bl_ept_eval(x, n, p);
  float w = BL_SQRT6 * sigma;
  float s = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    s += bl_tent_exp_term(x, w, p[i]);
  }
  return s;
}

// Periodic functions: pieces cover [0, period). Returns vec2(r, q), y = q period + r,
// r in [0, period); q is adjusted with r so the pair stays consistent after rounding.
vec2 bl_reduce_period(float y, float period) {
  float q = floor(y / period);
  float r = y - q * period;
  if (r < 0.0) {
    r += period;
    q -= 1.0;
  }
  if (r >= period) {
    r -= period;
    q += 1.0;
  }
  r = clamp(r, 0.0, period);
  if (r >= period) r = 0.0;
  return vec2(r, q);
}

// Signed remainder in (-period, period): y itself when |y| < period, so a tiny negative y (just
// below a period boundary) is not rounded by "+ period" before a tiny kernel magnifies it.
// reduce_signed_pow2 (support.hpp): y mod period with y's sign, exact for a power-of-two period.
float bl_reduce_signed_pow2(float y, float period) {
  float a = abs(y);
  float r = a - period * floor(a / period);
  return y < 0.0 ? -r : r;
}

// copysign(1, v) up to the sign of zero (-0.0 gives +1: the generated callers take either side of
// an exact tie).
float bl_copysign1(float v) { return v < 0.0 ? -1.0 : 1.0; }

float bl_reduce_signed(float y, float period) {
  float r = y - period * trunc(y / period);
  if (abs(r) >= period) r = 0.0;
  return r;
}

float bl_period_piece_eval(float r, int n, BlPiece p[4]) {
  for (int i = 0; i < 3; ++i) {
    if (i >= n - 1) break;
    if (r < p[i].hi) return bl_poly(p[i].c, r);
  }
  return bl_poly(p[n - 1].c, r);
}

// Piece chosen on the signed remainder (see support.hpp): r < 0 compares with hi - period.
float bl_periodic_eval(float x, float period, int n, BlPiece p[4]) {
  float r = bl_reduce_signed(x, period);
  if (!(r < 0.0)) return bl_period_piece_eval(r, n, p);
  for (int i = 0; i < 3; ++i) {
    if (i >= n - 1) break;
    if (r < p[i].hi - period) return bl_poly(p[i].c, r + period);
  }
  return bl_poly(p[n - 1].c, r + period);
}

// Tail multiple z with P(|Z| > z) <= tol/fmax (Mills: 2 phi(z) <= tol/fmax suffices for z >= 1).
float bl_image_z(float fmax, float tol) {
  float arg = 0.7978845608 * fmax / tol;
  if (!(arg > 1.6487212707)) return 1.0;
  return sqrt(2.0 * log(arg));
}

// Image sum over the periods within image_z(fmax, 1e-8) sigma of x (see support.hpp). It loops over
// about 12 sigma/period periods: use it where bl_prefer_fourier is false (Mesa's llvmpipe also
// stops any loop after 65535 iterations per invocation, reached near sigma ~ 500 period).
float bl_gauss_periodic_image(float x, float sigma, float period, int n, BlPiece p[4],
                              float fmax) {
  if (sigma == 0.0) return bl_periodic_eval(x, period, n, p);
  float xr = bl_reduce_signed(x, period);
  float R = bl_image_z(fmax, BL_SERIES_TOL) * sigma;
  int m0 = int(floor((xr - R) / period));
  int m1 = int(floor((xr + R) / period));
  float s = 0.0;
  for (int m = m0; m <= m1; ++m) {
    float shift = float(m) * period;
    for (int i = 0; i < 4; ++i) {
      if (i >= n) break;
      float dl = (p[i].lo + shift) - xr;
      float dh = (p[i].hi + shift) - xr;
      if (!(dh > -R) || !(dl < R)) continue;
      s += bl_gauss_core(xr - shift, sigma, dl, dh, p[i].lo, p[i].hi, p[i].c);
    }
  }
  return s;
}

// 1 - e^{-y}, y >= 0, without cancellation for small y (GLSL has no expm1).
float bl_one_minus_exp_neg(float y) {
  if (y < 1.0e-3) return y * (1.0 - y * (0.5 - y * (1.0 / 6.0)));
  return 1.0 - exp(-y);
}

float bl_fourier_bound(float a, float coef_bound, int K) {
  float u = float(K) + 1.0;
  return coef_bound * exp(-a * u * u) / bl_one_minus_exp_neg(2.0 * a * u);
}

// Smallest K with coef_bound e^{-a(K+1)^2} / (1 - e^{-2a(K+1)}) <= tol, a = 2 pi^2 s^2 (geometric
// majorant of the tail, see support.hpp); 2^30 when s is too small.
int bl_fourier_terms(float s, float coef_bound, float tol) {
  if (!(coef_bound > 0.0)) return 0;
  float a = 2.0 * BL_PI * BL_PI * s * s;
  if (!(a > 0.0)) return 1073741824;
  float L = log(coef_bound / tol);
  float u = sqrt(max(L, 0.0) / a);
  for (int it = 0; it < 4; ++it) {
    float Lg = L - log(bl_one_minus_exp_neg(2.0 * a * max(u, 1.0)));
    u = sqrt(max(Lg, 0.0) / a);
  }
  if (!(u < 1.0e9)) return 1073741824;
  int K = max(int(ceil(u)) - 1, 0);
  for (int it = 0; it < 64; ++it) {
    if (K > 0 && bl_fourier_bound(a, coef_bound, K - 1) <= tol) K -= 1;
    else break;
  }
  for (int it = 0; it < 64; ++it) {
    if (!(bl_fourier_bound(a, coef_bound, K) <= tol)) K += 1;
    else break;
  }
  return K;
}

int bl_image_periods(float s, float fmax, float tol) {
  float v = ceil(2.0 * bl_image_z(fmax, tol) * s) + 1.0;
  if (!(v < 1.0e9)) return 1073741824;
  return int(v);
}

// K Fourier terms when the Fourier series is cheaper than the image sum, else -1 (support.hpp).
int bl_fourier_terms_if_preferred(float s, int npieces, float coef_bound, float fmax) {
  int K = bl_fourier_terms(s, coef_bound, BL_SERIES_TOL);
  int P = bl_image_periods(s, fmax, BL_SERIES_TOL);
  float per_piece = s * float(npieces) > 0.5 ? 20.0 : 4.0;
  return 3.0 * float(K) < float(P) * float(npieces) * per_piece ? K : -1;
}
bool bl_prefer_fourier(float s, int npieces, float coef_bound, float fmax) {
  return bl_fourier_terms_if_preferred(s, npieces, coef_bound, fmax) >= 0;
}

// Box over a periodic f: direct shifted pieces when 2h <= 4 periods, else Appendix C with the
// integer parts subtracted as integers on the reduced argument (see support.hpp).
float bl_box_periodic(float x, float sigma, float period, int n, BlPiece p[4], BlPiece P1[4]) {
  if (sigma == 0.0) return bl_periodic_eval(x, period, n, p);
  float h = BL_SQRT3 * sigma;
  if (h <= 2.0 * period) {
    float xr = bl_reduce_signed(x, period);
    int m0 = int(floor((xr - h) / period));
    int m1 = int(floor((xr + h) / period));
    float s = 0.0;
    for (int m = m0; m <= m1; ++m) {
      float shift = float(m) * period;
      for (int i = 0; i < 4; ++i) {
        if (i >= n) break;
        float dl = (p[i].lo + shift) - xr;
        float dh = (p[i].hi + shift) - xr;
        if (!(dh > -h) || !(dl < h)) continue;
        s += bl_box_core(xr - shift, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  float xr = bl_reduce_period(x, period).x;
  vec2 y1 = bl_reduce_period(xr - h, period);
  vec2 y2 = bl_reduce_period(xr + h, period);
  float FT = bl_poly(P1[n - 1].c, period);
  return ((y2.y - y1.y) * FT +
          (bl_period_piece_eval(y2.x, n, P1) - bl_period_piece_eval(y1.x, n, P1))) /
         (2.0 * h);
}

// Tent over a periodic f: direct shifted pieces when 2w <= 4 periods, else the Appendix C second
// difference expanded with q0 = 0 (see support.hpp).
float bl_tent_periodic(float x, float sigma, float period, int n, BlPiece p[4], BlPiece P1[4],
                       BlPiece P2[4]) {
  if (sigma == 0.0) return bl_periodic_eval(x, period, n, p);
  float w = BL_SQRT6 * sigma;
  if (w <= 2.0 * period) {
    float xr = bl_reduce_signed(x, period);
    int m0 = int(floor((xr - w) / period));
    int m1 = int(floor((xr + w) / period));
    float s = 0.0;
    for (int m = m0; m <= m1; ++m) {
      float shift = float(m) * period;
      for (int i = 0; i < 4; ++i) {
        if (i >= n) break;
        float dl = (p[i].lo + shift) - xr;
        float dh = (p[i].hi + shift) - xr;
        if (!(dh > -w) || !(dl < w)) continue;
        s += bl_tent_core(xr - shift, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  float xr = bl_reduce_period(x, period).x;
  vec2 y1 = bl_reduce_period(xr - w, period);
  vec2 y2 = bl_reduce_period(xr + w, period);
  float A = bl_poly(P1[n - 1].c, period);
  float B = bl_poly(P2[n - 1].c, period);
  float g1 = period * y1.y * (y1.y - 1.0) * 0.5;
  float g2 = period * y2.y * (y2.y - 1.0) * 0.5;
  float num = A * ((g2 + g1) + (y2.x * y2.y + y1.x * y1.y)) + B * (y2.y + y1.y) +
              ((bl_period_piece_eval(y2.x, n, P2) + bl_period_piece_eval(y1.x, n, P2)) -
               2.0 * bl_period_piece_eval(xr, n, P2));
  return num / (w * w);
}

// ---- half-line restrictions of periodic functions ----
// f_right(x) = E[f(x+U) 1{x+U >= 0}], called by the generated bl_<kernel>_<f>_right only where the
// kernel straddles 0 (see support.hpp for the derivation and the bounds). Gaussian: the boundary
// series a0 Phi(z) + rho phi(z) sum_m cs[m] rho^m He_m(z) where its bound
// 1.65 coef_bound rho^(m+1) sqrt((m+1)!) reaches BL_SERIES_TOL within nc terms, else the image sum
// over the periods m >= 0. Box/tent: local pieces for a support of up to 4 periods, else the
// Appendix C integrals of the half line.
float bl_gauss_periodic_right(float x, float sigma, float period, int n, BlPiece p[4], float fmax,
                              float coef_bound, float a0, int nc, float cs[40]) {
  float rho = period / (2.0 * BL_PI * sigma);
  if (rho < 0.5) {
    float b = 1.65 * coef_bound;
    int last = -1;
    for (int m = 0; m < 40; ++m) {
      if (m >= nc) break;
      b *= rho * sqrt(float(m + 1));
      if (m >= 1 && b <= BL_SERIES_TOL) {
        last = m;
        break;
      }
    }
    if (last >= 0) {
      float z = x / sigma;
      float Gm1 = 0.0, G = 1.0, acc = 0.0;
      for (int m = 0; m < 40; ++m) {
        if (m > last) break;
        acc += cs[m] * G;
        float Gn = rho * z * G - float(m) * rho * rho * Gm1;
        Gm1 = G;
        G = Gn;
      }
      return a0 * bl_Phi(z) + rho * bl_phi(z) * acc;
    }
  }
  float R = bl_image_z(fmax, BL_SERIES_TOL) * sigma;
  int m0 = max(int(floor((x - R) / period)), 0);
  int m1 = int(floor((x + R) / period));
  float s = 0.0;
  for (int m = m0; m <= m1; ++m) {
    float shift = float(m) * period;
    for (int i = 0; i < 4; ++i) {
      if (i >= n) break;
      float dl = (p[i].lo + shift) - x;
      float dh = (p[i].hi + shift) - x;
      if (!(dh > -R) || !(dl < R)) continue;
      s += bl_gauss_core(x - shift, sigma, dl, dh, p[i].lo, p[i].hi, p[i].c);
    }
  }
  return s;
}

float bl_box_periodic_right(float x, float h, float period, int n, BlPiece p[4], BlPiece P1[4]) {
  if (h <= 2.0 * period) {
    int m1 = int(floor((x + h) / period));
    float s = 0.0;
    for (int m = 0; m <= m1; ++m) {
      float shift = float(m) * period;
      for (int i = 0; i < 4; ++i) {
        if (i >= n) break;
        float dl = (p[i].lo + shift) - x;
        float dh = (p[i].hi + shift) - x;
        if (!(dh > -h) || !(dl < h)) continue;
        s += bl_box_core(x - shift, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  vec2 y = bl_reduce_period(x + h, period);
  return (y.y * bl_poly(P1[n - 1].c, period) + bl_period_piece_eval(y.x, n, P1)) / (2.0 * h);
}

float bl_tent_half_F2(float y, float period, int n, BlPiece P2[4], float A, float B) {
  vec2 r = bl_reduce_period(y, period);
  return A * (period * r.y * (r.y - 1.0) * 0.5 + r.x * r.y) + B * r.y + bl_period_piece_eval(r.x, n, P2);
}

float bl_tent_periodic_right(float x, float w, float period, int n, BlPiece p[4], BlPiece P1[4],
                             BlPiece P2[4]) {
  if (w <= 2.0 * period) {
    int m1 = int(floor((x + w) / period));
    float s = 0.0;
    for (int m = 0; m <= m1; ++m) {
      float shift = float(m) * period;
      for (int i = 0; i < 4; ++i) {
        if (i >= n) break;
        float dl = (p[i].lo + shift) - x;
        float dh = (p[i].hi + shift) - x;
        if (!(dh > -w) || !(dl < w)) continue;
        s += bl_tent_core(x - shift, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  float A = bl_poly(P1[n - 1].c, period);
  float B = bl_poly(P2[n - 1].c, period);
  return (bl_tent_half_F2(x + w, period, n, P2, A, B) -
          2.0 * bl_tent_half_F2(max(x, 0.0), period, n, P2, A, B)) / (w * w);
}

// ---- first kernel moment of periodic functions ----
// M = E[U g(x + U)] for a periodic g given by one period of pieces (n <= 4, degree <= 6, absolute
// coordinate in [0, period)): bl_gauss_periodic_u_image, bl_box_periodic_u, bl_tent_periodic_u. The
// same regimes and stability arguments as the section of the same name in support.hpp: reduced
// argument only, mean removed (E[U c] = 0), each piece re-expanded about the kernel centre clamped
// into it, closed-form sums over full periods for the wide box/tent. sigma == 0 gives 0; sigma < 0,
// NaN or infinite, x not finite, or a piece of degree 7 give sqrt(-1) (NaN where the GPU has NaNs).
// The wide box needs h = sqrt(3) sigma beyond float precision (its dM/dh is O(1)): hl =
// fma(BL_SQRT3, sigma, -h) + BL_SQRT3_LO sigma and an fma reduction of h. A compiler that does not
// fuse fma only loses that correction (the error becomes eps h, as without it), nothing else.
// The Gaussian image sum loops over ~2 z sigma/period periods: use it where bl_prefer_fourier is
// false (llvmpipe stops loops after 65535 iterations).

const float BL_SQRT3_LO = 3.1087248875558696e-8;  // sqrt(3) - float(sqrt(3))

float bl_u_nan(float s) { return sqrt(-1.0 - abs(s)); }

bool bl_u_bad(float x, float sigma) {
  return !(abs(x) < BL_INF) || !(sigma >= 0.0) || !(sigma < BL_INF);
}

// int_a^b s^j q(s) ds, 0 <= a <= b, divided differences (see support.hpp).
// c is indexed by the loop counter alone (i = n - j), not by n - j: NVIDIA's compiler refuses a
// parameter array indexed by an expression it cannot bound ("C5025: lvalue in array access too
// complex"). Same operations in the same order as the C++ twin.
float bl_u_piece_moment(float c[8], int deg, int j, float a, float b) {
  float S = 1.0;
  float an = 1.0;
  for (int n = 1; n < 3; ++n) {  // S_j (j <= 2)
    if (n > j) break;
    an *= a;
    S = b * S + an;
  }
  float sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i > deg) break;
    if (i > 0) {
      an *= a;
      S = b * S + an;
    }
    if (c[i] != 0.0) sum += c[i] * S / float(i + j + 1);
  }
  return (b - a) * sum;
}

// Pieces minus the period mean (t), their degrees, I[j] = int_0^T s^j (g - gbar); false if a
// degree exceeds 6.
bool bl_u_period_data(float period, int n, BlPiece p[4], out BlPiece t[4], out int deg[4],
                      out float I[3]) {
  bool ok = true;
  float I0 = 0.0;
  for (int i = 0; i < 4; ++i) {
    t[i] = p[i];
    deg[i] = 0;
    if (i >= n) continue;
    deg[i] = bl_degree(p[i].c);
    if (deg[i] > 6) ok = false;
    if (p[i].hi > p[i].lo) I0 += bl_u_piece_moment(p[i].c, deg[i], 0, p[i].lo, p[i].hi);
  }
  float gbar = I0 / period;
  I[0] = 0.0;
  I[1] = 0.0;
  I[2] = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (i >= n) break;
    t[i].c[0] -= gbar;
    if (!(t[i].hi > t[i].lo)) continue;
    for (int j = 0; j < 3; ++j) I[j] += bl_u_piece_moment(t[i].c, deg[i], j, t[i].lo, t[i].hi);
  }
  return ok;
}

// Coefficients in v of (v + e) q(o + v).
void bl_u_coefs(float q[8], int deg, float o, float e, out float r[8]) {
  float g[8];
  bl_taylor_shift(q, deg, o, g);
  for (int k = 0; k < 8; ++k) r[k] = 0.0;
  r[0] = e * g[0];
  for (int k = 1; k < 8; ++k) {
    if (k > deg) break;
    r[k] = g[k - 1] + e * g[k];
  }
  // r[deg + 1] = g[deg] with constant indices: a run-time index sends both arrays to local memory
  // on NVIDIA (bricks_bumps' box/tent floor^2 programs: 312-670 slots, stop 42).
  for (int k = 0; k < 7; ++k)
    if (k == deg) r[k + 1] = g[k];
}

// Tent with the centre inside the piece: both halves term by term, odd terms as differences
// (exactly 0 when the support lies inside the piece), see u_tent_centre in support.hpp.
float bl_u_tent_centre(float c[8], int deg, float Lr, float Ll, float w) {
  float lr = Lr / w;
  float ll = Ll / w;
  float sum = 0.0;
  float Lrk = 1.0;
  float Llk = 1.0;
  for (int k = 0; k < 8; ++k) {
    if (k > deg) break;
    float ar = Lrk * lr * (1.0 / float(k + 1) - lr / float(k + 2));
    float al = Llk * ll * (1.0 / float(k + 1) - ll / float(k + 2));
    sum += c[k] * (((k & 1) == 1) ? ar - al : ar + al);
    Lrk *= Lr;
    Llk *= Ll;
  }
  return sum;
}

// One piece, expanded about the kernel centre clamped into it (kernel 0 Gaussian, 1 box, 2 tent;
// s = sigma, h or w).
float bl_u_piece(int kernel, float xq, float s, float dl, float dh, float lo, float hi, float q[8],
                 int deg) {
  float o = xq;
  float e = 0.0;
  float lo2 = dl;
  float hi2 = dh;
  if (!(dl < 0.0)) {
    o = lo;
    e = dl;
    lo2 = 0.0;
    hi2 = hi - lo;
  } else if (!(dh > 0.0)) {
    o = hi;
    e = dh;
    lo2 = lo - hi;
    hi2 = 0.0;
  }
  float c[8];
  bl_u_coefs(q, deg, o, e, c);
  if (kernel == 2 && dl < 0.0 && dh > 0.0) return bl_u_tent_centre(c, deg + 1, min(dh, s), min(-dl, s), s);
  if (kernel == 0) return bl_gauss_core(-e, s, dl, dh, lo2, hi2, c);
  if (kernel == 1) return bl_box_core(-e, s, dl, dh, lo2, hi2, c);
  return bl_tent_core(-e, s, dl, dh, lo2, hi2, c);
}

float bl_u_periods(int kernel, float xr, float s, float R, float period, int m0, int m1, int n,
                   BlPiece t[4], int deg[4]) {
  float sum = 0.0;
  for (int m = m0; m <= m1; ++m) {
    float shift = float(m) * period;
    for (int i = 0; i < 4; ++i) {
      if (i >= n) break;
      if (!(t[i].hi > t[i].lo)) continue;
      float dl = (t[i].lo + shift) - xr;
      float dh = (t[i].hi + shift) - xr;
      if (!(dh > -R) || !(dl < R)) continue;
      sum += bl_u_piece(kernel, xr - shift, s, dl, dh, t[i].lo, t[i].hi, t[i].c, deg[i]);
    }
  }
  return sum;
}

// int_0^L c(v) dv, either sign of L.
float bl_u_integral0(float c[8], int deg, float L) {
  float r = 0.0;
  for (int k = 7; k >= 0; --k) {
    if (k <= deg) r = r * L + c[k] / float(k + 1);
  }
  return r * L;
}

float bl_gauss_periodic_u_image(float x, float sigma, float period, int n, BlPiece p[4],
                                float fmax) {
  if (bl_u_bad(x, sigma)) return bl_u_nan(sigma);
  if (sigma == 0.0) return 0.0;
  BlPiece t[4];
  int deg[4];
  float I[3];
  if (!bl_u_period_data(period, n, p, t, deg, I)) return bl_u_nan(sigma);
  float xr = bl_reduce_signed(x, period);
  float R = bl_image_z(2.0 * fmax * max(sigma, 1.0), BL_SERIES_TOL) * sigma;
  int m0 = int(floor((xr - R) / period));
  int m1 = int(floor((xr + R) / period));
  return bl_u_periods(0, xr, sigma, R, period, m0, m1, n, t, deg);
}

// y = q period + r for y >= 0, remainder by fma (exact when fused).
vec2 bl_u_reduce_fma(float y, float period) {
  float q = floor(y / period);
  float r = fma(-q, period, y);
  if (r < 0.0) {
    r += period;
    q -= 1.0;
  }
  if (r >= period) {
    r -= period;
    q += 1.0;
  }
  return vec2(r, q);
}

float bl_box_periodic_u(float x, float sigma, float period, int n, BlPiece p[4]) {
  if (bl_u_bad(x, sigma)) return bl_u_nan(sigma);
  if (sigma == 0.0) return 0.0;
  BlPiece t[4];
  int deg[4];
  float I[3];
  if (!bl_u_period_data(period, n, p, t, deg, I)) return bl_u_nan(sigma);
  float h = BL_SQRT3 * sigma;
  if (h <= 2.0 * period) {
    float xs = bl_reduce_signed(x, period);
    int m0 = int(floor((xs - h) / period));
    int m1 = int(floor((xs + h) / period));
    return bl_u_periods(1, xs, h, h, period, m0, m1, n, t, deg);
  }
  float xr = bl_reduce_period(x, period).x;
  float hl = fma(BL_SQRT3, sigma, -h) + BL_SQRT3_LO * sigma;
  vec2 rq = bl_u_reduce_fma(h, period);
  float q2 = rq.y;
  float r2 = (rq.x + xr) + hl;
  if (!(r2 < period)) {
    r2 -= period;
    q2 += 1.0;
  } else if (r2 < 0.0) {
    r2 += period;
    q2 -= 1.0;
    if (!(r2 < period)) {
      r2 = 0.0;
      q2 += 1.0;
    }
  }
  float q1 = -rq.y;
  float r1 = (xr - rq.x) - hl;
  if (r1 < 0.0) {
    r1 += period;
    q1 -= 1.0;
    if (!(r1 < period)) {
      r1 = 0.0;
      q1 += 1.0;
    }
  } else if (!(r1 < period)) {
    r1 -= period;
    q1 += 1.0;
  }
  float s = (q2 - q1 - 1.0) * (I[1] - I[0] * (r1 + r2) * 0.5);
  float s1 = q1 * period;
  float s2 = q2 * period;
  for (int i = 0; i < 4; ++i) {
    if (i >= n) break;
    if (!(t[i].hi > t[i].lo)) continue;
    float c[8];
    if (t[i].lo < r2) {
      float b = min(t[i].hi, r2);
      bl_u_coefs(t[i].c, deg[i], t[i].lo, (t[i].lo + s2) - xr, c);
      s += bl_u_integral0(c, deg[i] + 1, b - t[i].lo);
    }
    if (t[i].hi > r1) {
      float a = max(t[i].lo, r1);
      bl_u_coefs(t[i].c, deg[i], t[i].hi, (t[i].hi + s1) - xr, c);
      s -= bl_u_integral0(c, deg[i] + 1, a - t[i].hi);
    }
  }
  return s / (2.0 * h);
}

float bl_tent_periodic_u(float x, float sigma, float period, int n, BlPiece p[4]) {
  if (bl_u_bad(x, sigma)) return bl_u_nan(sigma);
  if (sigma == 0.0) return 0.0;
  BlPiece t[4];
  int deg[4];
  float I[3];
  if (!bl_u_period_data(period, n, p, t, deg, I)) return bl_u_nan(sigma);
  float w = BL_SQRT6 * sigma;
  if (w <= 2.0 * period) {
    float xs = bl_reduce_signed(x, period);
    int m0 = int(floor((xs - w) / period));
    int m1 = int(floor((xs + w) / period));
    return bl_u_periods(2, xs, w, w, period, m0, m1, n, t, deg);
  }
  float xr = bl_reduce_period(x, period).x;
  vec2 y1 = bl_reduce_period(xr - w, period);
  vec2 y2 = bl_reduce_period(xr + w, period);
  int q1 = int(y1.y);
  int q2 = int(y2.y);
  float local = bl_u_periods(2, xr, w, w, period, q1, q1, n, t, deg) +
                bl_u_periods(2, xr, w, w, period, 0, 0, n, t, deg) +
                bl_u_periods(2, xr, w, w, period, q2, q2, n, t, deg);
  float nr = y2.y - 1.0;
  float nl = -y1.y - 1.0;
  float S1r = nr * (nr + 1.0) * 0.5;
  float S2r = S1r * (2.0 * nr + 1.0) / 3.0;
  float S1l = nl * (nl + 1.0) * 0.5;
  float S2l = S1l * (2.0 * nl + 1.0) / 3.0;
  float sd = period * S1r - nr * xr;
  float sd2 = period * period * S2r - 2.0 * period * xr * S1r + nr * xr * xr;
  float se = period * S1l + nl * xr;
  float se2 = period * period * S2l + 2.0 * period * xr * S1l + nl * xr * xr;
  float full = I[1] * (nr * (xr + y2.x) - nl * (xr + y1.x)) +
               I[0] * ((w * sd - sd2) - (w * se - se2)) + I[2] * (nl - nr);
  return local + full / (w * w);
}
