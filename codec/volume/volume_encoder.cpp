// encode_volumes: validation, planning (masks of sparse grids, the bricks to code), lossless
// coding for integer bounds only exact values meet, and the stream's head and assembly. The brick
// pass of the fixed-step, lossless and max-error modes is volume_encoder_bricks.cpp (the step per
// brick for a bound: volume_encoder_bound.cpp), the rate modes' volume_encoder_rate.cpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "codec/entropy/block_encoder.h"
#include "codec/error.h"
#include "codec/rate/byte_budget.h"
#include "codec/rate/quantizer.h"
#include "codec/volume/volume_encoder_plan.h"
#include "codec/volume/volume_outliers.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

// Quantizer of max-error mode: index floor(|c| / step + 0.375), reconstructed at the middle of
// its bin (delta = 0.5 - 0.375). Against the dead zone (rounding 0, delta 0.5) the zero bin
// shrinks from 2 steps to 1.25, so no coefficient's error exceeds 0.625 step instead of 1 (an
// L-infinity bound pays for the worst errors, through coarser steps or outliers): files 0.2-3.4%
// smaller on wmag91 and turbulence at 1e-2..1e-4 (rounding 0.35-0.45 within 0.07% of 0.375, 0.5
// up to 0.2% larger, 0.3 up to 0.5%). Encoder only: the stream carries delta, as before.
constexpr float kMaxErrorRounding = 0.375f;
constexpr double kMaxErrorDelta = 0.5 - double(kMaxErrorRounding);
// Finest bound or step, relative to the largest sample magnitude: coefficients are coded as
// float magnitudes (24 significant bits), and below this a transform's gain would push
// indices past float precision and the block coder's range. Refused up front, never mid-way.
constexpr double kFinestRelativeStep = 1.0 / 1048576.0;

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// A step or error bound finer than the coder resolves for samples up to `largest` in magnitude.
void check_precision(const VolumeEncodeOptions& o, double largest) {
  if (o.mode != VolumeRateMode::max_error && o.mode != VolumeRateMode::step) return;
  const double finest = kFinestRelativeStep * std::max(largest, 1e-300);
  if (o.target >= finest) return;
  const char* what = o.mode == VolumeRateMode::max_error ? "error bound" : "step";
  throw std::invalid_argument(std::string(what) + " " + number_text(o.target) +
                              " is finer than the volume coder resolves: the finest " + what +
                              " for samples up to " + number_text(largest) + " is " + number_text(finest) +
                              " (2^-20 of the largest magnitude)");
}

int log2_exact(std::size_t v, std::size_t lo, std::size_t hi, const char* what) {
  if (v < lo || v > hi || (v & (v - 1)) != 0)
    throw std::invalid_argument(std::string(what) + " must be a power of two in [" + std::to_string(lo) +
                                ", " + std::to_string(hi) + "]");
  int k = 0;
  while ((std::size_t(1) << k) < v) ++k;
  return k;
}

// Values of each part of each grid (grid_parts), read once for validation and planning.
using Summaries = std::vector<std::vector<ValueSummary>>;

// Checks one box (a box grid or a block) with the summary of its values; `total` is the running
// voxel count of all grids; `dense`: a dense box grid, whose NaN and infinities are missing
// values. Returns its largest |sample| (for the precision check).
double validate_volume(const VolumeView& v, const ValueSummary& values, std::size_t total, bool dense) {
  for (std::size_t d : v.dims)
    if (d < 1 || d > kMaxVolumeAxis) throw EncodeError("volume dims must be in [1, 2^20] per axis");
  if (total > kMaxVolumeVoxels) throw EncodeError("volumes exceed 2^31 voxels");
  if (!std::isfinite(v.background)) throw EncodeError("non-finite background");
  if (!values.finite && !dense)
    throw EncodeError("sparse volume has non-finite samples (NaN or infinity); only dense volumes keep them");
  return values.largest;
}

// A box grid without an active mask: the grids whose NaN, infinities and fill value are missing values.
bool is_dense_box(const VolumeGrid& g, const std::vector<VolumeView>& parts) {
  return !g.is_opaque() && !g.is_blocked() && !parts.empty() && !parts[0].is_sparse();
}

// Coordinates of blocks and tiles must stay in OpenVDB's 32-bit index range.
bool in_coord_range(std::int64_t o, std::int64_t extent) {
  return o >= -(std::int64_t(1) << 31) && o + extent <= (std::int64_t(1) << 31);
}

// Checks a sparse-native grid; returns its largest |sample| or |tile value|.
double validate_blocked(const VolumeGrid& g, const std::vector<VolumeView>& parts,
                        const std::vector<ValueSummary>& values, std::size_t& total) {
  double largest = 0.0;
  if (g.active_voxels() == 0)
    throw EncodeError("grid '" + g.name + "' has no active voxels; nothing to encode");
  for (std::size_t d : g.volume.dims)
    if (d < 1 || d > kMaxVolumeAxis)
      throw EncodeError("grid '" + g.name + "' bounding box must be in [1, 2^20] per axis");
  for (std::size_t k = 0; k < g.blocks.size(); ++k) {
    const VolumeBlock& b = g.blocks[k];
    total += b.volume.count();
    largest = std::max(largest, validate_volume(parts[k], values[k], total, false));
    if (b.volume.type != g.volume.type || b.volume.background != g.volume.background)
      throw std::invalid_argument("grid '" + g.name + "': block type or background differs from the grid's");
    for (std::size_t a = 0; a < 3; ++a)
      if (!in_coord_range(b.origin[a], std::int64_t(b.volume.dims[a])))
        throw EncodeError("grid '" + g.name + "': block outside the 32-bit index range");
  }
  for (const VolumeTile& t : g.tiles) {
    if (!std::isfinite(t.value)) throw EncodeError("grid '" + g.name + "' has a non-finite tile value");
    if (t.edge < 1 || t.edge > kMaxVolumeAxis)
      throw EncodeError("grid '" + g.name + "': tile edge out of range");
    for (std::size_t a = 0; a < 3; ++a)
      if (!in_coord_range(t.origin[a], t.edge))
        throw EncodeError("grid '" + g.name + "': tile outside the 32-bit index range");
    largest = std::max(largest, std::fabs(t.value));
  }
  return largest;
}

void validate(const std::vector<VolumeGrid>& grids, const std::vector<std::vector<VolumeView>>& parts,
              const Summaries& values, const VolumeEncodeOptions& o) {
  if (grids.empty()) throw EncodeError("no grids to encode");
  if (grids.size() > kMaxVolumeGrids) throw EncodeError("more than 1024 grids");
  if (o.mode != VolumeRateMode::lossless && !(o.target > 0.0 && std::isfinite(o.target)))
    throw std::invalid_argument("rate target must be positive and finite");
  if (o.fill_value && !std::isfinite(*o.fill_value))
    throw std::invalid_argument(
        "fill value must be finite (NaN and infinities are always kept as missing values)");
  std::size_t total = 0;
  double largest = 0.0;
  for (std::size_t i = 0; i < grids.size(); ++i) {
    const VolumeGrid& g = grids[i];
    if (g.is_opaque()) continue;     // carried verbatim
    for (std::int64_t c : g.origin)  // the decoder refuses origins outside OpenVDB's int32 range
      if (!in_coord_range(c, 0) || c == (std::int64_t(1) << 31))
        throw EncodeError("grid '" + g.name + "': origin outside the 32-bit index range");
    if (g.is_blocked()) {
      largest = std::max(largest, validate_blocked(g, parts[i], values[i], total));
    } else {
      if (parts[i][0].count() == 0)
        throw EncodeError("grid '" + g.name + "' has no active voxels; nothing to encode");
      total += parts[i][0].count();
      largest =
          std::max(largest, validate_volume(parts[i][0], values[i][0], total, is_dense_box(g, parts[i])));
    }
    if (o.mode == VolumeRateMode::lossless && !is_integer(g.volume.type))
      throw std::invalid_argument(
          "lossless coding needs integer volumes (u8, u16); use --max-error for float");
  }
  check_precision(o, largest);
}

// Bitwise equality: -0.0 is not 0.0, and each NaN keeps its own bits, so inactive values come back exact.
bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Voxel states and inactive values of a sparse grid (appended to m).
void append_mask(const VolumeView& v, MaskChunk& m) {
  std::size_t i = m.states.size();
  m.states.resize(i + v.count());  // grows geometrically over the blocks of a grid
  for_each_voxel(v, [&](double value, bool active) {
    VoxelState s = VoxelState::active;
    if (!active) {
      if (same_bits(value, v.background))
        s = VoxelState::inactive_background;
      else if (same_bits(value, -v.background))
        s = VoxelState::inactive_negative;
      else {
        s = VoxelState::inactive_other;
        m.other_values.push_back(value);
      }
    }
    m.states[i++] = std::uint8_t(s);
  });
}

MaskChunk make_mask(const VolumeView& v) {
  MaskChunk m;
  append_mask(v, m);
  return m;
}

// Geometry (no samples), tiles and voxel states of a sparse-native grid.
BlocksChunk make_layout(const VolumeGrid& g, const std::vector<VolumeView>& parts) {
  BlocksChunk c;
  c.tiles = g.tiles;
  for (std::size_t k = 0; k < g.blocks.size(); ++k) {
    VolumeBlock geometry;
    geometry.origin = g.blocks[k].origin;
    geometry.volume.dims = g.blocks[k].volume.dims;
    c.blocks.push_back(std::move(geometry));
    append_mask(parts[k], c.mask);
  }
  return c;
}

bool brick_has_active(const VolumeView& v, const BrickBox& box) {
  if (!v.is_sparse()) return true;
  for (std::size_t z = 0; z < box.size[2]; ++z)
    for (std::size_t y = 0; y < box.size[1]; ++y)
      for (std::size_t x = 0; x < box.size[0]; ++x)
        if (v.is_active(box.offset[0] + x, box.offset[1] + y, box.offset[2] + z)) return true;
  return false;
}

// Value range of the active voxels (active tiles included).
double value_range(const VolumeGrid& g, const std::vector<ValueSummary>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const ValueSummary& v : values) lo = std::min(lo, v.lo), hi = std::max(hi, v.hi);
  for (const VolumeTile& t : g.tiles)
    if (t.active) lo = std::min(lo, t.value), hi = std::max(hi, t.value);
  return hi > lo ? hi - lo : 0.0;
}

// Grid description for the header: everything but the values (a box grid's sparse marker from
// the view its values come from).
VolumeGrid describe(const VolumeGrid& g, const std::vector<VolumeView>& parts) {
  VolumeGrid d;
  d.name = g.name;
  d.grid_class = g.grid_class;
  d.origin = g.origin;
  d.index_to_world = g.index_to_world;
  d.metadata = g.metadata;
  d.volume.dims = g.volume.dims;
  d.volume.type = g.volume.type;
  d.volume.background = g.volume.background;
  d.volume.active.assign(!g.is_blocked() && !parts.empty() && parts[0].is_sparse() ? 1 : 0, 1);
  if (g.is_opaque()) d.volume = Volume({1, 1, 1}, VoxelType::f32), d.volume.samples.clear();
  return d;
}

// Bricks holding an active voxel, of the grid's box or of each of its blocks in turn.
void add_jobs(VolumePlan& plan, const std::vector<VolumeView>& parts, std::uint32_t grid, std::size_t edge) {
  std::uint32_t index = 0;
  const bool missing = plan.header.has_missing(grid);
  for (std::uint32_t k = 0; k < parts.size(); ++k) {
    for (const BrickBox& box : brick_boxes(parts[k].dims, edge)) {
      if (brick_has_active(parts[k], box)) plan.jobs.push_back({grid, index, box, k, parts[k], missing});
      ++index;
    }
  }
}

// Checks a caller's view of box grid `g` against the grid's description.
void check_grid_view(const VolumeGrid& g, const VolumeView& v) {
  check_view(v);
  if (g.is_opaque() || g.is_blocked() || !g.volume.samples.empty() || !g.volume.active.empty())
    throw std::invalid_argument("grid '" + g.name + "' is given both by a view and by its own values");
  if (g.volume.dims != v.dims || g.volume.type != v.type || g.volume.background != v.background)
    throw std::invalid_argument("grid '" + g.name + "': dims, type or background differ from its view's");
}

// Where each grid's values are read from: its box (the caller's view, or a view of its own
// Volume) or each of its blocks in turn; nothing for opaque grids.
std::vector<std::vector<VolumeView>> grid_parts(const std::vector<VolumeGrid>& grids,
                                                std::span<const VolumeView> views) {
  if (!views.empty() && views.size() != grids.size())
    throw std::invalid_argument("one view per grid is needed (null data: the grid's own values)");
  std::vector<std::vector<VolumeView>> parts(grids.size());
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const VolumeGrid& grid = grids[g];
    if (!views.empty() && views[g].data != nullptr) {
      check_grid_view(grid, views[g]);
      parts[g].push_back(views[g]);
    } else if (grid.is_blocked()) {
      for (const VolumeBlock& b : grid.blocks) parts[g].push_back(view_of(b.volume));
    } else if (!grid.is_opaque()) {
      parts[g].push_back(view_of(grid.volume));
    }
  }
  return parts;
}

}  // namespace

VolumePlan plan_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                        const VolumeEncodeOptions& o) {
  std::vector<std::vector<VolumeView>> parts = grid_parts(grids, views);
  Summaries values(parts.size());
  for (std::size_t g = 0; g < parts.size(); ++g) {
    const std::optional<double> fill = is_dense_box(grids[g], parts[g]) ? o.fill_value : std::nullopt;
    for (const VolumeView& v : parts[g]) values[g].push_back(summarize_values(v, fill));
  }
  validate(grids, parts, values, o);
  VolumePlan plan;
  plan.transform = make_transform(o.transform);
  check_stream_spec(plan.transform->spec());  // never write a stream the decoder's bounds refuse
  const bool reversible = o.mode == VolumeRateMode::lossless;
  if (reversible && !plan.transform->is_reversible())
    throw std::invalid_argument("lossless coding needs a reversible transform (cdf53), not " +
                                plan.transform->spec());
  VolumeStreamHeader& h = plan.header;
  h.spec = plan.transform->spec();
  h.reversible = reversible;
  h.brick_log2 = log2_exact(o.brick, 8, 256, "brick edge");
  h.block_log2 = log2_exact(o.block, 16, 64, "code-block edge");
  const int default_l = default_levels({o.brick, o.brick, o.brick});
  if (o.levels < -1 || o.levels > h.brick_log2)
    throw std::invalid_argument("levels must be in [0, log2(brick edge)]");
  h.levels = o.levels < 0 ? default_l : o.levels;
  h.delta = reversible                            ? 0.0
            : o.mode == VolumeRateMode::max_error ? kMaxErrorDelta
                                                  : kDefaultReconstructionDelta;
  h.max_error = o.mode == VolumeRateMode::max_error ? o.target : 0.0;
  // Max-error bricks are never truncated: the coefficient coder codes every index in one pass.
  h.coder = o.mode == VolumeRateMode::max_error ? 1 : 0;
  plan.coding = BrickCoding{plan.transform.get(), h.levels, o.block, h.delta, reversible, h.coder == 1};
  if (o.mode == VolumeRateMode::max_error && !reversible) plan.coding.rounding = kMaxErrorRounding;
  plan.executor = o.executor != nullptr ? o.executor : &default_executor();
  plan.masks.resize(grids.size());
  plan.layouts.resize(grids.size());
  plan.opaque.resize(grids.size());
  plan.valid.resize(grids.size());
  for (std::uint32_t g = 0; g < grids.size(); ++g) {
    const VolumeGrid& grid = grids[g];
    // A dense grid with missing values is coded as a sparse box whose inactive voxels are they.
    const bool missing = is_dense_box(grid, parts[g]) && values[g][0].missing > 0;
    if (missing) parts[g][0].active = missing_value_mask(parts[g][0], o.fill_value, plan.valid[g]);
    h.missing.push_back(missing ? 1 : 0);
    h.grids.push_back(describe(grid, parts[g]));
    h.blocked.push_back(grid.is_opaque() ? 2 : grid.is_blocked() ? 1 : 0);
    if (grid.is_opaque())
      plan.opaque[g] = grid.opaque;
    else if (grid.is_blocked())
      plan.layouts[g] = make_layout(grid, parts[g]);
    else if (parts[g][0].is_sparse())
      plan.masks[g] = make_mask(parts[g][0]);
    add_jobs(plan, parts[g], g, o.brick);
    if (grid.is_blocked())
      plan.voxels += grid.active_voxels();
    else if (!grid.is_opaque())
      plan.voxels += active_count(parts[g][0]);
    plan.range = std::max(plan.range, value_range(grid, values[g]));
  }
  h.brick_chunks = std::uint32_t(plan.jobs.size());
  return plan;
}

std::vector<double> reconstruct_brick(const VolumePlan& plan, const BrickJob& job, const BrickCode& code) {
  std::vector<BlockEntry> entries(code.passes.size());
  std::vector<std::vector<std::uint8_t>> words(code.passes.size());
  std::vector<std::span<const std::uint8_t>> spans;
  for (std::size_t i = 0; i < code.passes.size(); ++i) {
    const EncodedBlock& b = code.coded.coded[i];
    entries[i] = {code.passes[i] > 0 ? b.planes : 0, code.passes[i], std::uint32_t(b.size(code.passes[i]))};
    words[i] = b.codeword(code.passes[i]);
    spans.emplace_back(words[i]);
  }
  return decode_brick(plan.coding, job.box.size, code.base_step, entries, spans, 0);
}

void measure_brick(const VolumeGrid& grid, const BrickJob& job, std::vector<double> reconstruction,
                   BrickCode& code) {
  std::vector<double> samples;
  std::vector<std::uint8_t> active;
  brick_samples(job, samples, active);
  code.max_error = 0.0;
  code.sse = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!active.empty() && active[i] == 0) continue;
    const double e = std::abs(samples[i] - to_stored(reconstruction[i], grid.volume.type));
    code.max_error = std::max(code.max_error, e);
    code.sse += e * e;
  }
}

namespace {

// Signature, header and the per-grid chunks before the bricks.
std::vector<std::uint8_t> stream_head(const VolumePlan& plan) {
  std::vector<std::uint8_t> out;
  write_volume_signature(out);
  write_header_chunk(out, plan.header);
  for (std::uint32_t g = 0; g < plan.masks.size(); ++g) {
    if (plan.header.blocked[g] == 1) write_blocks_chunk(out, g, plan.layouts[g]);
    if (plan.header.blocked[g] == 2) write_opaque_chunk(out, g, plan.opaque[g]);
    if (plan.header.grids[g].volume.is_sparse()) write_mask_chunk(out, g, plan.masks[g]);
  }
  return out;
}

// Coded bytes of a brick (passes kept + outlier list), for sizing the assembled stream.
std::size_t code_bytes(const BrickCode& c) {
  std::size_t n = c.outliers.size();
  for (std::size_t i = 0; i < c.passes.size(); ++i) n += c.coded.coded[i].size(c.passes[i]);
  return n;
}

// Whether a max-error bound can only be met exactly: every coded grid holds integers (u8, u16),
// whose errors are integers too, and the bound is below 1. Lossless coding then meets it with a
// smaller stream than transform coding plus a correction for nearly every voxel.
bool only_exact(const std::vector<VolumeGrid>& grids, const VolumeEncodeOptions& o) {
  if (o.mode != VolumeRateMode::max_error || !(o.target > 0.0 && o.target < 1.0)) return false;
  bool any = false;
  for (const VolumeGrid& g : grids) {
    if (g.is_opaque()) continue;  // carried verbatim
    if (!is_integer(g.volume.type)) return false;
    any = true;
  }
  return any;
}

// Options for lossless coding in place of a bound only exact values meet: the given transform
// when it is reversible, cdf53 otherwise.
void code_lossless(VolumeEncodeOptions& o) {
  o.mode = VolumeRateMode::lossless;
  if (!make_transform(o.transform)->is_reversible()) o.transform = "cdf53";
}

// Hands the final stream to `write` piece by piece (the head, then one chunk per brick),
// releasing each brick's coded form once its chunk is written: the coded bricks are the only
// whole-stream-sized thing an encode holds, and a caller writing to a file holds nothing more.
void assemble_streaming(const VolumePlan& plan, std::vector<BrickCode>& codes, const StreamWriter& write) {
  write(stream_head(plan));
  std::vector<std::uint8_t> chunk;
  for (std::size_t i = 0; i < codes.size(); ++i) {
    chunk.clear();
    write_brick(chunk, plan.jobs[i], codes[i]);
    codes[i] = BrickCode{};
    write(chunk);
  }
}

}  // namespace

std::vector<std::uint8_t> assemble_volumes(const VolumePlan& plan, const std::vector<BrickCode>& codes) {
  std::vector<std::uint8_t> out = stream_head(plan);
  for (std::size_t i = 0; i < codes.size(); ++i) write_brick(out, plan.jobs[i], codes[i]);
  return out;
}

VolumeGrid describe_view(const VolumeView& view, std::string name) {
  VolumeGrid g;
  g.name = std::move(name);
  g.volume.dims = view.dims;
  g.volume.type = view.type;
  g.volume.background = view.background;
  return g;
}

VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, const VolumeEncodeOptions& options) {
  return encode_volumes(grids, {}, options);
}

VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                                  const VolumeEncodeOptions& options) {
  return encode_volumes(grids, views, options, nullptr);
}

namespace {

// VolumeEncodeResult::target_met for the caller's options: a bpv budget as for_size rounds it.
bool meets_target(const VolumeEncodeResult& r, const VolumeEncodeOptions& options, std::size_t voxels) {
  switch (options.mode) {
    case VolumeRateMode::bpv:
      return double(r.size) <= byte_budget(options.target, std::max<std::size_t>(voxels, 1));
    case VolumeRateMode::psnr: return r.psnr >= options.target;
    case VolumeRateMode::max_error: return r.max_error <= options.target;
    case VolumeRateMode::step:
    case VolumeRateMode::lossless: break;
  }
  return true;
}

VolumeEncodeResult encode_volumes_unchecked(const std::vector<VolumeGrid>& grids,
                                            std::span<const VolumeView> views,
                                            const VolumeEncodeOptions& given, const StreamWriter& write) {
  VolumeEncodeOptions options = given;
  const bool exact = only_exact(grids, options);
  if (exact) code_lossless(options);
  VolumePlan plan = plan_volumes(grids, views, options);
  VolumeEncodeResult r;
  r.switched_to_lossless = exact;
  const StreamWriter out = [&](std::span<const std::uint8_t> piece) {
    r.size += piece.size();
    if (write)
      write(piece);
    else
      r.bytes.insert(r.bytes.end(), piece.begin(), piece.end());
  };
  // Bricks are the parallel tasks; each brick's own transform runs serially inside its task.
  std::vector<BrickFigures> figures;
  if (options.mode == VolumeRateMode::bpv || options.mode == VolumeRateMode::psnr) {
    std::vector<BrickCode> codes = code_for_rate(grids, plan, options);  // PCRD needs every brick
    for (const BrickCode& c : codes) figures.push_back({c.max_error, c.sse, c.outlier_count});
    if (!write) {
      std::size_t estimate = 0;  // reserved once: no doubling copies of the stream
      for (const BrickCode& c : codes)
        estimate += code_bytes(c) + 2 * c.passes.size() + 64;  // + index, framing
      r.bytes.reserve(estimate);
    }
    assemble_streaming(plan, codes, out);
  } else {
    out(stream_head(plan));
    figures = code_and_write(grids, plan, options, out);
  }
  double sse = 0.0;
  for (const BrickFigures& f : figures) {
    r.max_error = std::max(r.max_error, f.max_error);
    r.outliers += f.outliers;
    sse += f.sse;
  }
  r.bpv = double(r.size) * 8.0 / double(std::max<std::size_t>(plan.voxels, 1));
  const double mse = plan.voxels > 0 ? sse / double(plan.voxels) : 0.0;
  r.psnr =
      mse > 0.0 ? 10.0 * std::log10(plan.range * plan.range / mse) : std::numeric_limits<double>::infinity();
  r.target_met = meets_target(r, given, plan.voxels);
  return r;
}

}  // namespace

VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                                  const VolumeEncodeOptions& options, const StreamWriter& write) {
  try {
    return encode_volumes_unchecked(grids, views, options, write);
  } catch (const IndexRangeError&) {
    // Unstable banks (pups:cinpact-c3) amplify the coarse band level after level; a streamed
    // encode cannot retry with fewer levels, so the message says what to change.
    throw IndexRangeError("transform '" + options.transform +
                          "': quantization indices beyond the coder's range at this target; the bank "
                          "amplifies its coarse band at every level: use fewer --levels, a looser target or "
                          "another --transform");
  }
}

}  // namespace pupwave
