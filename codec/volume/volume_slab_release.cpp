// SlabRelease: per row of bricks, counts of bricks left in a brick pass (volume_encoder_plan.h).
#include <map>
#include <tuple>

#include "codec/volume/volume_encoder_plan.h"

namespace pupwave {

SlabRelease::SlabRelease(const std::vector<BrickJob>& jobs) : jobs_(jobs) {
  bool any = false;
  for (const BrickJob& job : jobs) any = any || job.view.drop_rows != nullptr;
  if (!any) return;  // nothing to drop: no counting either
  // A row of bricks: those of one grid and block (one view) that start at the same y and z. Rows
  // rather than whole z-slabs: two threads finishing one slab and starting the next held two
  // slabs of input (8 MiB of a 256^3 u8 volume, half the raw size); rows hold a few bricks' worth.
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::size_t, std::size_t>, std::size_t> index;
  std::vector<std::size_t> count;
  slab_.reserve(jobs.size());
  for (const BrickJob& job : jobs) {
    const auto [it, added] =
        index.try_emplace({job.grid, job.block, job.box.offset[2], job.box.offset[1]}, count.size());
    if (added) count.push_back(0);
    ++count[it->second];
    slab_.push_back(it->second);
  }
  left_ = std::make_unique<std::atomic<std::size_t>[]>(count.size());
  for (std::size_t s = 0; s < count.size(); ++s) left_[s].store(count[s], std::memory_order_relaxed);
}

void SlabRelease::done(std::size_t i) {
  if (slab_.empty()) return;
  // acq_rel: the last brick of a slab sees every other brick's reads finished before it drops.
  if (left_[slab_[i]].fetch_sub(1, std::memory_order_acq_rel) != 1) return;
  const BrickJob& job = jobs_[i];
  job.view.drop(job.box.offset[2], job.box.offset[2] + job.box.size[2], job.box.offset[1],
                job.box.offset[1] + job.box.size[1]);
}

}  // namespace pupwave
