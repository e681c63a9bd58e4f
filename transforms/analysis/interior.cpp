// The bi-infinite side of the figures of merit: a transform's single-level filters read from
// impulse responses away from the ends, their iteration over levels, the Katto-Yasuda coding
// gain of the resulting tree filter bank and vanishing moments.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "transforms/analysis/merit.h"

namespace pupwave::merit {

namespace {

// Probe line: long enough for the longest preset filters (about 90 taps for l = 32 banks)
// to sit clear of both ends; IIR (Kobbelt) responses have decayed far below the tolerances.
constexpr std::size_t kProbe = 1024;

// Taps of `v` between the first and last entry above tol * max|v|; first = index of taps[0].
Taps support(const std::vector<double>& v, long origin) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  std::size_t lo = 0, hi = v.size();
  while (lo < hi && std::abs(v[lo]) <= 1e-13 * m) ++lo;
  while (hi > lo && std::abs(v[hi - 1]) <= 1e-13 * m) --hi;
  Taps t;
  t.c.assign(v.begin() + static_cast<std::ptrdiff_t>(lo), v.begin() + static_cast<std::ptrdiff_t>(hi));
  t.first = static_cast<long>(lo) - origin;
  return t;
}

std::vector<double> impulse(const Transform1D& t, std::size_t at, bool analysis) {
  std::vector<double> line(kProbe, 0.0);
  line[at] = 1.0;
  if (analysis)
    t.analyze(std::span<double>(line));
  else
    t.synthesize(std::span<double>(line));
  return line;
}

// Row `k` of the one-level analysis operator: entry j is the coefficient k of impulse j.
std::vector<std::vector<double>> analysis_rows(const Transform1D& t, const std::vector<std::size_t>& ks) {
  std::vector<std::vector<double>> rows(ks.size(), std::vector<double>(kProbe, 0.0));
  for (std::size_t j = 0; j < kProbe; ++j) {
    const std::vector<double> col = impulse(t, j, true);
    for (std::size_t r = 0; r < ks.size(); ++r) rows[r][j] = col[ks[r]];
  }
  return rows;
}

bool same_taps(const Taps& a, const Taps& b, long shift) {
  if (a.c.size() != b.c.size() || a.first != b.first + shift) return false;
  double m = 0, d = 0;
  for (std::size_t i = 0; i < a.c.size(); ++i) {
    m = std::max(m, std::abs(a.c[i]));
    d = std::max(d, std::abs(a.c[i] - b.c[i]));
  }
  return d <= 1e-9 * m;
}

// Coefficient k of a band sits at sample 2k (+1 for details); taps are recorded relative to
// 2k, so two neighbouring coefficients must give the same taps if the ends are out of reach.
Taps checked(const Taps& a, const Taps& b, const char* what) {
  if (!same_taps(a, b, 0))
    throw std::invalid_argument(std::string("interior filters: the ") + what +
                                " responses are not shift invariant on the probe line");
  return a;
}

std::vector<double> convolve(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
  return out;
}

std::vector<double> upsample(const std::vector<double>& a, std::size_t factor) {
  std::vector<double> out((a.size() - 1) * factor + 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) out[i * factor] = a[i];
  return out;
}

// Variance of sum_n f[n] x[n] for a unit-variance AR(1) x: sum_k r_f[k] rho^|k|.
double ar1_variance(const std::vector<double>& f, double rho) {
  double v = 0;
  const std::size_t n = f.size();
  for (std::size_t k = 0; k < n; ++k) {
    double r = 0;
    for (std::size_t i = 0; i + k < n; ++i) r += f[i] * f[i + k];
    v += (k == 0 ? 1.0 : 2.0) * r * std::pow(rho, static_cast<double>(k));
  }
  return v;
}

double energy(const std::vector<double>& f) {
  double e = 0;
  for (double x : f) e += x * x;
  return e;
}

}  // namespace

InteriorFilters interior_filters(const Transform1D& t) {
  const std::size_t half = kProbe / 2, kc = kProbe / 4, kd = half + kProbe / 4;
  const auto rows = analysis_rows(t, {kc, kc + 1, kd, kd + 1});
  const long c = static_cast<long>(2 * kc), d = static_cast<long>(2 * (kd - half));
  InteriorFilters f;
  f.h0 = checked(support(rows[0], c), support(rows[1], c + 2), "coarse analysis");
  f.h1 = checked(support(rows[2], d), support(rows[3], d + 2), "detail analysis");
  f.g0 = checked(support(impulse(t, kc, false), c), support(impulse(t, kc + 1, false), c + 2),
                 "coarse synthesis");
  f.g1 = checked(support(impulse(t, kd, false), d), support(impulse(t, kd + 1, false), d + 2),
                 "detail synthesis");
  return f;
}

int vanishing_moments(const Taps& f, double tol, double* residual) {
  constexpr int kMax = 12;
  const double centre = static_cast<double>(f.first) + 0.5 * static_cast<double>(f.c.size() - 1);
  for (int k = 0; k < kMax; ++k) {
    double m = 0, s = 0;
    for (std::size_t i = 0; i < f.c.size(); ++i) {
      const double p = std::pow(static_cast<double>(f.first) + static_cast<double>(i) - centre, k);
      m += f.c[i] * p;
      s += std::abs(f.c[i] * p);
    }
    if (std::abs(m) > tol * s) {
      if (residual) *residual = std::abs(m) / s;
      return k;
    }
  }
  if (residual) *residual = 0;
  return kMax;
}

std::vector<double> norm_products(const InteriorFilters& f, int levels) {
  if (levels < 1 || levels > 12) throw std::invalid_argument("norm products: levels must be 1..12");
  std::vector<double> a{1.0}, s{1.0}, out;
  for (int j = 1; j <= levels; ++j) {
    const std::size_t up = std::size_t(1) << (j - 1);
    out.push_back(
        std::sqrt(energy(convolve(a, upsample(f.h1.c, up))) * energy(convolve(s, upsample(f.g1.c, up)))));
    a = convolve(a, upsample(f.h0.c, up));
    s = convolve(s, upsample(f.g0.c, up));
  }
  out.push_back(std::sqrt(energy(a) * energy(s)));
  return out;
}

double interior_coding_gain_db(const InteriorFilters& f, int levels, double rho) {
  if (levels < 1 || levels > 12) throw std::invalid_argument("interior coding gain: levels must be 1..12");
  std::vector<double> a{1.0}, s{1.0};  // equivalent coarse analysis / synthesis filters so far
  double log_sum = 0;                  // sum_b eta_b log10(sigma_b^2 |g_b|^2)
  for (int j = 1; j <= levels; ++j) {
    const std::size_t up = std::size_t(1) << (j - 1);
    const std::vector<double> hd = convolve(a, upsample(f.h1.c, up)), gd = convolve(s, upsample(f.g1.c, up));
    log_sum += std::ldexp(1.0, -j) * std::log10(ar1_variance(hd, rho) * energy(gd));
    a = convolve(a, upsample(f.h0.c, up));
    s = convolve(s, upsample(f.g0.c, up));
  }
  log_sum += std::ldexp(1.0, -levels) * std::log10(ar1_variance(a, rho) * energy(s));
  return -10.0 * log_sum;
}

}  // namespace pupwave::merit
