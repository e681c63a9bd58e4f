#include "transforms/pups/filter_bank.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace pupwave::pups {

namespace {

constexpr std::uint8_t kMagic[4] = {'P', 'W', 'F', 'B'};
constexpr std::uint8_t kVersion = 1;
// Limits that keep a hostile header from asking for unbounded memory.
constexpr std::uint32_t kMaxTaps = 4096;
constexpr std::uint32_t kMaxName = 256;

struct KindName {
  WeightKind kind;
  const char* name;
};
constexpr KindName kKindNames[] = {{WeightKind::bspline, "bspline"},
                                   {WeightKind::polynomial, "polynomial"},
                                   {WeightKind::cinpact, "cinpact"},
                                   {WeightKind::cinpact_interp, "cinpact-interp"},
                                   {WeightKind::given, "given"}};

// Little-endian writer.
class Writer {
 public:
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out_.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 8; ++k) out_.push_back(static_cast<std::uint8_t>(bits >> (8 * k)));
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
  }
  void doubles(const std::vector<double>& v) {
    u32(static_cast<std::uint32_t>(v.size()));
    for (double x : v) f64(x);
  }
  std::vector<std::uint8_t> take() { return std::move(out_); }

 private:
  std::vector<std::uint8_t> out_;
};

// Little-endian reader that checks every read against the remaining input.
class Reader {
 public:
  explicit Reader(const std::vector<std::uint8_t>& in) : in_(in) {}
  void need(std::size_t n, const char* what) const {
    if (in_.size() - pos_ < n)
      throw std::invalid_argument(std::string("filter bank bytes truncated reading ") + what);
  }
  std::uint8_t u8(const char* what) {
    need(1, what);
    return in_[pos_++];
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t{in_[pos_++]} << (8 * k);
    return v;
  }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  double f64(const char* what) {
    need(8, what);
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits |= std::uint64_t{in_[pos_++]} << (8 * k);
    return std::bit_cast<double>(bits);
  }
  std::string str(const char* what) {
    const std::uint32_t n = u32(what);
    if (n > kMaxName) throw std::invalid_argument(std::string("filter bank ") + what + " too long");
    need(n, what);
    std::string s(in_.begin() + static_cast<std::ptrdiff_t>(pos_),
                  in_.begin() + static_cast<std::ptrdiff_t>(pos_ + n));
    pos_ += n;
    return s;
  }
  std::vector<double> doubles(const char* what) {
    const std::uint32_t n = u32(what);
    if (n > kMaxTaps) throw std::invalid_argument(std::string("filter bank ") + what + " too long");
    need(std::size_t{n} * 8, what);
    std::vector<double> v(n);
    for (auto& x : v) x = f64(what);
    return v;
  }
  bool done() const { return pos_ == in_.size(); }

 private:
  const std::vector<std::uint8_t>& in_;
  std::size_t pos_ = 0;
};

void write_filter(Writer& w, const Filter& f) {
  w.i32(f.offset);
  w.doubles(f.taps);
}

Filter read_filter(Reader& r, const char* what) {
  Filter f;
  f.offset = r.i32(what);
  f.taps = r.doubles(what);
  if (f.taps.empty()) throw std::invalid_argument(std::string("filter bank: empty ") + what);
  for (double t : f.taps)
    if (!std::isfinite(t)) throw std::invalid_argument(std::string("filter bank: non-finite ") + what);
  return f;
}

}  // namespace

std::string to_string(WeightKind kind) {
  for (const auto& kn : kKindNames)
    if (kn.kind == kind) return kn.name;
  throw std::invalid_argument("unknown weight kind");
}

WeightKind weight_kind_from_string(const std::string& name) {
  for (const auto& kn : kKindNames)
    if (name == kn.name) return kn.kind;
  throw std::invalid_argument("unknown weight function '" + name +
                              "' (expected bspline, polynomial, cinpact, cinpact-interp or given)");
}

std::vector<std::uint8_t> to_bytes(const FilterBank& bank) {
  Writer w;
  for (auto m : kMagic) w.u8(m);
  w.u8(kVersion);
  w.str(bank.name);
  const DesignParams& d = bank.design;
  w.u8(static_cast<std::uint8_t>(d.weight));
  w.i32(d.degree);
  w.doubles(d.coeffs);
  w.f64(d.domain_lo);
  w.f64(d.domain_hi);
  w.f64(d.c);
  w.f64(d.sigma);
  w.i32(d.samples);
  w.i32(d.extension);
  for (const Filter* f : {&bank.P, &bank.Q, &bank.A, &bank.B}) write_filter(w, *f);
  w.f64(bank.refinement_error);
  w.f64(bank.orthogonality_error);
  w.i32(bank.shift);
  return w.take();
}

FilterBank filter_bank_from_bytes(const std::vector<std::uint8_t>& bytes) {
  Reader r(bytes);
  for (auto m : kMagic)
    if (r.u8("magic") != m) throw std::invalid_argument("filter bank bytes: bad magic");
  if (r.u8("version") != kVersion) throw std::invalid_argument("filter bank bytes: unsupported version");
  FilterBank b;
  b.name = r.str("name");
  const std::uint8_t kind = r.u8("weight kind");
  if (kind > static_cast<std::uint8_t>(WeightKind::given))
    throw std::invalid_argument("filter bank bytes: unknown weight kind");
  b.design.weight = static_cast<WeightKind>(kind);
  b.design.degree = r.i32("degree");
  b.design.coeffs = r.doubles("coefficients");
  b.design.domain_lo = r.f64("domain");
  b.design.domain_hi = r.f64("domain");
  b.design.c = r.f64("c");
  b.design.sigma = r.f64("sigma");
  b.design.samples = r.i32("samples");
  b.design.extension = r.i32("extension");
  b.P = read_filter(r, "P");
  b.Q = read_filter(r, "Q");
  b.A = read_filter(r, "A");
  b.B = read_filter(r, "B");
  b.refinement_error = r.f64("refinement error");
  b.orthogonality_error = r.f64("orthogonality error");
  b.shift = r.i32("shift");
  if (!r.done()) throw std::invalid_argument("filter bank bytes: trailing data");
  return b;
}

}  // namespace pupwave::pups
