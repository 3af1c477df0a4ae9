// Runtime support of the clamped-domain rules (float); needs bandlimit.glsl before it. Same
// algorithms as clamped_support.hpp (see there), in float: the tail continued fraction starts at
// z = 2 (40 levels reach 1e-7 there), Newton stops at residuals below 1e-5.

struct BlTruncMoments {
  float mass;
  float mean;
  float var;
  float mu3;
  float mu4;
};

const float BL_GL20X[10] = float[10](0.076526521133497338, 0.22778585114164507, 0.37370608871541955,
    0.51086700195082713, 0.63605368072651502, 0.7463319064601508, 0.83911697182221878, 0.91223442825132595,
    0.96397192727791381, 0.99312859918509488);
const float BL_GL20W[10] = float[10](0.15275338713072584, 0.14917298647260374, 0.14209610931838204,
    0.13168863844917664, 0.11819453196151841, 0.10193011981724044, 0.083276741576704755, 0.062672048334109068,
    0.040601429800386939, 0.017614007139152118);

float bl_tn_zphi(float z, int k) {
  if (bl_is_inf(z)) return 0.0;
  float p = bl_phi(z);
  for (int i = 0; i < k; ++i) p *= z;
  return p;
}

// E[t^k | t >= 0] for the density proportional to phi(al + t), al >= 2 (continued fraction).
void bl_tn_upper(float al, out float u[5]) {
  float r[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  float nxt = 0.0;
  for (int k = 40; k >= 1; --k) {
    nxt = float(k) / (al + nxt);
    if (k <= 5) r[k] = nxt;
  }
  u[0] = 1.0;
  for (int k = 1; k <= 4; ++k) u[k] = u[k - 1] * r[k];
}

// Standard normal on [al, be]: returns mass, mean and central moments.
BlTruncMoments bl_tn_standard(float al, float be) {
  bool reflect = !bl_is_inf(be) && (al <= -BL_INF || al + be < 0.0);
  if (reflect) {
    float t = al;
    al = -be;
    be = -t;
  }
  if (al <= -BL_INF) return BlTruncMoments(1.0, 0.0, 1.0, 0.0, 3.0);
  float v[5] = float[5](1.0, 0.0, 0.0, 0.0, 0.0);
  float mass, mean, c2, c3, c4;
  float zmin = max(al, 0.0);
  float zfar = bl_is_inf(be) ? BL_INF : max(abs(al), abs(be));
  float drop = bl_is_inf(zfar) ? BL_INF : 0.5 * (zfar - zmin) * (zfar + zmin);
  if (drop <= 4.0) {
    float mid = 0.5 * (al + be), half_ = 0.5 * (be - al);
    float s0 = 0.0, s1 = 0.0;
    for (int i = 0; i < 20; ++i) {
      float t = (i % 2 == 0 ? -1.0 : 1.0) * half_ * BL_GL20X[i / 2];
      float z = mid + t;
      float w = BL_GL20W[i / 2] * exp(-0.5 * (z - zmin) * (z + zmin));
      s0 += w;
      s1 += w * t;
    }
    float mt = s1 / s0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
    for (int i = 0; i < 20; ++i) {
      float t = (i % 2 == 0 ? -1.0 : 1.0) * half_ * BL_GL20X[i / 2];
      float z = mid + t;
      float w = BL_GL20W[i / 2] * exp(-0.5 * (z - zmin) * (z + zmin));
      float d = t - mt;
      s2 += w * d * d;
      s3 += w * d * d * d;
      s4 += w * d * d * d * d;
    }
    mass = half_ * s0 * bl_phi(zmin);
    mean = mid + mt;
    c2 = s2 / s0;
    c3 = s3 / s0;
    c4 = s4 / s0;
  } else {
    if (al >= 2.0) {
      float ua[5], ub[5];
      bl_tn_upper(al, ua);
      float q = 0.0, L = be - al;
      if (!bl_is_inf(be)) {
        bl_tn_upper(be, ub);
        q = exp(-L * (al + 0.5 * L)) * (al + ua[1]) / (be + ub[1]);
      }
      for (int k = 1; k <= 4; ++k) {
        float tail = 0.0;
        if (q > 0.0) {
          float binom = 1.0, Lp = 1.0;
          for (int j = k; j >= 0; --j) {
            tail += binom * Lp * ub[j];
            binom = binom * float(j) / float(k - j + 1);
            Lp *= L;
          }
        }
        v[k] = (ua[k] - q * tail) / (1.0 - q);
      }
      mass = bl_phi(al) / (al + ua[1]) * (1.0 - q);
      mean = al + v[1];
    } else {
      float m = al >= 0.0 ? bl_Phic(al) - bl_Phic(be) : 1.0 - bl_Phi(al) - bl_Phic(be);
      float J[5];
      J[0] = m;
      J[1] = bl_phi(al) - (bl_is_inf(be) ? 0.0 : bl_phi(be));
      for (int k = 2; k <= 4; ++k) J[k] = float(k - 1) * J[k - 2] + bl_tn_zphi(al, k - 1) - bl_tn_zphi(be, k - 1);
      for (int k = 1; k <= 4; ++k) v[k] = J[k] / m;
      mass = m;
      mean = v[1];
    }
    float mm = v[1];
    c2 = max(v[2] - mm * mm, 0.0);
    c3 = v[3] - 3.0 * mm * v[2] + 2.0 * mm * mm * mm;
    c4 = max(v[4] - 4.0 * mm * v[3] + 6.0 * mm * mm * v[2] - 3.0 * mm * mm * mm * mm, 0.0);
    if (drop > 4.0 && al >= 2.0) mean = al + v[1];
  }
  if (reflect) {
    mean = -mean;
    c3 = -c3;
  }
  return BlTruncMoments(mass, mean, c2, c3, c4);
}

// X ~ N(mu, sigma^2) conditioned on [a, b] (+-BL_INF for no bound).
BlTruncMoments bl_truncnorm_moments(float mu, float sigma, float a, float b) {
  float n = bl_nan();
  if (!(sigma >= 0.0) || mu != mu || !(a <= b)) return BlTruncMoments(n, n, n, n, n);
  float al = bl_is_inf(a) ? -BL_INF : (a - mu) / sigma;
  float be = bl_is_inf(b) ? BL_INF : (b - mu) / sigma;
  if (sigma == 0.0 || a == b || al == be) {
    float m = clamp(mu, a, b);
    return BlTruncMoments((mu > a && mu < b) ? 1.0 : 0.0, m, 0.0, 0.0, 0.0);
  }
  BlTruncMoments s = bl_tn_standard(al, be);
  float s2 = sigma * sigma;
  return BlTruncMoments(s.mass, clamp(mu + sigma * s.mean, a, b), s2 * s.var, s2 * sigma * s.mu3, s2 * s2 * s.mu4);
}

vec2 bl_rule3_from_derivatives(float f0, float f1, float f2, BlTruncMoments m) {
  float mean = f0 + 0.5 * f2 * m.var;
  if (m.var == 0.0) return vec2(mean, 0.0);
  return vec2(mean, max(f1 * f1 * m.var + f1 * f2 * m.mu3 + 0.25 * f2 * f2 * (m.mu4 - m.var * m.var), 0.0));
}

// Rule 3 kept inside f's range [lo, hi] (mean) and Popoviciu's bound (variance); see clamped_support.hpp.
vec2 bl_rule3_in_range(vec2 s, float lo, float hi) {
  float mean = min(max(s.x, lo), hi);
  float pop = 0.25 * (hi - lo) * (hi - lo);
  return vec2(mean, min(s.y, pop));
}

// Variance of the density proportional to e^(k t) on [0, 1] with mean t (see clamped_support.hpp).
float bl_exp_family_var(float t) {
  float lo = -1e4, hi = 1e4;
  for (int i = 0; i < 60; ++i) {
    float k = 0.5 * (lo + hi);
    float m = abs(k) < 1e-2 ? 0.5 + k / 12.0 : 1.0 / (1.0 - exp(-k)) - 1.0 / k;
    if (m < t) lo = k; else hi = k;
  }
  float k = 0.5 * (lo + hi);
  if (abs(k) < 1e-2) return 1.0 / 12.0 - k * k / 720.0;
  float sh = sinh(0.5 * k);
  return 1.0 / (k * k) - 1.0 / (4.0 * sh * sh);
}

float bl_rule1_max_var(float m, float a, float b) {
  if (!bl_is_inf(a) && !bl_is_inf(b)) return (b - a) * (b - a) * bl_exp_family_var((m - a) / (b - a));
  if (!bl_is_inf(a)) return (m - a) * (m - a);
  if (!bl_is_inf(b)) return (b - m) * (b - m);
  return BL_INF;
}

// Kernel 0 gaussian (eq. 8, Newton in natural parameters), 1 box, 2 tent: vec3(center, sigma, steps).
vec3 bl_rule1_renormalize(int kernel, float m, float v, float a, float b) {
  float n = bl_nan();
  if (!(v >= 0.0) || m != m || !(a <= b) || !(m >= a && m <= b)) return vec3(n, n, 0.0);
  if (kernel != 0) {
    float c = kernel == 1 ? BL_SQRT3 : BL_SQRT6;
    return vec3(m, min(c * sqrt(v), min(m - a, b - m)) / c, 0.0);
  }
  if (v == 0.0 || a == b) return vec3(m, 0.0, 0.0);
  v = min(v, 0.98 * bl_rule1_max_var(m, a, b));
  if (!(v > 0.0)) return vec3(m, 0.0, 0.0);
  float sd = sqrt(v);
  float A = bl_is_inf(a) ? -BL_INF : (a - m) / sd, B = bl_is_inf(b) ? BL_INF : (b - m) / sd;
  float t1 = 0.0, t2 = -0.5;
  int steps = 0;
  for (int it = 0; it < 20; ++it) {
    float s = sqrt(-0.5 / t2), c = t1 * s * s;
    BlTruncMoments M = bl_truncnorm_moments(c, s, A, B);
    float e1 = M.mean, k2 = M.var;
    float r0 = e1, r1 = k2 + e1 * e1 - 1.0;
    if (abs(r0) < 1e-5 && abs(r1) < 1e-5) break;
    float J0 = k2, J1 = M.mu3 + 2.0 * e1 * k2, J3 = M.mu4 + 4.0 * e1 * M.mu3 + 4.0 * e1 * e1 * k2 - k2 * k2;
    float det = J0 * J3 - J1 * J1;
    float d1 = -(J3 * r0 - J1 * r1) / det, d2 = -(-J1 * r0 + J0 * r1) / det;
    for (int h = 0; h < 30 && !(t2 + d2 < 0.0); ++h) {
      d1 *= 0.5;
      d2 *= 0.5;
    }
    float s2 = sqrt(-0.5 / (t2 + d2));
    BlTruncMoments M2 = bl_truncnorm_moments((t1 + d1) * s2 * s2, s2, A, B);
    if (!(abs(M2.mean) < BL_INF && abs(M2.var) < BL_INF)) break;  // would leave the floats
    t1 += d1;
    t2 += d2;
    steps += 1;
  }
  float s = sqrt(-0.5 / t2);
  return vec3(m + sd * t1 * s * s, sd * s, float(steps));
}

// z_m: the point of [a, b] nearest the kernel centre, in z = (u - center) / sigma.
float bl_rule1_zm(vec3 p, float a, float b) {
  float A = bl_is_inf(a) ? -BL_INF : (a - p.x) / p.y, B = bl_is_inf(b) ? BL_INF : (b - p.x) / p.y;
  return min(max(0.0, A), B);
}

// Kernel density at u relative to its maximum on [a, b] (no underflow when the centre is far out).
float bl_rule1_density(int kernel, vec3 p, float zm, float u) {
  float z = (u - p.x) / p.y;
  if (kernel == 0) return exp(-0.5 * (z - zm) * (z + zm));
  if (kernel == 1) return 1.0;
  return max(0.0, 1.0 - abs(z) / BL_SQRT6);
}

// Support [l, r] of the renormalized kernel (Gaussian: density above e^-40 of its maximum) and the
// split point (the centre when inside).
vec3 bl_rule1_support(int kernel, vec3 p, float a, float b) {
  float zm = bl_rule1_zm(p, a, b);
  float reach = (kernel == 0 ? sqrt(zm * zm + 80.0) : (kernel == 1 ? BL_SQRT3 : BL_SQRT6)) * p.y;
  float l = max(a, p.x - reach), r = min(b, p.x + reach);
  return vec3(l, r, (p.x > l && p.x < r) ? p.x : r);
}

// Node k (|k| <= 26, h = 1/8) of tanh-sinh on [l, r]: vec2(u, weight); weight 0 when u rounds to an end.
vec2 bl_tanh_sinh_node(int k, float l, float r) {
  float t = float(k) * 0.125, s = 0.5 * BL_PI * sinh(t), e = exp(-2.0 * abs(s));
  float off = (r - l) * e / (1.0 + e);
  float u = k < 0 ? l + off : r - off;
  float ch = cosh(s);
  float w = 0.125 * 0.5 * (r - l) * 0.5 * BL_PI * cosh(t) / (ch * ch);
  return (off > 0.0 && u > l && u < r) ? vec2(u, w) : vec2(0.5 * (l + r), 0.0);
}

// The bimodal cut: vec2(centre, sigma) of the box kept after cutting [lo, hi] at `at` (count == 1).
vec2 bl_bimodal_cut(float mu, float sigma, float lo, float hi, float at, int count) {
  if (count != 1) return vec2(mu, sigma);
  float l = mu >= at ? at : lo, r = mu >= at ? hi : at;
  return vec2(0.5 * (l + r), (r - l) / (2.0 * BL_SQRT3));
}
