// The brick pass of the fixed-step, lossless and max-error modes (code_and_write in
// volume_encoder_plan.h): bricks coded in parallel, taken in index order, each serialised to its
// BRIK chunk as soon as it is coded and written in stream order, so an encode holds only the
// bricks in flight, never the coded volume.
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "codec/error.h"
#include "codec/volume/volume_encoder_plan.h"
#include "codec/volume/volume_outliers.h"
#include "codec/volume/volume_tasks.h"

namespace pupwave {
namespace {

// Per-thread buffers reused from brick to brick (its samples, as the input's own type, and the
// check of its coding): fresh brick-sized vectors per brick cost page faults and leave glibc
// arenas holding several.
template <class S>
struct BrickScratch {
  std::vector<S> samples;
  std::vector<std::uint8_t> active;
  BrickWork work;                    // the transform, then the reconstruction that checks it
  std::vector<std::uint8_t> joined;  // the brick's codewords, one after the other
  // Drops buffers larger than a 64^3 brick needs (a 256^3 brick's would stay with the thread).
  void trim() {
    constexpr std::size_t kKeptVoxels = std::size_t(1) << 18;
    if (samples.capacity() > kKeptVoxels || work.integer.capacity() > kKeptVoxels ||
        work.real.capacity() > kKeptVoxels)
      *this = BrickScratch{};
  }
};

// Error of a reconstruction (rounded to the stored type) against the samples, over the voxels
// that count, in voxel order (as measure_brick sums it).
template <class S, class T>
StoredError error_of(std::span<const S> samples, std::span<const std::uint8_t> active,
                     const std::vector<T>& reconstruction, VoxelType type) {
  double max_error = 0.0, sse = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!active.empty() && active[i] == 0) continue;
    const double e = std::abs(double(samples[i]) - to_stored(double(reconstruction[i]), type));
    max_error = std::max(max_error, e);
    sse += e * e;
  }
  return {max_error, sse};
}

// Block entries of a brick's chosen passes, and their codewords joined into `joined` (spans into
// it): what the decoder reads from the chunk.
std::vector<std::span<const std::uint8_t>> joined_codewords(const BrickCode& c,
                                                            std::vector<BlockEntry>& entries,
                                                            std::vector<std::uint8_t>& joined) {
  entries.clear();
  joined.clear();
  for (std::size_t k = 0; k < c.passes.size(); ++k) {
    const EncodedBlock& b = c.coded.coded[k];
    const std::size_t n = b.size(c.passes[k]);
    entries.push_back({c.passes[k] > 0 ? b.planes : 0, c.passes[k], std::uint32_t(n)});
    if (n == 0) continue;
    const TruncationPoint& end = b.passes[std::size_t(c.passes[k] - 1)];
    joined.insert(joined.end(), b.committed.begin(), b.committed.begin() + std::ptrdiff_t(end.prefix));
    joined.insert(joined.end(), end.tail.begin(), end.tail.end());
  }
  std::vector<std::span<const std::uint8_t>> spans;
  std::size_t at = 0;
  for (const BlockEntry& e : entries) {
    spans.emplace_back(joined.data() + at, e.length);
    at += e.length;
  }
  return spans;
}

// A brick coded at one base step with every pass (step and lossless modes), checked by decoding
// it as the decoder will (into the coefficient buffer the coding is done with).
template <class S>
BrickCode code_at_step(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                       BrickScratch<S>& s, double base) {
  BrickCode code;
  code.base_step = base;
  const std::span<const S> samples(s.samples);
  code.coded = code_brick(plan.coding, samples, job.box.size, base, s.work);
  for (const auto& b : code.coded.coded) code.passes.push_back(b.pass_count());
  std::vector<BlockEntry> entries;
  const auto spans = joined_codewords(code, entries, s.joined);
  const VoxelType type = grid.volume.type;
  StoredError e;
  if (plan.coding.reversible) {
    decode_brick_into(plan.coding, job.box.size, base, entries, spans, s.work.integer);
    e = error_of(samples, s.active, s.work.integer, type);
  } else {
    decode_brick_into(plan.coding, job.box.size, base, entries, spans, s.work.real);
    e = error_of(samples, s.active, s.work.real, type);
  }
  code.max_error = e.max;
  code.sse = e.sse;
  return code;
}

// A job's brick coded as the options say, its samples gathered as S (the type of the view's
// storage, so a u8 brick is held in a quarter of a MiB, not two as double).
template <class S>
BrickCode code_job(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                   const VolumeEncodeOptions& o) {
  thread_local BrickScratch<S> scratch;
  brick_samples(job, scratch.samples, scratch.active);
  BrickCode code;
  if (o.mode == VolumeRateMode::max_error)
    code = code_within_bound(plan, grid, job, std::span<const S>(scratch.samples), scratch.active);
  else
    code = code_at_step(plan, grid, job, scratch, o.mode == VolumeRateMode::step ? o.target : 1.0);
  scratch.trim();
  return code;
}

BrickCode code_job(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                   const VolumeEncodeOptions& o) {
  switch (job.view.storage) {
    case VoxelType::u8: return code_job<std::uint8_t>(plan, grid, job, o);
    case VoxelType::u16: return code_job<std::uint16_t>(plan, grid, job, o);
    case VoxelType::f32: return code_job<float>(plan, grid, job, o);
    case VoxelType::f64: break;
  }
  return code_job<double>(plan, grid, job, o);
}

// Hands chunks to the writer in stream order while bricks finish in any order: a chunk waits
// (serialised, the size of its share of the stream) only until those before it are written.
class OrderedChunks {
 public:
  OrderedChunks(std::size_t count, const StreamWriter& write) : count_(count), write_(write) {}
  // Chunk of brick i (thread-safe); writes it and every waiting chunk it was holding back.
  void put(std::size_t i, std::vector<std::uint8_t> chunk) {
    const std::lock_guard<std::mutex> lock(mutex_);
    waiting_.emplace(i, std::move(chunk));
    for (auto it = waiting_.begin(); it != waiting_.end() && it->first == next_; it = waiting_.erase(it)) {
      write_(it->second);
      ++next_;
    }
  }
  bool complete() const { return next_ == count_ && waiting_.empty(); }

 private:
  std::size_t count_;
  const StreamWriter& write_;
  std::mutex mutex_;
  std::size_t next_ = 0;
  std::map<std::size_t, std::vector<std::uint8_t>> waiting_;
};

}  // namespace

void write_brick(std::vector<std::uint8_t>& out, const BrickJob& job, const BrickCode& c) {
  BrickChunk chunk{job.grid, job.brick, c.base_step, {}, {}, c.outliers};
  for (std::size_t k = 0; k < c.passes.size(); ++k) {
    const EncodedBlock& b = c.coded.coded[k];
    chunk.entries.push_back(
        {c.passes[k] > 0 ? b.planes : 0, c.passes[k], std::uint32_t(b.size(c.passes[k]))});
    if (c.passes[k] == 0) continue;
    // The codeword in its two pieces (the committed prefix and the pass's tail), not joined first.
    const TruncationPoint& end = b.passes[std::size_t(c.passes[k] - 1)];
    chunk.codewords.emplace_back(b.committed.data(), end.prefix);
    chunk.codewords.emplace_back(end.tail);
  }
  write_brick_chunk(out, chunk);
}

std::vector<BrickFigures> code_and_write(const std::vector<VolumeGrid>& grids, const VolumePlan& plan,
                                         const VolumeEncodeOptions& o, const StreamWriter& write) {
  std::vector<BrickFigures> figures(plan.jobs.size());
  SlabRelease release(plan.jobs);  // the input's last read: each slab dropped once coded
  OrderedChunks chunks(plan.jobs.size(), write);
  const double bound = plan.header.max_error;
  run_in_index_order(*plan.executor, plan.jobs.size(), [&](std::size_t i) {
    const BrickJob& job = plan.jobs[i];
    const VolumeGrid& grid = grids[job.grid];
    BrickCode code = code_job(plan, grid, job, o);
    release.done(i);
    if (bound > 0.0 && code.max_error > bound)  // never expected: no chunk past the bound is written
      throw EncodeError("internal error: error bound exceeded after correction");
    figures[i] = {code.max_error, code.sse, code.outlier_count};
    std::vector<std::uint8_t> chunk;
    write_brick(chunk, job, code);
    code = BrickCode{};  // the coded blocks go before the chunk waits for the bricks before it
    chunks.put(i, std::move(chunk));
  });
  if (!chunks.complete()) throw std::logic_error("code_and_write: a brick chunk was not written");
  return figures;
}

}  // namespace pupwave
