#include "transforms/cdf.h"
#include "transforms/lifting.h"
#include "transforms/lifting_columns.h"
#include "transforms/scratch.h"

#include <type_traits>

namespace pupwave {
namespace {

// Real-valued 5/3: odd -= (even[i] + even[i+1]) / 2, then even += (odd[i-1] + odd[i]) / 4.
constexpr double kHalf[] = {-0.5, -0.5};
constexpr double kQuarter[] = {0.25, 0.25};
constexpr lifting::Taps kPredict{kHalf, 0}, kUpdate{kQuarter, -1};

// Reversible 5/3 of JPEG 2000 (T.800 Eq. F-9/F-10): the same steps with floor rounding.
constexpr int32_t kOnes[] = {1, 1};
constexpr lifting::IntegerTaps kPredictInt{kOnes, 0, 0, 1}, kUpdateInt{kOnes, -1, 2, 2};

template <class T>
void analyze53(std::span<T> line) {
  const std::size_t n = line.size();
  if (n < 2) return;
  lifting::split(line, thread_scratch<T>(n));  // n: the vectorized split
  const auto e = line.first((n + 1) / 2);
  const auto o = line.subspan((n + 1) / 2);
  const auto w = lifting::whole_sample_symmetric_wires(n);
  if constexpr (std::is_same_v<T, int32_t>) {
    lifting::lift_integer(e, w.even, o, kPredictInt, lifting::Direction::subtract);
    lifting::lift_integer(o, w.odd, e, kUpdateInt, lifting::Direction::add);
  } else {
    lifting::predict<T>(e, w.even, o, kPredict);
    lifting::update<T>(o, w.odd, e, kUpdate);
  }
}

template <class T>
void synthesize53(std::span<T> line) {
  const std::size_t n = line.size();
  if (n < 2) return;
  const auto e = line.first((n + 1) / 2);
  const auto o = line.subspan((n + 1) / 2);
  const auto w = lifting::whole_sample_symmetric_wires(n);
  if constexpr (std::is_same_v<T, int32_t>) {
    lifting::lift_integer(o, w.odd, e, kUpdateInt, lifting::Direction::subtract);
    lifting::lift_integer(e, w.even, o, kPredictInt, lifting::Direction::add);
  } else {
    lifting::undo_update<T>(o, w.odd, e, kUpdate);
    lifting::undo_predict<T>(e, w.even, o, kPredict);
  }
  lifting::merge(line, thread_scratch<T>(n));  // n: the vectorized merge
}

// analyze53 / synthesize53 on every column of a block of rows (lifting_columns.h).
template <class T>
void analyze53_columns(std::span<T> block, std::size_t width) {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n < 2) return;
  col::split(block.data(), n, width, thread_scratch<T>(n / 2 * width).data());
  T* e = block.data();
  T* o = e + (n + 1) / 2 * width;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  const auto w = lifting::whole_sample_symmetric_wires(n);
  if constexpr (std::is_same_v<T, int32_t>) {
    col::lift_integer(e, ne, w.even, o, no, kPredictInt, lifting::Direction::subtract, width);
    col::lift_integer(o, no, w.odd, e, ne, kUpdateInt, lifting::Direction::add, width);
  } else {
    col::apply<T>(e, ne, w.even, o, no, kPredict, T(1), width);
    col::apply<T>(o, no, w.odd, e, ne, kUpdate, T(1), width);
  }
}

template <class T>
void synthesize53_columns(std::span<T> block, std::size_t width) {
  namespace col = lifting::columns;
  const std::size_t n = width ? block.size() / width : 0;
  if (n < 2) return;
  T* e = block.data();
  T* o = e + (n + 1) / 2 * width;
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  const auto w = lifting::whole_sample_symmetric_wires(n);
  if constexpr (std::is_same_v<T, int32_t>) {
    col::lift_integer(o, no, w.odd, e, ne, kUpdateInt, lifting::Direction::subtract, width);
    col::lift_integer(e, ne, w.even, o, no, kPredictInt, lifting::Direction::add, width);
  } else {
    col::apply<T>(o, no, w.odd, e, ne, kUpdate, T(-1), width);
    col::apply<T>(e, ne, w.even, o, no, kPredict, T(-1), width);
  }
  col::merge(block.data(), n, width, thread_scratch<T>(n / 2 * width).data());
}

class Cdf53 final : public Transform1D {
 public:
  std::string spec() const override { return "cdf53"; }
  bool is_reversible() const override { return true; }
  void analyze(std::span<double> line) const override { analyze53(line); }
  void synthesize(std::span<double> line) const override { synthesize53(line); }
  void analyze(std::span<float> line) const override { analyze53(line); }
  void synthesize(std::span<float> line) const override { synthesize53(line); }
  void analyze(std::span<int32_t> line) const override { analyze53(line); }
  void synthesize(std::span<int32_t> line) const override { synthesize53(line); }
  void analyze_columns(std::span<float> b, std::size_t width) const override { analyze53_columns(b, width); }
  void synthesize_columns(std::span<float> b, std::size_t width) const override {
    synthesize53_columns(b, width);
  }
  void analyze_columns(std::span<double> b, std::size_t width) const override { analyze53_columns(b, width); }
  void synthesize_columns(std::span<double> b, std::size_t width) const override {
    synthesize53_columns(b, width);
  }
  void analyze_columns(std::span<int32_t> b, std::size_t width) const override {
    analyze53_columns(b, width);
  }
  void synthesize_columns(std::span<int32_t> b, std::size_t width) const override {
    synthesize53_columns(b, width);
  }
};

}  // namespace

Transform1DPtr make_cdf53() { return std::make_shared<const Cdf53>(); }

}  // namespace pupwave
