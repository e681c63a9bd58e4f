#include "transforms/pups/pups_transform.h"

#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "transforms/lifting.h"
#include "transforms/lifting_columns.h"
#include "transforms/pups/design.h"
#include "transforms/pups/stored_presets.h"
#include "transforms/scratch.h"

namespace pupwave {

namespace pups {

namespace {

// Half-sample symmetric extension of each wire at both ends: w[-1-k] = w[k] and
// w[m+k] = w[m-1-k]. Interleaved-line HSS would mix the wires (x[-1] = x[0] puts an even
// sample where an odd one belongs), which no lifting step can read; see docs/pups.md.
constexpr lifting::Boundary kWireHss{lifting::Extension::half_sample, lifting::Extension::half_sample};

// The rules each wire is read with on a line of n samples.
lifting::WireBoundaries wire_rules(BoundaryRule rule, std::size_t n) {
  if (rule == BoundaryRule::line_wss) return lifting::whole_sample_symmetric_wires(n);
  return {kWireHss, kWireHss};
}

// Bounded (as the synthesis-norms cache is) so that a stream of distinct specs, e.g. hostile
// file headers or a design search, cannot grow memory without limit.
constexpr std::size_t kMaxCachedSpecs = 256;

}  // namespace

PupsTransform::PupsTransform(const FilterBank& bank, std::string spec, BoundaryRule boundary)
    : bank_(bank), lifting_(factor_bank(bank, true)), spec_(std::move(spec)), boundary_(boundary) {
  for (const auto& s : lifting_.steps)
    steps_.push_back({s.kind == LiftingStep::Kind::predict, s.filter.c, s.filter.lo});
}

template <class T>
void PupsTransform::analyze_impl(std::span<T> line) const {
  const std::size_t n = line.size();
  if (n <= 1) return;  // one coarse sample, no detail: the identity (interface contract)
  lifting::split(line, thread_scratch<T>(n));  // n: the vectorized split
  const std::span<T> even = line.first((n + 1) / 2), odd = line.subspan((n + 1) / 2);
  const lifting::WireBoundaries rules = wire_rules(boundary_, n);
  for (const Step& s : steps_) {
    const lifting::Taps taps{s.taps, s.offset};
    if (s.predict)
      lifting::predict<T>(even, rules.even, odd, taps);
    else
      lifting::update<T>(odd, rules.odd, even, taps);
  }
  lifting::scale(even, lifting_.even_scale);
  lifting::scale(odd, lifting_.odd_scale);
}

template <class T>
void PupsTransform::synthesize_impl(std::span<T> line) const {
  const std::size_t n = line.size();
  if (n <= 1) return;
  const std::span<T> even = line.first((n + 1) / 2), odd = line.subspan((n + 1) / 2);
  lifting::undo_scale(even, lifting_.even_scale);
  lifting::undo_scale(odd, lifting_.odd_scale);
  const lifting::WireBoundaries rules = wire_rules(boundary_, n);
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    const lifting::Taps taps{it->taps, it->offset};
    if (it->predict)
      lifting::undo_predict<T>(even, rules.even, odd, taps);
    else
      lifting::undo_update<T>(odd, rules.odd, even, taps);
  }
  lifting::merge(line, thread_scratch<T>(n));  // n: the vectorized merge
}

// analyze_impl on every column of a block of rows: the same steps, each applied to whole rows
// (lifting::columns), so every sample gets the line form's operations in the same order.
template <class T>
void PupsTransform::analyze_columns_impl(std::span<T> block, std::size_t width) const {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n <= 1) return;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  col::split(block.data(), n, width, thread_scratch<T>(no * width).data());
  T* even = block.data();
  T* odd = even + ne * width;
  const lifting::WireBoundaries rules = wire_rules(boundary_, n);
  for (const Step& s : steps_) {
    const lifting::Taps taps{s.taps, s.offset};
    if (s.predict)
      col::apply<T>(even, ne, rules.even, odd, no, taps, T(1), width);
    else
      col::apply<T>(odd, no, rules.odd, even, ne, taps, T(1), width);
  }
  col::scale(even, ne * width, lifting_.even_scale);
  col::scale(odd, no * width, lifting_.odd_scale);
}

template <class T>
void PupsTransform::synthesize_columns_impl(std::span<T> block, std::size_t width) const {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n <= 1) return;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  T* even = block.data();
  T* odd = even + ne * width;
  col::undo_scale(even, ne * width, lifting_.even_scale);
  col::undo_scale(odd, no * width, lifting_.odd_scale);
  const lifting::WireBoundaries rules = wire_rules(boundary_, n);
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    const lifting::Taps taps{it->taps, it->offset};
    if (it->predict)
      col::apply<T>(even, ne, rules.even, odd, no, taps, T(-1), width);
    else
      col::apply<T>(odd, no, rules.odd, even, ne, taps, T(-1), width);
  }
  col::merge(block.data(), n, width, thread_scratch<T>(no * width).data());
}

void PupsTransform::analyze(std::span<double> line) const { analyze_impl(line); }
void PupsTransform::synthesize(std::span<double> line) const { synthesize_impl(line); }
void PupsTransform::analyze(std::span<float> line) const { analyze_impl(line); }
void PupsTransform::synthesize(std::span<float> line) const { synthesize_impl(line); }
void PupsTransform::analyze_columns(std::span<float> b, std::size_t w) const { analyze_columns_impl(b, w); }
void PupsTransform::synthesize_columns(std::span<float> b, std::size_t w) const {
  synthesize_columns_impl(b, w);
}
void PupsTransform::analyze_columns(std::span<double> b, std::size_t w) const { analyze_columns_impl(b, w); }
void PupsTransform::synthesize_columns(std::span<double> b, std::size_t w) const {
  synthesize_columns_impl(b, w);
}

}  // namespace pups

Transform1DPtr make_pups_transform(const pups::FilterBank& bank, std::string spec,
                                   pups::BoundaryRule boundary) {
  return std::make_shared<const pups::PupsTransform>(bank, std::move(spec), boundary);
}

namespace {

// Designing takes milliseconds (100000-sample least squares); cache by spec body.
struct SpecCache {
  std::mutex mutex;
  std::map<std::string, Transform1DPtr, std::less<>> map;
};

SpecCache& spec_cache() {
  static SpecCache cache;
  return cache;
}

}  // namespace

std::size_t pups_transform_cache_size() {
  SpecCache& c = spec_cache();
  const std::lock_guard lock(c.mutex);
  return c.map.size();
}

Transform1DPtr make_pups_transform_from_spec(std::string_view body) {
  const pups::DesignSpec parsed = pups::parse_design_spec(body);
  SpecCache& c = spec_cache();
  std::mutex& mutex = c.mutex;
  auto& cache = c.map;
  {
    const std::lock_guard lock(mutex);
    if (auto it = cache.find(body); it != cache.end()) return it->second;
  }
  // A preset's bank is stored (the same bits as its design), sparing every encoder and decoder
  // of a stream naming it the least-squares design.
  std::optional<pups::FilterBank> stored;
  if (!parsed.preset.empty()) stored = pups::stored_preset_bank(parsed.preset);
  const pups::FilterBank bank = stored ? *stored : pups::design(parsed);
  const std::string canonical = pups::canonical_spec_body(bank, parsed.boundary);
  Transform1DPtr t = make_pups_transform(bank, "pups:" + canonical, parsed.boundary);
  const std::lock_guard lock(mutex);
  if (cache.size() + 2 > pups::kMaxCachedSpecs) cache.clear();
  cache.emplace(std::string(body), t);
  cache.emplace(canonical, t);
  return t;
}

double analysis_condition_number(const Transform1D& t, std::size_t n, bool two_norm) {
  if (n == 0 || n > 8192) throw std::invalid_argument("condition number needs 1 <= n <= 8192");
  const auto m = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd T(m, m), Tinv(m, m);
  std::vector<double> col(n);
  for (Eigen::Index j = 0; j < m; ++j) {
    for (const bool forward : {true, false}) {
      std::fill(col.begin(), col.end(), 0.0);
      col[static_cast<std::size_t>(j)] = 1.0;
      if (forward)
        t.analyze(std::span<double>(col));
      else
        t.synthesize(std::span<double>(col));
      (forward ? T : Tinv).col(j) = Eigen::Map<const Eigen::VectorXd>(col.data(), m);
    }
  }
  if (two_norm) {
    const Eigen::VectorXd sv = Eigen::BDCSVD<Eigen::MatrixXd>(T).singularValues();
    return sv(0) / sv(m - 1);
  }
  return T.cwiseAbs().colwise().sum().maxCoeff() * Tinv.cwiseAbs().colwise().sum().maxCoeff();
}

std::vector<std::string> pups_transform_specs() {
  std::vector<std::string> out;
  for (const auto& p : pups::presets()) out.push_back("pups:" + p.name);
  return out;
}

}  // namespace pupwave
