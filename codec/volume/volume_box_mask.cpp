#include "codec/volume/volume_box_mask.h"

#include <algorithm>

#include "codec/error.h"

namespace pupwave {
namespace {

constexpr std::size_t kBatchBytes = std::size_t(1) << 20;  // states decompressed at a time

// Whether n states are all 0 (inactive background); the common case of a sparse box, kept to a
// vectorisable OR so that empty regions are skimmed at memory speed.
bool all_background(const std::uint8_t* s, std::size_t n) {
  std::uint8_t any = 0;
  for (std::size_t i = 0; i < n; ++i) any |= s[i];
  return any == 0;
}

}  // namespace

BoxBricks::BoxBricks(const Extent& d, int l) : dims(d), log2(l) {
  const std::size_t edge = std::size_t(1) << l;
  for (std::size_t a = 0; a < 3; ++a) n[a] = (dims[a] + edge - 1) / edge;
}

BrickBox BoxBricks::box(std::size_t index) const {
  const std::size_t edge = std::size_t(1) << log2;
  const Extent at{index % n[0], index / n[0] % n[1], index / n[0] / n[1]};
  BrickBox b;
  for (std::size_t a = 0; a < 3; ++a) {
    b.offset[a] = at[a] * edge;
    b.size[a] = std::min(edge, dims[a] - b.offset[a]);
  }
  return b;
}

MaskRows::MaskRows(std::span<const std::uint8_t> frame, const Extent& dims)
    : frame_(frame), dims_(dims), ctx_(ZSTD_createDCtx()) {
  if (ctx_ == nullptr) throw std::bad_alloc();
  rows_per_batch_ = std::max<std::size_t>(1, kBatchBytes / dims[0]);
  buffer_.resize(rows_per_batch_ * dims[0]);
  in_ = ZSTD_inBuffer{frame.data(), frame.size(), 0};
}

MaskRows::~MaskRows() { ZSTD_freeDCtx(ctx_); }

std::size_t MaskRows::next(std::size_t& first_row, const std::uint8_t*& states) {
  const std::size_t rows = std::min(rows_per_batch_, dims_[1] * dims_[2] - row_);
  first_row = row_;
  states = buffer_.data();
  if (rows == 0) return 0;
  ZSTD_outBuffer out{buffer_.data(), rows * dims_[0], 0};
  while (out.pos < out.size) {
    const std::size_t before = out.pos, consumed = in_.pos;
    last_status_ = ZSTD_decompressStream(ctx_, &out, &in_);
    require_stream(!ZSTD_isError(last_status_), "volume stream: corrupt mask");
    // No progress with the frame unfinished: the input ran out (a truncated frame).
    require_stream(out.pos > before || in_.pos > consumed || last_status_ == 0 || out.pos == out.size,
                   "volume stream: corrupt mask");
    require_stream(out.pos == out.size || last_status_ != 0, "volume stream: mask size");
  }
  row_ += rows;
  return rows;
}

void MaskRows::expect_end() {
  // Flush: a complete frame reports 0 once its last block and checksum are read.
  std::uint8_t spare = 0;
  while (last_status_ != 0) {
    ZSTD_outBuffer out{&spare, 1, 0};
    const std::size_t consumed = in_.pos;
    last_status_ = ZSTD_decompressStream(ctx_, &out, &in_);
    require_stream(!ZSTD_isError(last_status_) && out.pos == 0, "volume stream: mask size");
    require_stream(last_status_ == 0 || in_.pos > consumed, "volume stream: corrupt mask");
  }
  require_stream(in_.pos == in_.size, "volume stream: corrupt mask");
}

BoxMask scan_box_mask(std::span<const std::uint8_t> frame, std::vector<double> other_values,
                      const Extent& dims, int brick_log2, const DecodeLimits& limits, std::size_t already) {
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  require_stream(content == dims[0] * dims[1] * dims[2], "volume stream: mask size");
  const BoxBricks geometry(dims, brick_log2);
  BoxMask m;
  m.frame = frame;
  m.bricks.assign(geometry.count(), 0);
  std::size_t others = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(frame, dims);
  while (const std::size_t n = rows.next(first, states)) {
    if (all_background(states, n * dims[0])) continue;
    for (std::size_t r = 0; r < n; ++r) {
      const std::uint8_t* row = states + r * dims[0];
      if (all_background(row, dims[0])) continue;
      const std::size_t y = (first + r) % dims[1], z = (first + r) / dims[1];
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const std::uint8_t s = row[x];
        if (s == 0) continue;
        require_stream(s <= 3, "volume stream: bad voxel state");
        std::uint8_t& bits = m.bricks[geometry.at(x, y, z)];
        if (bits == 0) {  // a brick the decode will hold: counted against the limit now
          const BrickBox box = geometry.box(geometry.at(x, y, z));
          m.content_voxels += box.count();
          check_decode_limit(already + m.content_voxels, limits, "volume stream: voxels to decode");
          m.last_row = std::max(m.last_row,
                                (box.offset[1] + box.size[1]) + dims[1] * (box.offset[2] + box.size[2] - 1));
        }
        bits |= std::uint8_t(1u << s);
        m.active += s == 1 ? 1 : 0;
        others += s == 3 ? 1 : 0;
      }
    }
  }
  rows.expect_end();
  require_stream(others <= other_values.size(), "volume stream: missing inactive values");
  require_stream(others == other_values.size(), "volume stream: extra inactive values");
  m.other_values = std::move(other_values);
  return m;
}

}  // namespace pupwave
