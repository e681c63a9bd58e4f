#include "codec/image/image_strip_encoder.h"

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <vector>

#include "codec/image/image_components.h"
#include "transforms/scratch.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

// Rows of coefficients (interleaved) produced per level at a time: the column analysis of a
// window costs its 2 * reach overlap rows once per chunk, and each level holds a window and a
// chunk of output rows. 32, not 64: 1.3 MiB less peak resident memory for a 4096-wide grey
// encode (of 24 MiB); the overlap it adds costs at most ~2.5% of an ht encode's CPU.
constexpr std::size_t kChunk = 32;
// Most rows read, or handed from a level to the next or to a band, at a time: every receiver
// holds what it needs plus one delivery, so small deliveries keep the buffers near their
// least (a whole chunk at a time held 3.7 MB more for a 4096-wide image).
constexpr std::size_t kPiece = 16;
// Columns per column-analysis task (a window of them stays in cache while lifted).
constexpr std::size_t kColumnChunk = 128;
// Samples per colour-conversion task: a strip of a 4096-wide image in four.
constexpr std::size_t kTaskSamples = std::size_t(1) << 14;

// Takes rows top to bottom, either copied in (add: `count` rows of the receiver's width, row i
// at rows + i * stride) or written in place (append, then appended: a level's column analysis
// writes its output rows straight into its receivers, with no full-width staging copy).
template <class T>
class RowSink {
 public:
  virtual ~RowSink() = default;
  virtual std::size_t width() const = 0;
  // Room for `count` more rows (width() apart), valid until appended(count) is called.
  virtual T* append(std::size_t count) = 0;
  // The rows append gave are written: takes them.
  virtual void appended(std::size_t count) = 0;
  void add(const T* rows, std::size_t stride, std::size_t count) {
    T* to = append(count);
    for (std::size_t r = 0; r < count; ++r) std::copy_n(rows + r * stride, width(), to + r * width());
    appended(count);
  }
};

// One subband of the component: keeps its rows until a block row is complete, then hands its
// blocks to the sink (as tasks, each copying its block out) and drops those rows.
template <class T>
class BandBlocks final : public RowSink<T> {
 public:
  BandBlocks(const ImagePlan& plan, const std::vector<std::size_t>& blocks, const Subband& band,
             const BlockSink<T>& sink)
      : plan_(plan), sink_(sink), x0_(band.offset[0]), y0_(band.offset[1]), width_(band.size[0]) {
    for (std::size_t i : blocks) {  // partition order: block rows top to bottom, x fastest
      const CodeBlock& b = plan.blocks[i];
      if (block_rows_.empty() || block_rows_.back().y0 != b.offset[1] - y0_)
        block_rows_.push_back({b.offset[1] - y0_, b.offset[1] - y0_ + b.size[1], {}});
      block_rows_.back().blocks.push_back(i);
    }
    // The most rows held: a block row less one, and the rows one delivery adds.
    std::size_t tallest = 0;
    for (const auto& r : block_rows_) tallest = std::max(tallest, r.y1 - r.y0);
    data_.reserve((tallest + kPiece) * width_);
  }

  std::size_t width() const override { return width_; }

  T* append(std::size_t count) override {
    data_.resize((hi_ + count - lo_) * width_);
    return data_.data() + (hi_ - lo_) * width_;
  }

  void appended(std::size_t count) override {
    hi_ += count;
    while (next_ < block_rows_.size() && hi_ >= block_rows_[next_].y1) emit_row(block_rows_[next_++]);
  }

  bool done() const { return next_ == block_rows_.size(); }

 private:
  struct BlockRow {
    std::size_t y0, y1;  // band rows
    std::vector<std::size_t> blocks;
  };

  // Coded as soon as complete rather than gathered per strip: a strip of a wide image
  // completes block rows of several bands and levels at once (a copy of each held 3 MB for
  // a 4096-wide image).
  void emit_row(const BlockRow& br) {
    plan_.executor->run(br.blocks.size(), [&](std::size_t k) {
      const std::size_t i = br.blocks[k];
      const CodeBlock& b = plan_.blocks[i];
      RowBuffer<T> values(b.count());  // every sample copied in before it is read
      for (std::size_t y = 0; y < b.size[1]; ++y)
        std::copy_n(data_.data() + (br.y0 + y - lo_) * width_ + (b.offset[0] - x0_), b.size[0],
                    values.data() + y * b.size[0]);
      sink_(i, values);
    });
    data_.erase(data_.begin(), data_.begin() + std::ptrdiff_t((br.y1 - lo_) * width_));
    lo_ = br.y1;
  }

  const ImagePlan& plan_;
  const BlockSink<T>& sink_;
  std::size_t x0_, y0_, width_;
  std::vector<BlockRow> block_rows_;
  std::size_t next_ = 0;  // first block row not emitted yet
  RowBuffer<T> data_;     // band rows [lo_, hi_)
  std::size_t lo_ = 0, hi_ = 0;
};

// One level of the forward transform: takes the rows of the level-(l-1) coarse band (the
// image at l = 1), analyses each row as it arrives, and produces coefficient rows a chunk at a
// time by column analysis over a window reaching `reach` rows beyond the chunk. The coarse
// rows' low half goes to the next level (or the coarse band), the rest to the detail bands:
// out[0] coarse rows' low half, out[1] their high half, out[2] and out[3] the detail rows'
// halves (Mallat layout; null where the band does not exist).
template <class T>
class LevelAnalysis final : public RowSink<T> {
 public:
  LevelAnalysis(const Transform1D& t, std::size_t reach, const Extent& region, std::vector<RowSink<T>*> out,
                const Executor& ex)
      : t_(t), reach_(reach), width_(region[0]), height_(region[1]), out_(std::move(out)), ex_(ex) {
    // The most rows held: a window (a chunk and its reach on both sides) less one row, and the
    // rows one delivery adds (so the buffer is never reallocated to twice that).
    data_.reserve(std::min(height_, kChunk + 2 * reach_ + 2 + kPiece) * width_);
  }

  std::size_t width() const override { return width_; }

  T* append(std::size_t count) override {
    data_.resize((hi_ + count - lo_) * width_);
    return data_.data() + (hi_ - lo_) * width_;
  }

  void appended(std::size_t count) override {
    T* first = data_.data() + (hi_ - lo_) * width_;
    if (width_ > 1)
      ex_.run(count, [&](std::size_t r) { t_.analyze(std::span<T>(first + r * width_, width_)); });
    hi_ += count;
    while (p_ < height_) {
      const std::size_t p1 = std::min(height_, p_ + kChunk);
      if (hi_ < window_end(p1)) break;
      produce(p1);
      p_ = p1;
      const std::size_t keep = window_start(p_);
      if (keep > lo_) {
        data_.erase(data_.begin(), data_.begin() + std::ptrdiff_t((keep - lo_) * width_));
        lo_ = keep;
      }
    }
  }

 private:
  // Window [window_start(p0), window_end(p1)) of the columns for coefficients [p0, p1): starts
  // even (so its even wire is the coarse band) and ends at an even row or the column's end.
  std::size_t window_start(std::size_t p0) const { return (p0 > reach_ ? p0 - reach_ : 0) & ~std::size_t(1); }
  std::size_t window_end(std::size_t p1) const {
    std::size_t w1 = std::min(height_, p1 + reach_);
    if (w1 % 2 != 0 && w1 < height_) ++w1;
    return w1;
  }

  void produce(std::size_t p1) {
    const std::size_t wc = coarse_size(width_);
    if (height_ == 1) {  // no column to analyse: the row is the coarse row
      deliver(data_.data(), 1, true, wc);
      return;
    }
    const std::size_t w0 = window_start(p_), w1 = window_end(p1), n = w1 - w0;
    const std::size_t c0 = p_ / 2, c1 = (p1 + 1) / 2, d1 = p1 / 2, nc = coarse_size(n);
    // The rows go straight into the receivers (a full-width copy of a chunk, nested over the
    // levels, would be 1 MiB of a 4096-wide grey encode's peak), handed on in the order
    // deliver gave them: coarse low and high halves, then detail (one piece each: kChunk / 2
    // rows at most).
    const std::size_t nd = d1 > c0 ? d1 - c0 : 0;
    const std::array<std::size_t, 4> rows{c1 - c0, c1 - c0, nd, nd};
    std::array<T*, 4> to{};
    for (std::size_t o = 0; o < 4; ++o)
      if (out_[o] != nullptr && rows[o] > 0) to[o] = out_[o]->append(rows[o]);
    const std::size_t chunks = (width_ + kColumnChunk - 1) / kColumnChunk;
    ex_.run(chunks, [&](std::size_t k) {
      const std::size_t x0 = k * kColumnChunk, nb = std::min(kColumnChunk, width_ - x0);
      T* g = thread_rows<T>(n * nb);  // every row is written below
      for (std::size_t i = 0; i < n; ++i)
        std::copy_n(data_.data() + (w0 + i - lo_) * width_ + x0, nb, g + i * nb);
      t_.analyze_columns(std::span<T>(g, n * nb), nb);
      for (std::size_t j = c0; j < c1; ++j) scatter(g + (j - w0 / 2) * nb, x0, nb, wc, j - c0, to[0], to[1]);
      for (std::size_t j = c0; j < d1; ++j)
        scatter(g + (nc + j - w0 / 2) * nb, x0, nb, wc, j - c0, to[2], to[3]);
    });
    for (std::size_t o = 0; o < 4; ++o)
      if (out_[o] != nullptr && rows[o] > 0) out_[o]->appended(rows[o]);
  }

  // Columns [x0, x0 + nb) of an output row to row `r` of the receivers: those left of `wc` to
  // `low` (width wc), the rest to `high` (width width_ - wc); a null receiver takes nothing.
  void scatter(const T* row, std::size_t x0, std::size_t nb, std::size_t wc, std::size_t r, T* low,
               T* high) const {
    const std::size_t split = std::clamp(wc, x0, x0 + nb);
    if (low != nullptr && split > x0) std::copy_n(row, split - x0, low + r * wc + x0);
    if (high != nullptr && x0 + nb > split)
      std::copy_n(row + (split - x0), x0 + nb - split, high + r * (width_ - wc) + (split - wc));
  }

  void deliver(const T* rows, std::size_t count, bool coarse, std::size_t wc) {
    RowSink<T>* low = out_[coarse ? 0 : 2];
    RowSink<T>* high = out_[coarse ? 1 : 3];
    for (std::size_t r = 0; r < count; r += kPiece) {
      const std::size_t n = std::min(kPiece, count - r);
      if (low) low->add(rows + r * width_, width_, n);
      if (high) high->add(rows + r * width_ + wc, width_, n);
    }
  }

  const Transform1D& t_;
  std::size_t reach_, width_, height_;
  std::vector<RowSink<T>*> out_;
  const Executor& ex_;
  RowBuffer<T> data_;            // row-analysed input rows [lo_, hi_)
  std::size_t lo_ = 0, hi_ = 0;  // input rows held
  std::size_t p_ = 0;            // next coefficient (interleaved row) to produce
};

// Index of the band of `level` with `orientation` in plan.bands, or npos.
std::size_t find_band(const ImagePlan& plan, int level, unsigned orientation) {
  for (std::size_t i = 0; i < plan.bands.size(); ++i)
    if (plan.bands[i].level == level && plan.bands[i].orientation == orientation) return i;
  return std::size_t(-1);
}

// Rows [y0, y1) of component c (colour converted and level shifted) as tasks of a few rows
// each: the converters split rows into tasks of 2^16 samples, so a strip of a wide image would be
// one task, and its colour conversion (6% of an RGB ht encode) would run on one thread.
template <class T>
void component_rows(const ImagePlan& plan, std::size_t c, std::size_t y0, std::size_t y1, T* out,
                    const Executor& ex) {
  if constexpr (std::is_same_v<T, float>)
    float_component_rows(plan.source, plan.header.colour, c, y0, y1, out, ex);
  else
    integer_component_rows(plan.source, plan.header.colour, c, y0, y1, out, ex);
}

// Rows [y0, y1) of component c (colour converted and level shifted). Colour converted rows go
// as tasks of a few rows each: the converters split rows into tasks of 2^16 samples, so a
// strip of a 4096-wide image would be one task, and its ICT (6% of an RGB ht encode) would run
// on one thread. Rows only level shifted keep the converters' tasks (a smaller one costs more than it).
template <class T>
void strip_rows(const ImagePlan& plan, std::size_t c, std::size_t y0, std::size_t y1, T* out) {
  if (plan.header.colour == ColourTransform::none || c >= 3)
    return component_rows<T>(plan, c, y0, y1, out, *plan.executor);
  const std::size_t width = plan.header.dims[0];
  const std::size_t per_task = std::max<std::size_t>(1, kTaskSamples / std::max<std::size_t>(width, 1));
  const std::size_t tasks = (y1 - y0 + per_task - 1) / per_task;
  plan.executor->run(tasks, [&](std::size_t k) {
    const std::size_t a = y0 + k * per_task, b = std::min(y1, a + per_task);
    component_rows<T>(plan, c, a, b, out + (a - y0) * width, serial_executor());
  });
}

}  // namespace

template <class T>
void stream_component(const ImagePlan& plan, std::size_t c, const BlockSink<T>& sink,
                      const std::function<bool()>& stop) {
  if (plan.strip_reach == 0) throw std::logic_error("stream_component: the plan's transform is not local");
  const StreamHeader& h = plan.header;
  const Executor& ex = *plan.executor;
  std::vector<std::vector<std::size_t>> by_band(plan.bands.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    if (plan.blocks[i].component == c) by_band[plan.blocks[i].band].push_back(i);
  std::vector<std::unique_ptr<BandBlocks<T>>> bands(plan.bands.size());
  for (std::size_t b = 0; b < plan.bands.size(); ++b)
    bands[b] = std::make_unique<BandBlocks<T>>(plan, by_band[b], plan.bands[b], sink);
  // Levels from the coarsest up, each feeding the next coarser one.
  std::vector<std::unique_ptr<LevelAnalysis<T>>> levels;
  RowSink<T>* top = bands[0].get();
  for (int l = h.levels; l >= 1; --l) {
    std::vector<RowSink<T>*> out{top, nullptr, nullptr, nullptr};
    for (unsigned o : {1u, 2u, 3u})
      if (const std::size_t b = find_band(plan, l, o); b != std::size_t(-1)) out[o] = bands[b].get();
    levels.push_back(std::make_unique<LevelAnalysis<T>>(*plan.transform, plan.strip_reach,
                                                        level_extent(h.dims, l - 1), std::move(out), ex));
    top = levels.back().get();
  }
  const std::size_t width = h.dims[0], height = h.dims[1];
  std::vector<T> rows(kPiece * width);
  for (std::size_t y0 = 0; y0 < height; y0 += kPiece) {
    const std::size_t y1 = std::min(height, y0 + kPiece);
    strip_rows<T>(plan, c, y0, y1, rows.data());
    // With the rows before too: the kernel may map pages again while mapping those after them
    // (ext4's large folios; 4 MB of a 16 MB PGM stay mapped when only [y0, y1) is dropped).
    if (plan.source.drop_rows)
      plan.source.drop_rows(plan.source.drop_context, plan.source, y0 > kChunk ? y0 - kChunk : 0, y1);
    top->add(rows.data(), width, y1 - y0);
    if (stop()) return;
  }
  for (const auto& b : bands)
    if (!b->done()) throw std::logic_error("stream_component: a code-block was never completed");
}

template void stream_component<float>(const ImagePlan&, std::size_t, const BlockSink<float>&,
                                      const std::function<bool()>&);
template void stream_component<std::int32_t>(const ImagePlan&, std::size_t, const BlockSink<std::int32_t>&,
                                             const std::function<bool()>&);

}  // namespace pupwave
