#include "transforms/cdf.h"
#include "transforms/lifting.h"
#include "transforms/lifting_columns.h"
#include "transforms/scratch.h"

namespace pupwave {
namespace {

using C = Cdf97Constants;
constexpr double kAlpha[] = {C::alpha, C::alpha};
constexpr double kBeta[] = {C::beta, C::beta};
constexpr double kGamma[] = {C::gamma, C::gamma};
constexpr double kDelta[] = {C::delta, C::delta};
// Predicts read even[i], even[i+1]; updates read odd[i-1], odd[i] (symmetric 2-tap steps).
constexpr lifting::Taps kPredict1{kAlpha, 0}, kUpdate1{kBeta, -1};
constexpr lifting::Taps kPredict2{kGamma, 0}, kUpdate2{kDelta, -1};

template <class T>
void analyze97(std::span<T> line) {
  const std::size_t n = line.size();
  if (n < 2) return;  // JPEG 2000: a single (even) sample passes unchanged
  lifting::split(line, thread_scratch<T>(n / 2));
  const auto e = line.first((n + 1) / 2);
  const auto o = line.subspan((n + 1) / 2);
  const auto w = lifting::whole_sample_symmetric_wires(n);
  lifting::predict<T>(e, w.even, o, kPredict1);
  lifting::update<T>(o, w.odd, e, kUpdate1);
  lifting::predict<T>(e, w.even, o, kPredict2);
  lifting::update<T>(o, w.odd, e, kUpdate2);
  lifting::undo_scale(e, C::K);
  lifting::scale(o, C::K);
}

template <class T>
void synthesize97(std::span<T> line) {
  const std::size_t n = line.size();
  if (n < 2) return;
  const auto e = line.first((n + 1) / 2);
  const auto o = line.subspan((n + 1) / 2);
  const auto w = lifting::whole_sample_symmetric_wires(n);
  lifting::undo_scale(o, C::K);
  lifting::scale(e, C::K);
  lifting::undo_update<T>(o, w.odd, e, kUpdate2);
  lifting::undo_predict<T>(e, w.even, o, kPredict2);
  lifting::undo_update<T>(o, w.odd, e, kUpdate1);
  lifting::undo_predict<T>(e, w.even, o, kPredict1);
  lifting::merge(line, thread_scratch<T>(n / 2));
}

// analyze97 / synthesize97 on every column of a block of rows (lifting_columns.h).
template <class T>
void analyze97_columns(std::span<T> block, std::size_t width) {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n < 2) return;
  col::split(block.data(), n, width, thread_scratch<T>(n / 2 * width).data());
  T* e = block.data();
  T* o = e + (n + 1) / 2 * width;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  const auto w = lifting::whole_sample_symmetric_wires(n);
  col::apply<T>(e, ne, w.even, o, no, kPredict1, T(1), width);
  col::apply<T>(o, no, w.odd, e, ne, kUpdate1, T(1), width);
  col::apply<T>(e, ne, w.even, o, no, kPredict2, T(1), width);
  col::apply<T>(o, no, w.odd, e, ne, kUpdate2, T(1), width);
  col::undo_scale(e, ne * width, C::K);
  col::scale(o, no * width, C::K);
}

template <class T>
void synthesize97_columns(std::span<T> block, std::size_t width) {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n < 2) return;
  T* e = block.data();
  T* o = e + (n + 1) / 2 * width;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  const auto w = lifting::whole_sample_symmetric_wires(n);
  col::undo_scale(o, no * width, C::K);
  col::scale(e, ne * width, C::K);
  col::apply<T>(o, no, w.odd, e, ne, kUpdate2, T(-1), width);
  col::apply<T>(e, ne, w.even, o, no, kPredict2, T(-1), width);
  col::apply<T>(o, no, w.odd, e, ne, kUpdate1, T(-1), width);
  col::apply<T>(e, ne, w.even, o, no, kPredict1, T(-1), width);
  col::merge(block.data(), n, width, thread_scratch<T>(n / 2 * width).data());
}

class Cdf97 final : public Transform1D {
 public:
  std::string spec() const override { return "cdf97"; }
  void analyze(std::span<double> line) const override { analyze97(line); }
  void synthesize(std::span<double> line) const override { synthesize97(line); }
  void analyze(std::span<float> line) const override { analyze97(line); }
  void synthesize(std::span<float> line) const override { synthesize97(line); }
  void analyze_columns(std::span<float> b, std::size_t width) const override { analyze97_columns(b, width); }
  void synthesize_columns(std::span<float> b, std::size_t width) const override {
    synthesize97_columns(b, width);
  }
  void analyze_columns(std::span<double> b, std::size_t width) const override { analyze97_columns(b, width); }
  void synthesize_columns(std::span<double> b, std::size_t width) const override {
    synthesize97_columns(b, width);
  }
  using Transform1D::analyze;
  using Transform1D::analyze_columns;
  using Transform1D::synthesize;
  using Transform1D::synthesize_columns;
};

}  // namespace

Transform1DPtr make_cdf97() { return std::make_shared<const Cdf97>(); }

}  // namespace pupwave
