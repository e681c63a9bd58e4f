// Variational subdivision against independent references: the 4-point rule, the natural
// interpolating cubic spline, and polynomial reproduction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "transforms/kobbelt/kobbelt_transform.h"
#include "transforms/kobbelt/subdivision.h"

namespace pupwave::kobbelt {
namespace {

// Natural cubic spline through (i, y[i]), i = 0 .. n-1, written here independently of the
// library: second derivatives M from the classical tridiagonal system (Thomas algorithm),
// M_0 = M_{n-1} = 0, linear continuation beyond the last knot.
class NaturalSpline {
 public:
  explicit NaturalSpline(std::vector<double> y) : y_(std::move(y)), m_(y_.size(), 0.0) {
    const std::size_t n = y_.size();
    if (n < 3) return;
    std::vector<double> c(n, 0.0), d(n, 0.0);  // forward sweep of M_{i-1} + 4 M_i + M_{i+1}
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double rhs = 6.0 * (y_[i - 1] - 2.0 * y_[i] + y_[i + 1]);
      const double denom = 4.0 - (i > 1 ? c[i - 1] : 0.0);
      c[i] = 1.0 / denom;
      d[i] = (rhs - (i > 1 ? d[i - 1] : 0.0)) / denom;
    }
    for (std::size_t i = n - 2; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
  }
  double operator()(double x) const {
    const std::size_t n = y_.size();
    if (n == 1) return y_[0];
    if (x > static_cast<double>(n - 1)) {  // natural spline continues linearly
      const double slope = y_[n - 1] - y_[n - 2] + m_[n - 2] / 6.0;
      return y_[n - 1] + slope * (x - static_cast<double>(n - 1));
    }
    const auto i = std::min(static_cast<std::size_t>(x), n - 2);
    const double a = static_cast<double>(i + 1) - x, b = x - static_cast<double>(i);
    return a * y_[i] + b * y_[i + 1] + ((a * a * a - a) * m_[i] + (b * b * b - b) * m_[i + 1]) / 6.0;
  }

 private:
  std::vector<double> y_, m_;
};

// Synthesis with zero details = one subdivision step of the coarse samples.
std::vector<double> subdivide_line(const std::string& body, std::span<const double> coarse, std::size_t n) {
  std::vector<double> line(n, 0.0);
  std::copy(coarse.begin(), coarse.end(), line.begin());
  make_kobbelt_transform_from_spec(body)->synthesize(std::span<double>(line));
  return line;
}

TEST(Subdivision, FourPointRuleInTheInterior) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (std::size_t n : {9u, 10u, 33u, 64u, 101u}) {
    std::vector<double> c(coarse_size(n));
    for (auto& v : c) v = uni(rng);
    for (const char* body : {"k4pt", "k4pt-raw"}) {
      const std::vector<double> f = subdivide_line(body, c, n);
      for (std::size_t j = 1; j + 2 < c.size(); ++j) {
        const double rule = (-c[j - 1] + 9 * c[j] + 9 * c[j + 1] - c[j + 2]) / 16;
        ASSERT_NEAR(f[2 * j + 1], rule, 1e-14) << body << " n=" << n << " j=" << j;
      }
      for (std::size_t j = 0; j < c.size(); ++j) ASSERT_EQ(f[2 * j], c[j]);
    }
  }
}

// Kspl reproduces the natural interpolating cubic spline everywhere, including the end
// segments and (even lengths) the sample beyond the last knot.
TEST(Subdivision, KsplIsTheNaturalCubicSpline) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (std::size_t n = 2; n <= 80; ++n) {
    std::vector<double> c(coarse_size(n));
    for (auto& v : c) v = uni(rng);
    const NaturalSpline spline(c);
    const std::vector<double> f = subdivide_line("kspl", c, n);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NEAR(f[i], spline(0.5 * static_cast<double>(i)), 1e-12) << "n=" << n << " i=" << i;
    }
  }
}

// Refining samples of a spline again gives the same spline: several levels stay on it.
TEST(Subdivision, KsplRefinesSplineSamplesOnTheSameSpline) {
  const std::vector<double> knots{0.0, 1.0, -0.5, 2.0, 0.25, 0.0, 1.5};
  const NaturalSpline spline(knots);
  std::vector<double> values = knots;
  for (int level = 1; level <= 4; ++level) {
    values = refine_open(Scheme::kspl, values);
    const double h = std::ldexp(1.0, -level);
    for (std::size_t i = 0; i < values.size(); ++i) {
      ASSERT_NEAR(values[i], spline(h * static_cast<double>(i)), 1e-12) << level << " " << i;
    }
  }
}

// Polynomials the energy annihilates are reproduced exactly: K2, Kspl, K4pt cubics (inside),
// K3 quintics (inside); every scheme reproduces straight lines up to the ends.
TEST(Subdivision, PolynomialReproduction) {
  const auto poly = [](double x, int degree) { return std::pow(x / 60.0 - 1.1, degree); };
  struct Case {
    Scheme s;
    int degree;
  };
  for (const Case cs :
       {Case{Scheme::k2, 3}, Case{Scheme::kspl, 3}, Case{Scheme::k4pt, 3}, Case{Scheme::k3, 5}}) {
    std::vector<double> c(120), line(20);
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = poly(static_cast<double>(i), cs.degree);
    for (std::size_t i = 0; i < line.size(); ++i) line[i] = poly(static_cast<double>(i), 1);
    const std::vector<double> f = refine_open(cs.s, c), g = refine_open(cs.s, line);
    for (std::size_t i = 80; i + 80 < f.size(); ++i) {  // 40 odd samples from the ends
      ASSERT_NEAR(f[i], poly(0.5 * static_cast<double>(i), cs.degree), 1e-12)
          << scheme_name(cs.s) << " i=" << i;
    }
    for (std::size_t i = 0; i < g.size(); ++i) {
      ASSERT_NEAR(g[i], poly(0.5 * static_cast<double>(i), 1), 1e-12) << scheme_name(cs.s);
    }
  }
}

TEST(Subdivision, PolylineCountsAndInterpolation) {
  const std::vector<Point2> pts{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {2, -1}};
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
    for (bool closed : {false, true}) {
      const auto out = subdivide(pts, {s, 3, closed, Parameterization::uniform});
      ASSERT_EQ(out.size(), closed ? 8 * pts.size() : 8 * (pts.size() - 1) + 1);
      for (std::size_t i = 0; i < pts.size(); ++i) {  // interpolating: old points stay
        EXPECT_EQ(out[8 * i].x, pts[i].x);
        EXPECT_EQ(out[8 * i].y, pts[i].y);
      }
    }
  }
}

// A closed polygon's refinement is invariant under cyclic relabelling of its points and
// equals the open refinement of a long periodic repetition in the middle.
TEST(Subdivision, ClosedPolygonIsPeriodic) {
  const std::vector<Point2> pts{{0, 0}, {2, 0.5}, {3, 2}, {1, 3}, {-1, 1.5}};
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
    const auto a = subdivide(pts, {s, 2, true, Parameterization::uniform});
    std::vector<Point2> rotated(pts.begin() + 2, pts.end());
    rotated.insert(rotated.end(), pts.begin(), pts.begin() + 2);
    const auto b = subdivide(rotated, {s, 2, true, Parameterization::uniform});
    for (std::size_t i = 0; i < a.size(); ++i) {
      const auto& q = b[(i + a.size() - 8) % a.size()];
      ASSERT_NEAR(a[i].x, q.x, 1e-12) << scheme_name(s);
      ASSERT_NEAR(a[i].y, q.y, 1e-12) << scheme_name(s);
    }
    // Four-point rule on the closed polygon, wrapping around.
    if (s == Scheme::k4pt) {
      const auto one = subdivide(pts, {s, 1, true, Parameterization::uniform});
      const std::size_t n = pts.size();
      for (std::size_t j = 0; j < n; ++j) {
        const auto& p0 = pts[(j + n - 1) % n];
        const auto &p1 = pts[j], &p2 = pts[(j + 1) % n], &p3 = pts[(j + 2) % n];
        EXPECT_NEAR(one[2 * j + 1].x, (-p0.x + 9 * p1.x + 9 * p2.x - p3.x) / 16, 1e-14);
      }
    }
  }
}

// Divided differences reduce to forward differences for uniform parameters, and are
// invariant under an affine change of the parameter.
TEST(Subdivision, NonUniformK2AndK3) {
  for (Scheme s : {Scheme::k2, Scheme::k3}) {
    for (std::size_t n : {2u, 3u, 4u, 5u, 6u, 17u, 40u}) {
      std::vector<double> t(n), t_affine(n);
      for (std::size_t i = 0; i < n; ++i) {
        t[i] = static_cast<double>(i);
        t_affine[i] = 3.0 + 0.37 * t[i];
      }
      const auto u = euler_lagrange_system(s, n), a = euler_lagrange_system(s, t),
                 b = euler_lagrange_system(s, t_affine);
      for (std::size_t j = 0; j < n / 2; ++j) {
        const auto ru = euler_lagrange_row(u, j), ra = euler_lagrange_row(a, j),
                   rb = euler_lagrange_row(b, j);
        for (std::size_t k = 0; k < 7; ++k) {
          ASSERT_NEAR(ra[k], ru[k], 1e-12) << scheme_name(s) << n;
          ASSERT_NEAR(rb[k], ru[k], 1e-9) << scheme_name(s) << n;
        }
      }
    }
  }
  // Centripetal K2 and K3 interpolate, reproduce straight lines with any parameters.
  const std::vector<Point2> line{{0, 0}, {0.1, 0.2}, {2, 4}, {2.5, 5}, {7, 14}};
  for (Scheme s : {Scheme::k2, Scheme::k3}) {
    const auto out = subdivide(line, {s, 3, false, Parameterization::centripetal});
    for (const auto& p : out) EXPECT_NEAR(p.y, 2 * p.x, 1e-10);
  }
}

TEST(Subdivision, RejectsBadInput) {
  const std::vector<Point2> one{{0, 0}}, two{{0, 0}, {1, 1}}, dup{{0, 0}, {0, 0}, {1, 1}};
  EXPECT_THROW(subdivide(one, {}), std::invalid_argument);
  EXPECT_THROW(subdivide(two, {Scheme::k2, 13, false, Parameterization::uniform}), std::invalid_argument);
  EXPECT_THROW(subdivide(two, {Scheme::k2, -1, false, Parameterization::uniform}), std::invalid_argument);
  EXPECT_THROW(subdivide(dup, {Scheme::k2, 1, false, Parameterization::centripetal}), std::invalid_argument);
  EXPECT_THROW(subdivide(two, {Scheme::kspl, 1, false, Parameterization::centripetal}),
               std::invalid_argument);
  const std::vector<Point2> nan{{0, 0}, {std::nan(""), 1}};
  EXPECT_THROW(subdivide(nan, {}), std::invalid_argument);
  EXPECT_EQ(subdivide(two, {Scheme::k3, 0, false, Parameterization::uniform}).size(), 2u);
  EXPECT_THROW(parse_scheme("k5"), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::kobbelt
