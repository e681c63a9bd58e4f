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
  if (n < 2) return;                           // JPEG 2000: a single (even) sample passes unchanged
  lifting::split(line, thread_scratch<T>(n));  // n: the vectorized split
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
  lifting::merge(line, thread_scratch<T>(n));  // n: the vectorized merge
}

// analyze97 / synthesize97 on every column of a block of rows (lifting_columns.h), with the
// four lifting steps and the scaling pipelined down the block: step s on row k runs as soon
// as the rows it reads are final for step s - 1, so each row is lifted while it is still in
// L1 (one pass over the block instead of six). Every sample gets the same operations as from
// the step-by-step form, so the results are the same to the bit. Rows read beyond a wire's end
// are reflected onto rows at most as far along, which are already done.
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
  const T one(1);
  for (std::size_t k = 0; k <= ne + 1; ++k) {
    const auto i = std::ptrdiff_t(k);
    if (k < no) col::apply_row<T>(e, ne, w.even, o, no, i, kPredict1, one, width);  // reads e[k], e[k+1]
    if (k < ne) col::apply_row<T>(o, no, w.odd, e, ne, i, kUpdate1, one, width);    // o[k-1], o[k]
    if (k >= 1 && k - 1 < no) col::apply_row<T>(e, ne, w.even, o, no, i - 1, kPredict2, one, width);
    if (k >= 1 && k - 1 < ne) {
      col::apply_row<T>(o, no, w.odd, e, ne, i - 1, kUpdate2, one, width);  // e[k-1] is final
      col::undo_scale(e + (k - 1) * width, width, C::K);
    }
    if (k >= 2 && k - 2 < no) col::scale(o + (k - 2) * width, width, C::K);  // read for the last time above
  }
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
  const T minus(-1);
  for (std::size_t k = 0; k <= ne + 1; ++k) {
    const auto i = std::ptrdiff_t(k);
    if (k < no) col::undo_scale(o + k * width, width, C::K);
    if (k < ne) {
      col::scale(e + k * width, width, C::K);
      col::apply_row<T>(o, no, w.odd, e, ne, i, kUpdate2, minus, width);  // reads o[k-1], o[k]
    }
    if (k >= 1 && k - 1 < no) col::apply_row<T>(e, ne, w.even, o, no, i - 1, kPredict2, minus, width);
    if (k >= 1 && k - 1 < ne) col::apply_row<T>(o, no, w.odd, e, ne, i - 1, kUpdate1, minus, width);
    if (k >= 2 && k - 2 < no) col::apply_row<T>(e, ne, w.even, o, no, i - 2, kPredict1, minus, width);
  }
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
