#pragma once
// The volume encoder's input: a non-owning, typed, strided view of a box of voxels in the
// caller's memory (a raw file mapped read-only, a sub-box of a larger array, a numpy array), so
// a volume is never copied or widened to double to be coded: the encoder gathers one brick at a
// time and converts only that brick. The owning Volume (volume.h) is what decoders return;
// view_of() views one. VolumeOutput is the decoder's typed, writable counterpart.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "codec/volume/volume.h"

namespace pupwave {

// Strides in elements along x, y, z.
using VolumeStrides = std::array<std::ptrdiff_t, 3>;

// Voxel (x, y, z) is the `storage` element at data + x * strides[0] + y * strides[1] + z * strides[2].
// `type` is what the voxels are (and what the stream records); `storage` is how they are held:
// the same type for a raw file, f64 for an owning Volume (which holds every type as double).
// `active`, when not null, is a mask laid out like the data (same element strides, one byte per
// element, nonzero = active); inactive voxels keep their values and `background` is the value of
// inactive voxels outside the box (as Volume::active and Volume::background).
struct VolumeView {
  const void* data = nullptr;
  Extent dims{0, 0, 0};
  VolumeStrides strides{0, 0, 0};
  VoxelType type = VoxelType::f32;
  VoxelType storage = VoxelType::f32;
  const std::uint8_t* active = nullptr;
  double background = 0.0;
  // Optional, for views of a file mapped read-only: called (with drop_context) for rows [y0, y1)
  // of planes [z0, z1) that the encoder will not read again in the current pass, so their pages
  // leave resident memory (read again, they come back from the page cache). Null: nothing is
  // dropped. Called from worker threads (bricks run in parallel), so it must be thread-safe.
  void (*drop_rows)(const void* context, const VolumeView& view, std::size_t z0, std::size_t z1,
                    std::size_t y0, std::size_t y1) = nullptr;
  const void* drop_context = nullptr;

  std::size_t count() const { return dims[0] * dims[1] * dims[2]; }
  bool is_sparse() const { return active != nullptr; }
  std::ptrdiff_t offset(std::size_t x, std::size_t y, std::size_t z) const {
    return std::ptrdiff_t(x) * strides[0] + std::ptrdiff_t(y) * strides[1] + std::ptrdiff_t(z) * strides[2];
  }
  // Calls drop_rows for rows [y0, y1) of planes [z0, z1) (all rows: whole planes) when it is set.
  void drop(std::size_t z0, std::size_t z1) const { drop(z0, z1, 0, dims[1]); }
  void drop(std::size_t z0, std::size_t z1, std::size_t y0, std::size_t y1) const {
    if (drop_rows != nullptr && z1 > z0 && y1 > y0) drop_rows(drop_context, *this, z0, z1, y0, y1);
  }
  // Voxel (x, y, z) as double (exact for every type).
  double at(std::size_t x, std::size_t y, std::size_t z) const;
  bool is_active(std::size_t x, std::size_t y, std::size_t z) const {
    return active == nullptr || active[offset(x, y, z)] != 0;
  }
  // Row (y, z) from x0, n voxels, as double into out.
  void read_row(std::size_t x0, std::size_t y, std::size_t z, std::size_t n, double* out) const;
};

// Contiguous voxels (x fastest, no padding) held as their own type.
VolumeView contiguous_view(const void* data, const Extent& dims, VoxelType type);
// A view of an owning Volume (samples as double, its mask and background). Throws
// std::invalid_argument when the sample or mask count does not match its dims.
VolumeView view_of(const Volume& volume);
// The box [offset, offset + size) of a view (same memory, same strides).
VolumeView sub_view(const VolumeView& view, const Extent& offset, const Extent& size);

// Throws std::invalid_argument naming the problem for a view that cannot be read: null data,
// an empty extent, a storage that cannot hold the type (integer storage for float voxels, u8
// for u16), zero strides along an axis longer than one voxel.
void check_view(const VolumeView& view);

// The voxels of box [offset, offset + size) of a view, x fastest, as S (`samples`), and the
// mask bytes of the box (`active`, left empty for a dense view). The encoder's only read path.
// S is std::uint8_t, std::uint16_t, float or double and must hold every element of the view's
// storage exactly (sample_type_holds; std::invalid_argument otherwise): the encoder gathers a
// brick as its storage type, not as double, so a worker holds a u8 brick in a quarter of a MiB.
template <class S>
void gather_box(const VolumeView& view, const Extent& offset, const Extent& size, std::vector<S>& samples,
                std::vector<std::uint8_t>& active);

// Whether every element of `storage` is exactly an S (the S gather_box accepts for it).
template <class S>
bool sample_type_holds(VoxelType storage);

// Calls f(value, active) for every voxel, row by row (values as double).
template <class F>
void for_each_voxel(const VolumeView& view, F f) {
  std::vector<double> row(view.dims[0]);
  for (std::size_t z = 0; z < view.dims[2]; ++z)
    for (std::size_t y = 0; y < view.dims[1]; ++y) {
      view.read_row(0, y, z, view.dims[0], row.data());
      for (std::size_t x = 0; x < view.dims[0]; ++x) f(row[x], view.is_active(x, y, z));
    }
}

// What the encoder and the CLI need of a view's values, read in one pass: the range of the active
// voxels, and whether every voxel (active or not) is finite and the largest magnitude of all.
// Missing values (NaN, infinities and voxels equal to `fill`: what a dense grid keeps exactly,
// volume_missing.h) are left out of the range and the magnitude, and counted.
// Drops (VolumeView::drop) every plane once it is read.
struct ValueSummary {
  double lo = 0.0, hi = 0.0;  // min and max of the active voxels not missing (lo > hi: none)
  double largest = 0.0;       // largest |value| of all voxels not missing
  bool finite = true;         // no NaN or infinity among all voxels
  std::size_t missing = 0;    // active voxels that are missing
};
ValueSummary summarize_values(const VolumeView& view, const std::optional<double>& fill = std::nullopt);

// Active voxels of a view (all of them when dense).
std::size_t active_count(const VolumeView& view);

// A writable typed box the decoder fills brick by brick: voxel (x, y, z) is the `storage`
// element at data + offset(x, y, z); `active` (optional, contiguous x fastest, one byte per
// voxel) receives the mask of a sparse grid.
struct VolumeOutput {
  void* data = nullptr;
  Extent dims{0, 0, 0};
  VolumeStrides strides{0, 0, 0};
  VoxelType storage = VoxelType::f32;
  std::uint8_t* active = nullptr;
  // Optional, for an output mapped from a file: called (with done_context) for planes [z0, z1)
  // once the decoder has written every voxel of them (dense grids, full resolution), so their
  // pages can leave resident memory. Called from worker threads (bricks run in parallel), so it
  // must be thread-safe. Null: nothing is reported.
  void (*done_slabs)(const void* context, const VolumeOutput& out, std::size_t z0, std::size_t z1) = nullptr;
  const void* done_context = nullptr;

  std::ptrdiff_t offset(std::size_t x, std::size_t y, std::size_t z) const {
    return std::ptrdiff_t(x) * strides[0] + std::ptrdiff_t(y) * strides[1] + std::ptrdiff_t(z) * strides[2];
  }
  // Stores a value already rounded to the grid's stored type (to_stored).
  void set(std::size_t x, std::size_t y, std::size_t z, double value) const;
  // Stores n such values from (x, y, z) on along x (one type dispatch per row, not per voxel).
  void set_row(std::size_t x, std::size_t y, std::size_t z, const double* values, std::size_t n) const;
};

// Contiguous output (x fastest) of `storage` elements.
VolumeOutput contiguous_output(void* data, const Extent& dims, VoxelType storage);

}  // namespace pupwave
