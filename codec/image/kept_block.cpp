#include "codec/image/kept_block.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace pupwave {
namespace {

void put_u32(std::uint8_t* at, std::size_t v) {
  const auto u = std::uint32_t(v);
  std::memcpy(at, &u, 4);
}

std::size_t get_u32(const std::uint8_t* at) {
  std::uint32_t u = 0;
  std::memcpy(&u, at, 4);
  return u;
}

}  // namespace

KeptBlock::KeptBlock(EncodedBlock&& b, int limit, bool distortions)
    : planes(b.planes), initial_distortion(b.initial_distortion), distortions_(distortions) {
  const std::size_t n = std::min(b.passes.size(), std::size_t(std::max(limit, 0)));
  std::size_t committed = 0, tails = 0;
  for (std::size_t k = 0; k < n; ++k) {
    committed = std::max(committed, b.passes[k].prefix);
    tails += b.passes[k].tail.size();
  }
  passes_ = std::uint32_t(n);
  committed_ = std::uint32_t(committed);
  tails_ = std::uint32_t(tails);
  if (n == 0) return;  // nothing to hold (no allocation either)
  data_ = std::make_unique<std::uint8_t[]>(tails_at() + tails);
  std::uint8_t* tail = data_.get() + tails_at();
  for (std::size_t k = 0; k < n; ++k) {
    const TruncationPoint& p = b.passes[k];
    put_u32(data_.get() + 4 * k, p.prefix);
    tail = std::copy(p.tail.begin(), p.tail.end(), tail);
    put_u32(data_.get() + 4 * (n + k), std::size_t(tail - (data_.get() + tails_at())));
    if (distortions_) std::memcpy(data_.get() + 8 * n + 8 * k, &b.distortion_drop[k], 8);
  }
  std::copy_n(b.committed.data(), committed, data_.get() + committed_at());
}

std::size_t KeptBlock::prefix(std::size_t k) const { return get_u32(data_.get() + 4 * k); }
std::size_t KeptBlock::tail_end(std::size_t k) const { return get_u32(data_.get() + 4 * (passes_ + k)); }

std::size_t KeptBlock::size(int n) const {
  if (n <= 0) return 0;
  const auto k = std::size_t(n - 1);
  return prefix(k) + tail_end(k) - (k > 0 ? tail_end(k - 1) : 0);
}

void KeptBlock::append_codeword(int n, std::vector<std::uint8_t>& out) const {
  if (n <= 0) return;
  const auto k = std::size_t(n - 1);
  const std::uint8_t* committed = data_.get() + committed_at();
  const std::uint8_t* tails = data_.get() + tails_at();
  out.insert(out.end(), committed, committed + prefix(k));
  out.insert(out.end(), tails + (k > 0 ? tail_end(k - 1) : 0), tails + tail_end(k));
}

double KeptBlock::distortion_drop(int k) const {
  if (!distortions_) throw std::logic_error("KeptBlock: distortion drops were not kept");
  double d = 0.0;
  std::memcpy(&d, data_.get() + 8 * std::size_t(passes_) + 8 * std::size_t(k), 8);
  return d;
}

void KeptBlock::truncate(int n) {
  if (n >= pass_count()) return;
  const auto m = std::size_t(std::max(n, 0));
  KeptBlock cut;
  cut.planes = planes;
  cut.initial_distortion = initial_distortion;
  cut.distortions_ = distortions_;
  cut.passes_ = std::uint32_t(m);
  std::size_t committed = 0;
  for (std::size_t k = 0; k < m; ++k) committed = std::max(committed, prefix(k));
  cut.committed_ = std::uint32_t(committed);
  cut.tails_ = std::uint32_t(m > 0 ? tail_end(m - 1) : 0);
  if (m == 0) {
    *this = std::move(cut);
    return;
  }
  cut.data_ = std::make_unique<std::uint8_t[]>(cut.tails_at() + cut.tails_);
  std::uint8_t* to = cut.data_.get();
  const std::uint8_t* from = data_.get();
  std::copy_n(from, 4 * m, to);                                          // prefixes
  std::copy_n(from + 4 * passes_, 4 * m, to + 4 * m);                    // tail ends
  if (distortions_) std::copy_n(from + 8 * passes_, 8 * m, to + 8 * m);  // distortion drops
  std::copy_n(from + committed_at(), committed, to + cut.committed_at());
  std::copy_n(from + tails_at(), cut.tails_, to + cut.tails_at());
  *this = std::move(cut);
}

std::size_t KeptBlock::bytes_held() const { return data_ ? tails_at() + tails_ : 0; }

}  // namespace pupwave
