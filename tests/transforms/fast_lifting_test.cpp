// The fast lifting paths (interior without index checks, reflected ends gathered once, taps
// outermost over vector lanes, column blocks) against a plain reference that reads every tap
// through reflect_index: equal results for every filter length and offset, every boundary
// rule, line lengths 1..9 and beyond the lane blocks, column widths that are not multiples of
// the lane count, and whole PUPs transforms (line and column forms) built from their banks.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "transforms/kobbelt/kobbelt_transform.h"
#include "transforms/lifting.h"
#include "transforms/lifting_columns.h"
#include "transforms/pups/pups_transform.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

using lifting::Boundary;
using lifting::Extension;

// target[i] += sign * sum_k taps[k] * source[reflect(i + offset + k)], one sample at a time.
// A two-tap step's interior is written (sign * t0) x + (sign * t1) y by the library: the same
// sum, as negation is exact; only the sign of a zero sum could differ, which == ignores.
template <class T>
void reference_step(const std::vector<T>& source, Boundary b, std::vector<T>& target,
                    const std::vector<double>& taps, std::ptrdiff_t offset, T sign) {
  if (source.empty()) return;
  for (std::size_t i = 0; i < target.size(); ++i) {
    T s = 0;
    for (std::size_t k = 0; k < taps.size(); ++k)
      s += T(taps[k]) * source[lifting::reflect_index(std::ptrdiff_t(i + k) + offset, source.size(), b)];
    target[i] += sign * s;
  }
}

template <class T>
std::vector<T> random_wire(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> v(-100, 100);
  std::vector<T> w(n);
  for (auto& x : w) x = T(v(rng));
  return w;
}

const Boundary kBoundaries[] = {{Extension::whole_sample, Extension::whole_sample},
                                {Extension::half_sample, Extension::half_sample},
                                {Extension::whole_sample, Extension::half_sample},
                                {Extension::half_sample, Extension::whole_sample}};

// Filters of 1..20 taps (and Kobbelt's stabilizing filters) at offsets placing them left of,
// around and right of the target, on wires of 1..9 samples and past two lane blocks.
template <class T>
void expect_steps_match_reference() {
  std::mt19937 rng(7);
  std::vector<std::vector<double>> filters;
  for (std::size_t nk = 1; nk <= 20; ++nk) {
    std::vector<double> f(nk);
    for (auto& x : f) x = std::uniform_real_distribution<double>(-0.7, 0.7)(rng);
    filters.push_back(f);
  }
  for (auto s : {kobbelt::Scheme::k2, kobbelt::Scheme::k4pt})
    filters.push_back(kobbelt::stabilizing_weights(s));
  const std::size_t lengths[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 33, 70};
  for (const auto& f : filters) {
    const auto nk = std::ptrdiff_t(f.size());
    for (std::ptrdiff_t offset = -nk - 2; offset <= 3; ++offset)
      for (std::size_t ms : lengths)
        for (std::size_t mt : {ms, ms + 1, ms > 1 ? ms - 1 : ms})
          for (const Boundary& b : kBoundaries)
            for (const T sign : {T(1), T(-1)}) {
              const auto source = random_wire<T>(ms, rng);
              const auto target = random_wire<T>(mt, rng);
              auto expected = target;
              reference_step(source, b, expected, f, offset, sign);
              auto got = target;
              lifting::detail::apply<T>(source, b, got, lifting::Taps{f, offset}, sign);
              ASSERT_EQ(got, expected) << "nk=" << nk << " offset=" << offset << " ms=" << ms << " mt=" << mt;
              // The column form: the same step on every column of a block of rows.
              for (std::size_t width : {1u, 5u, 17u, 40u}) {
                std::vector<T> src(ms * width), tgt(mt * width);
                for (std::size_t i = 0; i < ms; ++i)
                  for (std::size_t c = 0; c < width; ++c) src[i * width + c] = source[i] + T(c);
                for (std::size_t i = 0; i < mt; ++i)
                  for (std::size_t c = 0; c < width; ++c) tgt[i * width + c] = target[i] - T(c);
                auto col_expected = tgt;
                for (std::size_t c = 0; c < width; ++c) {
                  std::vector<T> s1(ms), t1(mt);
                  for (std::size_t i = 0; i < ms; ++i) s1[i] = src[i * width + c];
                  for (std::size_t i = 0; i < mt; ++i) t1[i] = tgt[i * width + c];
                  reference_step(s1, b, t1, f, offset, sign);
                  for (std::size_t i = 0; i < mt; ++i) col_expected[i * width + c] = t1[i];
                }
                lifting::columns::apply<T>(src.data(), ms, b, tgt.data(), mt, lifting::Taps{f, offset}, sign,
                                           width);
                ASSERT_EQ(tgt, col_expected) << "columns nk=" << nk << " offset=" << offset << " ms=" << ms
                                             << " mt=" << mt << " width=" << width;
              }
            }
  }
}

TEST(FastLifting, StepsMatchReferenceFloat) { expect_steps_match_reference<float>(); }
TEST(FastLifting, StepsMatchReferenceDouble) { expect_steps_match_reference<double>(); }

// A PUPs analysis (or synthesis) from its factorization, every step through reference_step.
template <class T>
std::vector<T> reference_pups(const pups::PupsTransform& t, std::vector<T> line, bool analysis) {
  const std::size_t n = line.size();
  if (n <= 1) return line;
  const std::size_t ne = (n + 1) / 2;
  const auto& lf = t.factorization();
  const auto rules = t.boundary() == pups::BoundaryRule::line_wss
                         ? lifting::whole_sample_symmetric_wires(n)
                         : lifting::WireBoundaries{{Extension::half_sample, Extension::half_sample},
                                                   {Extension::half_sample, Extension::half_sample}};
  std::vector<T> even, odd;
  if (analysis) {
    for (std::size_t i = 0; i < n; ++i) (i % 2 ? odd : even).push_back(line[i]);
  } else {
    even.assign(line.begin(), line.begin() + std::ptrdiff_t(ne));
    odd.assign(line.begin() + std::ptrdiff_t(ne), line.end());
    for (auto& v : even) v /= T(lf.even_scale);
    for (auto& v : odd) v /= T(lf.odd_scale);
  }
  const std::size_t steps = lf.steps.size();
  for (std::size_t q = 0; q < steps; ++q) {
    const auto& s = lf.steps[analysis ? q : steps - 1 - q];
    const T sign = analysis ? T(1) : T(-1);
    if (s.kind == pups::LiftingStep::Kind::predict)
      reference_step(even, rules.even, odd, s.filter.c, s.filter.lo, sign);
    else
      reference_step(odd, rules.odd, even, s.filter.c, s.filter.lo, sign);
  }
  if (analysis) {
    for (auto& v : even) v *= T(lf.even_scale);
    for (auto& v : odd) v *= T(lf.odd_scale);
    std::copy(even.begin(), even.end(), line.begin());
    std::copy(odd.begin(), odd.end(), line.begin() + std::ptrdiff_t(ne));
  } else {
    for (std::size_t i = 0; i < n; ++i) line[i] = i % 2 ? odd[i / 2] : even[i / 2];
  }
  return line;
}

template <class T>
void expect_pups_matches_reference(const std::string& spec) {
  const auto holder = make_transform(spec);
  const auto* t = dynamic_cast<const pups::PupsTransform*>(holder.get());
  ASSERT_NE(t, nullptr) << spec;
  std::mt19937 rng(11);
  const std::size_t lengths[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 31, 33, 64, 65, 150};
  for (std::size_t n : lengths)
    for (bool analysis : {true, false}) {
      const auto input = random_wire<T>(n, rng);
      const auto expected = reference_pups(*t, input, analysis);
      auto line = input;
      if (analysis)
        t->analyze(std::span<T>(line));
      else
        t->synthesize(std::span<T>(line));
      ASSERT_EQ(line, expected) << spec << " n=" << n << (analysis ? " analysis" : " synthesis");
      for (std::size_t width : {3u, 17u, 32u}) {
        std::vector<T> block(n * width), col_expected(n * width);
        for (std::size_t c = 0; c < width; ++c) {
          std::vector<T> column(n);
          for (std::size_t i = 0; i < n; ++i) block[i * width + c] = column[i] = input[i] * T(c + 1) / T(3);
          column = reference_pups(*t, column, analysis);
          for (std::size_t i = 0; i < n; ++i) col_expected[i * width + c] = column[i];
        }
        if (analysis)
          t->analyze_columns(std::span<T>(block), width);
        else
          t->synthesize_columns(std::span<T>(block), width);
        ASSERT_EQ(block, col_expected) << spec << " columns n=" << n << " width=" << width;
      }
    }
}

TEST(FastLifting, PupsBanksMatchReference) {
  for (const char* spec : {"pups:chaikin", "pups:cubic-bspline", "pups:cinpact-interp-vm4",
                           "pups:poly16-vm4-cg", "pups:cinpact-c3-ext", "pups:cinpact-interp-c5-ext"}) {
    expect_pups_matches_reference<float>(spec);
    expect_pups_matches_reference<double>(spec);
  }
}

}  // namespace
}  // namespace pupwave
