#include "transforms/kobbelt/kobbelt_transform.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "transforms/kobbelt/cyclic_reduction.h"
#include "transforms/lifting.h"
#include "transforms/scratch.h"

namespace pupwave {
namespace kobbelt {

std::vector<double> stabilizing_weights(Scheme scheme) {
  switch (scheme) {
    case Scheme::k2: return {-3.0 / 64, 15.0 / 64, 15.0 / 64, -3.0 / 64};
    case Scheme::k3: return {-25.0 / 512, 105.0 / 512, 105.0 / 512, -25.0 / 512};
    case Scheme::kspl: return {-7.0 / 144, 31.0 / 144, 31.0 / 144, -7.0 / 144};
    case Scheme::k4pt: return {-1.0 / 32, 9.0 / 32, 9.0 / 32, -1.0 / 32};
  }
  throw std::invalid_argument("stabilizing_weights: unknown scheme");
}

}  // namespace kobbelt

namespace {

using kobbelt::BandedStep;
using kobbelt::Scheme;

// Everything one line length needs; built once per length and shared between threads.
struct Plan {
  kobbelt::EulerLagrangeSystem el;
  kobbelt::CyclicReduction cr;
  BandedStep v;  // coarse[i] += sum V * detail[i-2 .. i+1] (Eq. 19), empty when raw
};

// V as rows over the coarse wire: column j (detail j) puts weights w[0..3] on coarse
// j-1 .. j+2; a weight that falls outside the coarse wire goes to the nearest coarse sample.
BandedStep stabilizing_step(Scheme scheme, std::size_t n) {
  const std::size_t ne = coarse_size(n), no = detail_size(n);
  const std::vector<double> w = kobbelt::stabilizing_weights(scheme);
  BandedStep v = kobbelt::make_banded_step(ne, 4, -2);
  for (std::size_t j = 0; j < no; ++j) {
    for (std::size_t k = 0; k < 4; ++k) {
      const auto row = std::clamp<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(j + k) - 1, 0,
                                                  static_cast<std::ptrdiff_t>(ne) - 1);
      const std::ptrdiff_t tap = static_cast<std::ptrdiff_t>(j) - row + 2;
      if (tap < 0 || tap > 3) throw std::logic_error("stabilizing_step: fold outside the band");
      v.at(static_cast<std::size_t>(row), static_cast<std::size_t>(tap)) += w[k];
    }
  }
  return v;
}

// detail <- A detail for the unit-diagonal tridiagonal A, in place (keeps the old left value).
template <class T>
void multiply_unit_tridiagonal(const kobbelt::Tridiagonal& a, std::span<T> x) {
  const std::size_t m = x.size();
  T previous = T(0);
  for (std::size_t j = 0; j < m; ++j) {
    const T current = x[j];
    T sum = current;
    if (j > 0) sum += T(a.sub[j]) * previous;
    if (j + 1 < m) sum += T(a.super[j]) * x[j + 1];
    previous = current;
    x[j] = sum;
  }
}

class KobbeltTransform final : public Transform1D {
 public:
  KobbeltTransform(Scheme scheme, bool stabilized, std::string body)
      : scheme_(scheme), stabilized_(stabilized), body_(std::move(body)) {}

  std::string spec() const override { return "kobbelt:" + body_; }
  void analyze(std::span<double> line) const override { analyze_impl(line); }
  void synthesize(std::span<double> line) const override { synthesize_impl(line); }
  void analyze(std::span<float> line) const override { analyze_impl(line); }
  void synthesize(std::span<float> line) const override { synthesize_impl(line); }

 private:
  // Eq. (18): coarse = even samples, detail = C p = A p_odd + B p_even; then V (Eq. 19).
  template <class T>
  void analyze_impl(std::span<T> line) const {
    if (line.size() < 2) return;
    const std::shared_ptr<const Plan> plan = plan_for(line.size());
    const std::size_t ne = coarse_size(line.size());
    lifting::split<T>(line, thread_scratch<T>(detail_size(line.size())));
    const std::span<T> coarse = line.first(ne), detail = line.subspan(ne);
    multiply_unit_tridiagonal(plan->el.a, detail);
    kobbelt::lift<T>(plan->el.b, coarse, detail);
    if (stabilized_) kobbelt::lift<T>(plan->v, detail, coarse);
  }

  // Fig. 12/13 backwards: undo V, predict odd with -B, cyclic reduction for A^{-1}, merge.
  template <class T>
  void synthesize_impl(std::span<T> line) const {
    if (line.size() < 2) return;
    const std::shared_ptr<const Plan> plan = plan_for(line.size());
    const std::size_t ne = coarse_size(line.size());
    const std::span<T> coarse = line.first(ne), detail = line.subspan(ne);
    if (stabilized_) kobbelt::unlift<T>(plan->v, detail, coarse);
    kobbelt::unlift<T>(plan->el.b, coarse, detail);
    plan->cr.solve(detail);
    lifting::merge<T>(line, thread_scratch<T>(detail_size(line.size())));
  }

  std::shared_ptr<const Plan> plan_for(std::size_t n) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = cache_.find(n);
    if (it != cache_.end()) return it->second;
    kobbelt::EulerLagrangeSystem el = kobbelt::euler_lagrange_system(scheme_, n);
    kobbelt::CyclicReduction cr(el.a);
    BandedStep v = stabilized_ ? stabilizing_step(scheme_, n) : BandedStep{};
    auto plan = std::make_shared<const Plan>(Plan{std::move(el), std::move(cr), std::move(v)});
    if (cache_.size() >= kMaxCachedLengths) cache_.clear();  // bounded memory
    cache_.emplace(n, plan);
    return plan;
  }

  static constexpr std::size_t kMaxCachedLengths = 64;
  Scheme scheme_;
  bool stabilized_;
  std::string body_;
  mutable std::mutex mutex_;
  mutable std::map<std::size_t, std::shared_ptr<const Plan>> cache_;
};

constexpr std::string_view kRawSuffix = "-raw";

}  // namespace

Transform1DPtr make_kobbelt_transform_from_spec(std::string_view body) {
  std::string_view name = body;
  bool stabilized = true;
  if (name.size() > kRawSuffix.size() && name.ends_with(kRawSuffix)) {
    name.remove_suffix(kRawSuffix.size());
    stabilized = false;
  }
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
    if (name == kobbelt::scheme_name(s)) {
      return std::make_shared<KobbeltTransform>(s, stabilized, std::string(body));
    }
  }
  std::string valid;
  for (const std::string& spec : kobbelt_transform_specs()) {
    valid += (valid.empty() ? "" : ", ") + spec.substr(8);
  }
  throw std::invalid_argument("unknown Kobbelt transform 'kobbelt:" + std::string(body) +
                              "' (valid after 'kobbelt:': " + valid + ")");
}

std::vector<std::string> kobbelt_transform_specs() {
  std::vector<std::string> specs;
  for (std::string_view suffix : {std::string_view(), kRawSuffix}) {
    for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
      specs.push_back("kobbelt:" + std::string(kobbelt::scheme_name(s)) + std::string(suffix));
    }
  }
  return specs;
}

}  // namespace pupwave
