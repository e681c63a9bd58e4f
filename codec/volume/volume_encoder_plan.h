#pragma once
// Internal to the volume encoder: the validated options, the stream header being built and the
// bricks to code, shared by the fixed-step / lossless / max-error path (volume_encoder.cpp,
// volume_encoder_bricks.cpp, volume_encoder_bound.cpp) and the rate-controlled path
// (volume_encoder_rate.cpp).

#include <atomic>
#include <memory>
#include <span>
#include <vector>

#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "codec/volume/volume_missing.h"
#include "codec/volume/volume_view.h"

namespace pupwave {

// One brick to code: its grid, its index among the grid's bricks (over all blocks of a
// sparse-native grid in turn), the block it lies in (0 for box grids), its box in there and the
// view of that box grid or block the brick is gathered from.
struct BrickJob {
  std::uint32_t grid = 0;
  std::uint32_t brick = 0;
  BrickBox box;
  std::uint32_t block = 0;
  VolumeView view;
  bool missing = false;  // the view's inactive voxels are missing values, filled before coding
};

struct VolumePlan {
  VolumeStreamHeader header;
  Transform1DPtr transform;
  BrickCoding coding;
  std::vector<MaskChunk> masks;                   // per grid (empty for dense)
  std::vector<BlocksChunk> layouts;               // per grid (empty unless sparse-native)
  std::vector<std::vector<std::uint8_t>> opaque;  // per grid (empty unless opaque)
  std::vector<std::vector<std::uint8_t>> valid;   // per grid with missing values: its view's mask
  std::vector<BrickJob> jobs;
  std::size_t voxels = 0;              // active voxels of all grids (what bpv counts)
  double range = 0.0;                  // largest value range (max - min of active voxels) over grids
  const Executor* executor = nullptr;  // VolumeEncodeOptions::executor, resolved (never null)
};

// A brick coded with the passes that go into the stream.
struct BrickCode {
  double base_step = 1.0;
  CodedBrick coded;
  std::vector<int> passes;
  std::vector<std::uint8_t> outliers;
  std::size_t outlier_count = 0;
  double max_error = 0.0;  // over voxels that must meet the bound, after correction
  double sse = 0.0;        // squared error over the same voxels
};

// Drops (VolumeView::drop) the rows of each row of bricks of a view (same y and z) once every brick
// of it has been read in a brick pass, so a mapped input does not stay resident until the end.
// Bricks run in parallel and finish in any order: one atomic count of bricks left per row.
class SlabRelease {
 public:
  explicit SlabRelease(const std::vector<BrickJob>& jobs);
  // Job i has read its input for the last time in this pass (thread-safe).
  void done(std::size_t i);

 private:
  const std::vector<BrickJob>& jobs_;
  std::vector<std::size_t> slab_;                     // per job, its brick row (empty: no drops)
  std::unique_ptr<std::atomic<std::size_t>[]> left_;  // per brick row, bricks not yet done
};

// `views[g]` (when its data is set) holds the values of box grid g; see encode_volumes.
VolumePlan plan_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                        const VolumeEncodeOptions& options);

// Samples of a job's brick (x fastest) and the flags of voxels that count (empty: all),
// gathered from its view: the only place the encoder reads voxel values after planning. S as
// gather_box takes it (the brick pass uses the view's storage type, see code_and_write).
template <class S>
void brick_samples(const BrickJob& job, std::vector<S>& samples, std::vector<std::uint8_t>& active) {
  gather_box(job.view, job.box.offset, job.box.size, samples, active);
  if (job.missing) fill_missing(samples, active, job.box.size);
}

// Max-error coding of a brick (its samples and voxels that count, as brick_samples gives them):
// every pass of every block at the step chosen for the bound, and the corrections that hold it.
template <class S>
BrickCode code_within_bound(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                            std::span<const S> samples, std::span<const std::uint8_t> active);

// Reconstructs a brick from its chosen passes (exactly as the decoder will, before outliers).
std::vector<double> reconstruct_brick(const VolumePlan& plan, const BrickJob& job, const BrickCode& code);

// Error statistics of a reconstruction (rounded to the stored type) against the original.
void measure_brick(const VolumeGrid& grid, const BrickJob& job, std::vector<double> reconstruction,
                   BrickCode& code);

// The complete stream.
std::vector<std::uint8_t> assemble_volumes(const VolumePlan& plan, const std::vector<BrickCode>& codes);

// Appends a brick's BRIK chunk (its chosen passes and outliers) to out.
void write_brick(std::vector<std::uint8_t>& out, const BrickJob& job, const BrickCode& code);

// What the result needs of a coded brick once its chunk is written.
struct BrickFigures {
  double max_error = 0.0;
  double sse = 0.0;
  std::size_t outliers = 0;
};

// Fixed step, lossless or max-error coding of every brick, each brick's chunk handed to `write`
// (after the head the caller wrote) in stream order as soon as the bricks before it are written:
// only the bricks in flight are held. `write` runs on worker threads, one call at a time.
// Returns each brick's figures, in brick order.
std::vector<BrickFigures> code_and_write(const std::vector<VolumeGrid>& grids, const VolumePlan& plan,
                                         const VolumeEncodeOptions& options, const StreamWriter& write);

// Rate-controlled coding (bpv, psnr): PCRD over every code-block of every brick.
std::vector<BrickCode> code_for_rate(const std::vector<VolumeGrid>& grids, VolumePlan& plan,
                                     const VolumeEncodeOptions& options);

}  // namespace pupwave
