#include "transforms/pups/search.h"

#include <cmath>
#include <stdexcept>

#include "transforms/pups/mask_weight.h"
#include "transforms/pups/refinement.h"

namespace pupwave::pups {

namespace {

// (sum of even taps - sum of odd taps) / sum of |taps|: zero when B . 1 = 0.
double leak(const DesignParams& p) {
  const Refinement r = refine(p);
  double d = 0, s = 0;
  for (std::size_t i = 0; i < r.coeffs.size(); ++i) {
    d += ((r.first + static_cast<int>(i)) % 2 == 0 ? 1.0 : -1.0) * r.coeffs[i];
    s += std::abs(r.coeffs[i]);
  }
  return d / s;
}

void check(const SearchSpace& s) {
  if (!(s.c_step > 0) || !(s.c_hi >= s.c_lo) || !(s.c_lo > 0) || (s.c_hi - s.c_lo) / s.c_step > 1000)
    throw std::invalid_argument("search: c needs 0 < lo <= hi and a step giving at most 1000 values");
  if (s.extensions.empty() || s.boundaries.empty())
    throw std::invalid_argument("search: no l or boundary given");
  for (int l : s.extensions)
    if (l < 0 || l % 2 != 0 || l > 256) throw std::invalid_argument("search: every l must be even, 0..256");
}

// The weight parameter sets of the space (l and boundary not yet applied).
std::vector<DesignParams> weights(const SearchSpace& s, std::vector<std::string>* skipped) {
  std::vector<DesignParams> out;
  auto skip = [skipped](const std::string& why) {
    if (skipped) skipped->push_back(why);
  };
  switch (s.weight) {
    case WeightKind::bspline:
      for (int d : s.degrees) {
        DesignParams p;
        p.degree = d;
        p.samples = s.samples;
        out.push_back(p);
      }
      break;
    case WeightKind::cinpact:
    case WeightKind::cinpact_interp:
      for (int k = 0; s.c_lo + k * s.c_step <= s.c_hi * (1 + 1e-12); ++k) {
        DesignParams p;
        p.weight = s.weight;
        p.c = s.c_lo + k * s.c_step;
        p.samples = s.samples;
        std::vector<double> sigmas;
        if (s.leak_free_sigma) {
          sigmas = leak_free_sigmas(p);
          if (sigmas.empty()) skip("c=" + std::to_string(p.c) + ": no sigma with B.1 = 0");
        } else {
          const double best = optimize_sigma(p);
          for (double f : s.sigma_scales) sigmas.push_back(f * best);
        }
        for (double sg : sigmas) {
          p.sigma = sg;
          out.push_back(p);
        }
      }
      break;
    case WeightKind::polynomial:
      for (double t : s.mask_params) try {
          out.push_back(
              polynomial_weight_for_mask(vanishing_moment_mask(s.moments, t), s.poly_degree, s.samples)
                  .params);
        } catch (const std::invalid_argument& e) {
          skip("mask t=" + std::to_string(t) + ": " + e.what());
        }
      break;
    case WeightKind::given: throw std::invalid_argument("search: 'given' is not a weight function");
  }
  return out;
}

}  // namespace

std::vector<double> leak_free_sigmas(DesignParams p, double lo, double hi) {
  if (p.weight != WeightKind::cinpact && p.weight != WeightKind::cinpact_interp)
    throw std::invalid_argument("leak-free sigma needs a CINPACT weight");
  constexpr double kRatio = 1.08;  // grid fine enough to separate the roots met in practice
  std::vector<double> roots;
  p.sigma = lo;
  double prev_s = lo, prev = leak(p);
  for (double s = lo * kRatio; s <= hi; s *= kRatio) {
    p.sigma = s;
    const double f = leak(p);
    if ((f > 0) != (prev > 0)) {
      double a = prev_s, b = s, fa = prev;
      for (int it = 0; it < 60 && b - a > 1e-14 * b; ++it) {
        p.sigma = 0.5 * (a + b);
        const double fm = leak(p);
        ((fm > 0) == (fa > 0) ? a : b) = p.sigma;
      }
      roots.push_back(0.5 * (a + b));
    }
    prev = f;
    prev_s = s;
  }
  return roots;
}

std::vector<std::string> search_candidates(const SearchSpace& space, std::vector<std::string>* skipped) {
  check(space);
  std::vector<std::string> out;
  for (const DesignParams& p : weights(space, skipped))
    for (int l : space.extensions) try {
        const FilterBank bank = design(p, ExtensionRule{l});
        for (BoundaryRule b : space.boundaries) out.push_back(canonical_spec_body(bank, b));
      } catch (const std::invalid_argument& e) {
        if (skipped) skipped->push_back(to_string(p.weight) + " l=" + std::to_string(l) + ": " + e.what());
      }
  return out;
}

}  // namespace pupwave::pups
