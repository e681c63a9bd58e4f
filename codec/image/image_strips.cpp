#include "codec/image/image_strips.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "codec/error.h"
#include "codec/image/image_components.h"
#include "transforms/reach.h"
#include "transforms/scratch.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

// Rows a level adds to its cache at a time: the column synthesis of a window costs its
// 2 * reach overlap rows once per chunk, so chunks well above the reach keep that small.
constexpr std::size_t kLevelChunk = 64;
// Columns per column-synthesis task (a window of them stays in cache while lifted).
constexpr std::size_t kColumnChunk = 128;

// Rows [first, end) of `width` samples, dropped at the front and added at the back. Dropped
// rows are let go lazily, once they are at least as many as the rows kept, so each kept row is
// moved to the front about once instead of on every drop (moving them on every drop costs 7% of
// a decode); the buffer holds at most about twice the rows kept.
template <class T>
class RowWindow {
 public:
  explicit RowWindow(std::size_t width) : width_(width) {}

  std::size_t width() const { return width_; }
  std::size_t end() const { return end_; }
  // Forgets every row: the window is empty and starts at `row`.
  void restart(std::size_t row) {
    data_.clear();
    base_ = first_ = end_ = row;
  }
  // Rows before a (a <= end()) are not needed again.
  void drop_before(std::size_t a) {
    if (a <= first_) return;
    first_ = a;
    if (first_ - base_ < end_ - first_) return;
    data_.erase(data_.begin(), data_.begin() + std::ptrdiff_t((first_ - base_) * width_));
    base_ = first_;
  }
  // Adds rows [end(), e) (contents unset, to be written by the caller). When the buffer must
  // grow, dropped rows are let go first (growing copies every row anyway) and it grows to the
  // rows asked for, not to double: a window's size settles after a few chunks, and doubling
  // would leave half of every window's buffer unused.
  void extend_to(std::size_t e) {
    if ((e - base_) * width_ > data_.capacity()) {
      data_.erase(data_.begin(), data_.begin() + std::ptrdiff_t((first_ - base_) * width_));
      base_ = first_;
      data_.reserve((e - base_) * width_);
    }
    data_.resize((e - base_) * width_);
    end_ = e;
  }
  T* row(std::size_t r) { return data_.data() + (r - base_) * width_; }
  const T* row(std::size_t r) const { return data_.data() + (r - base_) * width_; }

 private:
  std::size_t width_;
  RowBuffer<T> data_;  // rows [base_, end_); those before first_ are dropped
  std::size_t base_ = 0, first_ = 0, end_ = 0;
};

// Columns [first, end) of a level or band: the part of it a pipeline computes (all of it, or
// the columns one tile of a column-tiled pass needs).
struct Columns {
  std::size_t first = 0, end = 0;
};

// One subband of one component, decoded one block row at a time as rows are asked for. Rows
// above the lowest one still needed are dropped (the few kept move to the front), so a band
// holds little more than one block row even where a window straddles two. Only the blocks
// that meet the columns asked for are decoded and kept.
template <class T>
class BandRows {
 public:
  BandRows(const ParsedStream& s, const std::vector<std::size_t>& blocks, const Subband& band, Columns wanted,
           const Executor& ex)
      : s_(s), ex_(ex), band_x_(band.offset[0]), y0_(band.offset[1]) {
    std::size_t first = band.size[0], end = 0;
    for (std::size_t i : blocks) {  // partition order: block rows top to bottom, x fastest
      const CodeBlock& b = s.blocks[i];
      const std::size_t bx = b.offset[0] - band_x_;
      if (bx >= wanted.end || bx + b.size[0] <= wanted.first) continue;
      first = std::min(first, bx);
      end = std::max(end, bx + b.size[0]);
      if (block_rows_.empty() || block_rows_.back().y0 != b.offset[1] - y0_)
        block_rows_.push_back({b.offset[1] - y0_, b.offset[1] - y0_ + b.size[1], {}});
      block_rows_.back().blocks.push_back(i);
    }
    first_ = end > first ? first : 0;
    rows_ = RowWindow<T>(end > first ? end - first : 0);
  }

  // Makes band rows [a, b) readable; a never decreases from one call to the next.
  void ensure(std::size_t a, std::size_t b) {
    if (b <= a) return;
    if (a >= rows_.end()) {  // nothing cached is needed again: restart at a's block row
      while (block_rows_[next_].y1 <= a) ++next_;
      rows_.restart(block_rows_[next_].y0);
    }
    rows_.drop_before(a);
    while (rows_.end() < b) decode_next_row();
  }

  // Band row r from column x on (x among the columns asked for).
  const T* at(std::size_t r, std::size_t x) const { return rows_.row(r) + (x - first_); }

 private:
  struct BlockRow {
    std::size_t y0, y1;  // band rows
    std::vector<std::size_t> blocks;
  };

  void decode_next_row() {
    const BlockRow& br = block_rows_[next_++];
    rows_.extend_to(br.y1);
    T* rows = rows_.row(br.y0);
    ex_.run(br.blocks.size(), [&](std::size_t j) {
      const CodeBlock& b = s_.blocks[br.blocks[j]];
      decode_block_at(s_, br.blocks[j], rows + (b.offset[0] - band_x_ - first_), rows_.width());
    });
  }

  const ParsedStream& s_;
  const Executor& ex_;
  std::size_t band_x_, y0_;
  std::size_t first_ = 0;  // first band column kept (that of the first block decoded)
  std::vector<BlockRow> block_rows_;
  std::size_t next_ = 0;  // first block row not decoded yet
  RowWindow<T> rows_{0};  // band rows (every row decoded before it is read)
};

// The columns of a level that synthesizing its columns `out` reads (the windowed lifting's
// reach on each side, starting at an even column, ending at an even one or the level's end),
// and the columns of its coarse (even) and detail (odd) halves those are made from.
struct ColumnWindow {
  Columns level, coarse, detail;
};

ColumnWindow column_window(Columns out, std::size_t width, std::size_t reach) {
  std::size_t w0 = out.first > reach ? out.first - reach : 0;
  w0 &= ~std::size_t(1);
  std::size_t w1 = std::min(width, out.end + reach);
  if (w1 % 2 != 0 && w1 < width) ++w1;
  return {{w0, w1}, {w0 / 2, (w1 + 1) / 2}, {w0 / 2, w1 / 2}};
}

// The level-l coarse band of one component (the image at 1/2^l size), produced top to bottom
// in chunks of rows from the level-(l+1) rows and the level-(l+1) detail bands: column
// synthesis over a window reaching `reach` rows beyond the chunk, then row synthesis over
// the columns' window (all of them, or those one tile needs plus the reach on each side).
template <class T>
class LevelRows {
 public:
  using Bands = std::vector<std::unique_ptr<BandRows<T>>>;  // indexed by orientation 0..3

  LevelRows(const Transform1D& t, std::size_t reach, const Extent& size, const ColumnWindow& window,
            std::unique_ptr<LevelRows> child, Bands bands, const Executor& ex)
      : t_(t),
        reach_(reach),
        width_(size[0]),
        height_(size[1]),
        window_(window),
        child_(std::move(child)),
        bands_(std::move(bands)),
        ex_(ex),
        rows_(window.level.end - window.level.first) {}

  std::size_t height() const { return height_; }

  // Makes rows [a, b) readable and frees those above a; a never decreases between calls.
  void ensure(std::size_t a, std::size_t b) {
    if (!child_) return bands_[0]->ensure(a, b);  // the coarsest level is the coarse band
    if (a > rows_.end()) rows_.restart(a);        // nothing cached is needed again
    rows_.drop_before(a);
    while (rows_.end() < b) {
      const std::size_t p0 = rows_.end(), end = std::min(height_, std::max(b, p0 + kLevelChunk));
      rows_.extend_to(end);
      produce(p0, end, rows_.row(p0));
    }
  }

  // Row r from column x on (x among the columns this level was built for).
  const T* at(std::size_t r, std::size_t x) const {
    return child_ ? rows_.row(r) + (x - window_.level.first) : bands_[0]->at(r, x);
  }

  // Rows [p0, p1) of the columns this level was built for into `out` (rows of that many
  // columns) without keeping them, for a level whose rows are each read once (the PSNR check's
  // full resolution); p0 never decreases between calls.
  void produce_into(std::size_t p0, std::size_t p1, Columns columns, T* out) {
    const std::size_t n = columns.end - columns.first, stored = window_.level.end - window_.level.first;
    if (child_ && n == stored) return produce(p0, p1, out);
    if (child_) {
      scratch_.resize((p1 - p0) * stored);
      produce(p0, p1, scratch_.data());
    } else {
      bands_[0]->ensure(p0, p1);
    }
    for (std::size_t r = p0; r < p1; ++r)
      std::copy_n(child_ ? scratch_.data() + (r - p0) * stored + (columns.first - window_.level.first)
                         : bands_[0]->at(r, columns.first),
                  n, out + (r - p0) * n);
  }

 private:
  // Window column j of row r of the level's Mallat layout: the coarse part (rows < child
  // height) from the child and the x-detail band, the rest from the y-detail bands; the
  // window's coarse columns first, then its detail columns.
  void copy_layout_row(std::size_t r, bool detail, std::size_t j0, std::size_t n, T* out) const {
    const Columns& c = window_.coarse;
    const Columns& d = window_.detail;
    const std::size_t nc = c.end - c.first;
    if (j0 < nc) {  // two plain copies: memcpy
      const T* left = detail ? bands_[2]->at(r, c.first + j0) : child_->at(r, c.first + j0);
      std::copy_n(left, std::min(j0 + n, nc) - j0, out);
    }
    if (j0 + n <= nc) return;
    const std::size_t from = std::max(j0, nc);
    const T* right = bands_[detail ? 3 : 1]->at(r, d.first + (from - nc));
    std::copy_n(right, j0 + n - from, out + (from - j0));
  }

  // Rows [p0, p1) of the window's columns into `out` (rows of that many columns).
  void produce(std::size_t p0, std::size_t p1, T* out) {
    const std::size_t nx = window_.level.end - window_.level.first;
    if (height_ > 1) {
      // Window [w0, w1) of the rows: starts even (so its even wire is the coarse band)
      // and ends at an even row or the column's end.
      const ColumnWindow rw = column_window({p0, p1}, height_, reach_);
      const std::size_t w0 = rw.level.first, c0 = rw.coarse.first, c1 = rw.coarse.end, d1 = rw.detail.end;
      const std::size_t n = rw.level.end - w0;
      child_->ensure(c0, c1);
      for (int o : {1, 2, 3})
        if (bands_[o]) bands_[o]->ensure(c0, o == 1 ? c1 : d1);
      const std::size_t chunks = (nx + kColumnChunk - 1) / kColumnChunk;
      ex_.run(chunks, [&](std::size_t k) {
        const std::size_t x0 = k * kColumnChunk, nb = std::min(kColumnChunk, nx - x0);
        T* g = thread_rows<T>(n * nb);  // every row is written below
        for (std::size_t i = 0; i < n; ++i) {
          const bool detail = i >= c1 - c0;
          copy_layout_row(c0 + (detail ? i - (c1 - c0) : i), detail, x0, nb, g + i * nb);
        }
        t_.synthesize_columns(std::span<T>(g, n * nb), nb);
        for (std::size_t p = p0; p < p1; ++p) std::copy_n(g + (p - w0) * nb, nb, out + (p - p0) * nx + x0);
      });
    } else {
      child_->ensure(0, 1);
      if (bands_[1]) bands_[1]->ensure(0, 1);
      copy_layout_row(0, false, 0, nx, out);
    }
    if (width_ <= 1) return;
    ex_.run(p1 - p0, [&](std::size_t k) { t_.synthesize(std::span<T>(out + k * nx, nx)); });
  }

  const Transform1D& t_;
  std::size_t reach_, width_, height_;
  ColumnWindow window_;               // the columns stored, and those read from the child and bands
  std::unique_ptr<LevelRows> child_;  // level l + 1; null at the coarsest level
  Bands bands_;                       // [0]: the coarse band (coarsest level only), [1..3]: details of l + 1
  const Executor& ex_;
  RowWindow<T> rows_;     // this level's rows (every row produced before it is read)
  RowBuffer<T> scratch_;  // produce_into's rows where it keeps only some of the window's columns
};

// Index of the band of `level` with `orientation` in s.bands, or npos.
std::size_t find_band(const ParsedStream& s, int level, unsigned orientation) {
  for (std::size_t i = 0; i < s.bands.size(); ++i)
    if (s.bands[i].level == level && s.bands[i].orientation == orientation) return i;
  return std::size_t(-1);
}

// The pipeline of levels `levels` down to `level` for one component, computing the columns
// `out` of `level` (and at each coarser level the columns those need).
template <class T>
std::unique_ptr<LevelRows<T>> build_levels(const ParsedStream& s,
                                           const std::vector<std::vector<std::size_t>>& by_band,
                                           std::size_t component, int level, Columns out,
                                           const Transform1D& t, std::size_t reach, const Executor& ex) {
  const StreamHeader& h = s.header;
  const std::size_t nb = s.bands.size();
  std::vector<ColumnWindow> windows(std::size_t(h.levels + 1));  // by level, level..levels
  for (int l = level; l <= h.levels; ++l) {
    const std::size_t width = level_extent(h.dims, l)[0];
    windows[std::size_t(l)] = l == h.levels ? ColumnWindow{out, out, {}} : column_window(out, width, reach);
    out = windows[std::size_t(l)].coarse;
  }
  auto band_rows = [&](std::size_t band, Columns wanted) {
    return std::make_unique<BandRows<T>>(s, by_band[component * nb + band], s.bands[band], wanted, ex);
  };
  typename LevelRows<T>::Bands coarse(4);
  coarse[0] = band_rows(0, windows[std::size_t(h.levels)].level);
  auto rows = std::make_unique<LevelRows<T>>(t, reach, level_extent(h.dims, h.levels),
                                             windows[std::size_t(h.levels)], nullptr, std::move(coarse), ex);
  for (int l = h.levels - 1; l >= level; --l) {
    const ColumnWindow& w = windows[std::size_t(l)];
    typename LevelRows<T>::Bands details(4);
    for (unsigned o : {1u, 2u, 3u}) {
      const std::size_t band = find_band(s, l + 1, o);
      if (band != std::size_t(-1)) details[o] = band_rows(band, o == 2 ? w.coarse : w.detail);
    }
    rows = std::make_unique<LevelRows<T>>(t, reach, level_extent(h.dims, l), w, std::move(rows),
                                          std::move(details), ex);
  }
  return rows;
}

// Block indices of every (component, band), in stream order.
std::vector<std::vector<std::size_t>> blocks_by_band(const ParsedStream& s) {
  std::vector<std::vector<std::size_t>> by_band(std::size_t(s.header.channels) * s.bands.size());
  for (std::size_t i = 0; i < s.blocks.size(); ++i)
    by_band[s.blocks[i].component * s.bands.size() + s.blocks[i].band].push_back(i);
  return by_band;
}

// Whether each block decodes on its own (some coders' blocks need their parent bands first).
bool blocks_decode_alone(const StreamHeader& h) { return coder_traits(h.entropy).blocks_alone; }

// Columns the PSNR check synthesizes at a time: its memory (each level's window and its
// bands' block rows, for every component) grows with this, not with the image's width. The
// cost is the blocks straddling tiles' edges and the coarse levels, decoded once per tile.
constexpr std::size_t kPsnrTileColumns = 1024;

// Columns [first, end) of a view (the same samples, the same row and channel strides).
ImageView columns_of(const ImageView& v, Columns c) {
  ImageView out = v;
  out.data = static_cast<const std::uint8_t*>(v.data) +
             std::ptrdiff_t(c.first) * v.pixel_stride * std::ptrdiff_t(bytes_per_sample(v.storage));
  out.width = c.end - c.first;
  return out;
}

// The squared error of every component's full-resolution pipeline against the reference in
// columns `tile`, added up strip by strip. The full-resolution rows are synthesized straight
// into the compared strip (read once, so never cached).
template <class T>
double tile_squared_error(const ImageView& reference, const ParsedStream& s,
                          const std::vector<std::vector<std::size_t>>& by_band, Columns tile,
                          const Transform1D& t, std::size_t reach, const Executor& ex) {
  const StreamHeader& h = s.header;
  std::vector<std::unique_ptr<LevelRows<T>>> levels;
  for (std::size_t c = 0; c < h.channels; ++c)
    levels.push_back(build_levels<T>(s, by_band, c, 0, tile, t, reach, ex));
  const ImageView columns = columns_of(reference, tile);
  std::vector<std::vector<T>> strip(h.channels);
  double sum_sq = 0.0;
  for (std::size_t y0 = 0; y0 < columns.height; y0 += kLevelChunk) {
    const std::size_t y1 = std::min(columns.height, y0 + kLevelChunk);
    for (std::size_t c = 0; c < h.channels; ++c) {
      strip[c].resize((y1 - y0) * columns.width);
      levels[c]->produce_into(y0, y1, tile, strip[c].data());
    }
    if constexpr (std::is_same_v<T, float>)
      sum_sq += components_squared_error(columns, y0, y1 - y0, strip, h.colour, h.nonnegative);
    else
      sum_sq += components_squared_error(columns, y0, y1 - y0, strip, h.colour);
    if (columns.drop_rows)  // a mapped input: its compared rows need not stay resident
      columns.drop_rows(columns.drop_context, columns, y0, y1);
  }
  return sum_sq;
}

// The squared error of the stream's full-resolution decode against the reference, tile by
// tile of at most kPsnrTileColumns columns.
template <class T>
double strip_squared_error(const ImageView& reference, const ParsedStream& s, const Transform1D& t,
                           std::size_t reach, const Executor& ex) {
  const auto by_band = blocks_by_band(s);
  const std::size_t w = reference.width,
                    tiles = std::max<std::size_t>(1, (w + kPsnrTileColumns - 1) / kPsnrTileColumns);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < tiles; ++k)
    sum_sq +=
        tile_squared_error<T>(reference, s, by_band, {k * w / tiles, (k + 1) * w / tiles}, t, reach, ex);
  return sum_sq;
}

}  // namespace

std::optional<double> strip_psnr(const ImageView& reference, const ParsedStream& s, const Executor& ex) {
  const StreamHeader& h = s.header;
  if (!blocks_decode_alone(h)) return std::nullopt;
  const auto t = make_stream_transform(h);
  const std::size_t reach = synthesis_reach(*t);
  if (reach == 0) return std::nullopt;
  const double sum_sq = h.reversible ? strip_squared_error<std::int32_t>(reference, s, *t, reach, ex)
                                     : strip_squared_error<float>(reference, s, *t, reach, ex);
  return psnr_of_squared_error(reference, sum_sq);
}

struct ImageStripDecoder::State {
  ParsedStream stream;
  Transform1DPtr transform;
  const Executor* ex = nullptr;
  Extent size{};
  int level = 0;
  double gain = 1.0;
  std::size_t next_row = 0;
  std::vector<std::vector<std::size_t>> by_band;              // block indices per (component, band)
  std::vector<std::unique_ptr<LevelRows<float>>> float_rows;  // one per component
  std::vector<std::unique_ptr<LevelRows<std::int32_t>>> int_rows;
};

ImageStripDecoder::ImageStripDecoder(std::unique_ptr<State> state) : state_(std::move(state)) {}
ImageStripDecoder::~ImageStripDecoder() = default;

std::unique_ptr<ImageStripDecoder> ImageStripDecoder::open(std::span<const std::uint8_t> bytes, int level,
                                                           const Executor& ex, const DecodeLimits& limits) {
  auto st = std::make_unique<State>();
  st->stream = parse_container(bytes, level, limits);
  const ParsedStream& s = st->stream;
  const StreamHeader& h = s.header;
  require_stream(h.dims[2] == 1, "a volume stream, not an image");
  if (!is_integer(h.type)) return nullptr;  // float images go through the coded-domain transfer
  if (!blocks_decode_alone(h)) return nullptr;
  st->transform = make_stream_transform(h);
  const std::size_t reach = synthesis_reach(*st->transform);
  if (reach == 0) return nullptr;
  st->ex = &ex;
  st->size = level_extent(h.dims, level);
  st->level = level;
  if (!h.reversible) st->gain = coarse_gain(*st->transform, h.dims, level);
  st->by_band = blocks_by_band(s);
  const Columns all{0, st->size[0]};
  for (std::size_t c = 0; c < h.channels; ++c) {
    if (h.reversible)
      st->int_rows.push_back(
          build_levels<std::int32_t>(s, st->by_band, c, level, all, *st->transform, reach, ex));
    else
      st->float_rows.push_back(build_levels<float>(s, st->by_band, c, level, all, *st->transform, reach, ex));
  }
  return std::unique_ptr<ImageStripDecoder>(new ImageStripDecoder(std::move(st)));
}

std::size_t ImageStripDecoder::width() const { return state_->size[0]; }
std::size_t ImageStripDecoder::height() const { return state_->size[1]; }
std::size_t ImageStripDecoder::channels() const { return state_->stream.header.channels; }
SampleType ImageStripDecoder::type() const { return state_->stream.header.type; }
ImageMetadata ImageStripDecoder::metadata() const {
  return decoded_metadata(state_->stream.header, state_->level);
}

namespace {

// Rows [y0, y1) of every component's pipeline, into the planes of `out` (converted to float:
// reversible samples are integers below 2^24, exact in float).
template <class T>
void copy_rows(std::vector<std::unique_ptr<LevelRows<T>>>& levels, std::size_t y0, std::size_t y1,
               Image& out) {
  for (std::size_t c = 0; c < levels.size(); ++c) {
    levels[c]->ensure(y0, y1);
    for (std::size_t y = y0; y < y1; ++y)
      std::copy_n(levels[c]->at(y, 0), out.width, out.plane(c) + (y - y0) * out.width);
  }
}

}  // namespace

// The same steps as decode_image's (image_from_components, finish_image_in_place): gain,
// inverse colour transform (RCT on the integers), level shift, rounding and clamping.
Image ImageStripDecoder::next(std::size_t rows) {
  State& st = *state_;
  const StreamHeader& h = st.stream.header;
  const std::size_t y0 = st.next_row, y1 = std::min(height(), y0 + std::max<std::size_t>(rows, 1));
  st.next_row = y1;
  Image strip(width(), y1 - y0, channels(), type());
  if (y1 == y0) return strip;
  if (h.reversible) {
    copy_rows(st.int_rows, y0, y1, strip);  // RCT needs the integers: undone on them first
    if (h.colour == ColourTransform::rct) {
      std::vector<std::vector<std::int32_t>> p(3, std::vector<std::int32_t>(strip.plane_size()));
      for (std::size_t c = 0; c < 3; ++c) std::copy_n(strip.plane(c), strip.plane_size(), p[c].data());
      inverse_rct(p[0].data(), p[1].data(), p[2].data(), strip.plane_size());
      for (std::size_t c = 0; c < 3; ++c) std::copy_n(p[c].data(), strip.plane_size(), strip.plane(c));
    }
    finish_image_in_place(strip, ColourTransform::none, *st.ex);  // in parallel: tasks own their samples
    return strip;
  }
  copy_rows(st.float_rows, y0, y1, strip);
  if (st.gain != 1.0)  // dividing by exactly 1 would change no value
    for (float& v : strip.samples) v = float(double(v) / st.gain);
  finish_image_in_place(strip, h.colour, *st.ex);  // in parallel (serial, 5% of decode CPU)
  return strip;
}

}  // namespace pupwave
