// `pupwave lod IN.vdb OUT.vdb --levels N`: a level-of-detail pyramid of every float/double grid,
// written in the conventions of OpenVDB's vdb_lod (tools::MultiResGrid), so tools that read its
// output read ours:
//   - level k of grid NAME is named NAME_level_K (level 0 is the input), with the metadata
//     MultiResGrid_Level (float k) and MultiResGrid_Levels (int64, highest level + 1) added;
//   - its transform is the input's pre-scaled by 2^k: coarse voxel i lies where fine voxel 2^k i
//     lies, so world placement is kept (the coarse samples of the symmetric odd-length CDF low
//     passes are centred on the even fine samples, which is exactly this lattice);
//   - coarse voxel c is active when a fine voxel of [2c-1, 2c+1]^3 is (vdb_lod's one-voxel
//     dilation followed by injection of the even voxels); background and grid class are kept.
// The values differ from vdb_lod on purpose: level k is the coarse band of k levels of the chosen
// wavelet transform (vdb_lod uses the (1/4, 1/2, 1/4) full-weighting filter), normalised by the
// transform's coarse-band response to a constant so constant fields stay constant, and clamped
// to the input's value range. Level sets keep a meaningful narrow band: inactive voxels take
// +-background by the sign of the low band (what signed flood filling would give).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/atomic_file.h"
#include "tools/cli_numbers.h"
#include "tools/commands.h"
#include "tools/volume_io.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave::cli {
namespace {

// Highest level accepted: the dense box is padded by 2^level voxels on each side.
constexpr int kMaxLodLevel = 12;

int parse_level(std::string_view text, std::string_view option) {
  int value = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 0 ||
      value > kMaxLodLevel)
    throw std::invalid_argument(
        "invalid " + std::string(option) + " '" + std::string(text) + "' (integer levels 0.." +
        std::to_string(kMaxLodLevel) +
        "; a wavelet low band halves the resolution, so fractional levels do not exist)");
  return value;
}

// vdb_lod's -range syntax: FROM[-TO[:STEP]] with integer levels.
std::vector<int> parse_range(std::string_view text) {
  const std::size_t dash = text.find('-'), colon = text.find(':');
  if (colon != std::string_view::npos && (dash == std::string_view::npos || colon < dash))
    throw std::invalid_argument("invalid --range '" + std::string(text) + "' (expected FROM[-TO[:STEP]])");
  const int from = parse_level(text.substr(0, dash), "--range");
  int to = from, step = 1;
  if (dash != std::string_view::npos) {
    to = parse_level(text.substr(dash + 1, colon == std::string_view::npos ? colon : colon - dash - 1),
                     "--range");
    if (colon != std::string_view::npos) step = parse_level(text.substr(colon + 1), "--range step");
  }
  if (to < from || step < 1)
    throw std::invalid_argument("invalid --range '" + std::string(text) +
                                "' (need FROM <= TO and STEP >= 1)");
  std::vector<int> levels;
  for (int k = from; k <= to; k += step) levels.push_back(k);
  return levels;
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The dense working array of one grid: values and active mask over a box whose low corner and
// size are multiples of 2^K, so every level halves exactly and coarse voxel j of level k sits at
// index origin/2^k + j.
struct Pyramid {
  std::array<std::int64_t, 3> origin{};
  Extent dims{};
  std::vector<double> values;
  std::vector<std::uint8_t> mask;
  std::array<std::vector<double>, 3> gain;  // 1-D coarse-band response to a constant, per axis
};

// What the padding around a grid's box holds (--edge).
enum class LodEdge { automatic, symmetric, background };

// Whole-sample symmetric reflection of offset d (any integer) into [0, n): the extension the
// CDF banks use at the ends of a line.
std::int64_t reflect(std::int64_t d, std::int64_t n) {
  if (n == 1) return 0;
  const std::int64_t period = 2 * (n - 1);
  d %= period;
  if (d < 0) d += period;
  return d < n ? d : period - d;
}

// Fills the padding of p (everything outside the box of `n` voxels at `shift`) by symmetric
// extension of the box, axis by axis, so the corners are filled too.
void extend_symmetrically(Pyramid& p, const std::array<std::int64_t, 3>& shift, const Extent& n) {
  const Extent& d = p.dims;
  auto at = [&](std::size_t x, std::size_t y, std::size_t z) -> double& {
    return p.values[x + d[0] * (y + d[1] * z)];
  };
  auto inside = [&](std::size_t axis, std::size_t i) {
    return std::int64_t(i) >= shift[axis] && std::int64_t(i) < shift[axis] + std::int64_t(n[axis]);
  };
  auto source = [&](std::size_t axis, std::size_t i) {
    return std::size_t(shift[axis] + reflect(std::int64_t(i) - shift[axis], std::int64_t(n[axis])));
  };
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x) {
        if (!inside(1, y) || !inside(2, z) || inside(0, x)) continue;
        at(x, y, z) = at(source(0, x), y, z);
      }
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      if (inside(2, z) && !inside(1, y))
        for (std::size_t x = 0; x < d[0]; ++x) at(x, y, z) = at(x, source(1, y), z);
  for (std::size_t z = 0; z < d[2]; ++z)
    if (!inside(2, z))
      for (std::size_t y = 0; y < d[1]; ++y)
        for (std::size_t x = 0; x < d[0]; ++x) at(x, y, z) = at(x, y, source(2, z));
}

// Pads the grid's box to multiples of B = 2^K plus one block of B on each side (enough room for
// the dilated active topology of every level) with inactive voxels: background where the grid's
// outside really is background, or the box extended symmetrically where the data ends at the
// box (a dense grid: every voxel of its box active), so its border does not darken.
Pyramid pad_to_blocks(const VolumeGrid& g, int top_level, LodEdge edge) {
  const std::int64_t block = std::int64_t(1) << top_level;
  const Volume& v = g.volume;
  Pyramid p;
  std::array<std::int64_t, 3> shift{};
  for (std::size_t a = 0; a < 3; ++a) {
    const std::int64_t lo = g.origin[a], end = lo + std::int64_t(v.dims[a]);
    p.origin[a] = (floor_div(lo, block) - 1) * block;
    p.dims[a] = std::size_t((floor_div(end + block - 1, block) + 1) * block - p.origin[a]);
    shift[a] = lo - p.origin[a];
  }
  const std::size_t count = p.dims[0] * p.dims[1] * p.dims[2];
  if (count / p.dims[0] / p.dims[1] != p.dims[2] || count > kMaxVdbBoxVoxels)
    throw std::runtime_error("grid '" + g.name + "' padded to level " + std::to_string(top_level) +
                             " blocks exceeds the dense limit of " + std::to_string(kMaxVdbBoxVoxels) +
                             " voxels");
  p.values.assign(count, v.background);
  p.mask.assign(count, 0);
  for (std::size_t z = 0; z < v.dims[2]; ++z)
    for (std::size_t y = 0; y < v.dims[1]; ++y)
      for (std::size_t x = 0; x < v.dims[0]; ++x) {
        const std::size_t i = v.index(x, y, z);
        const std::size_t j = std::size_t(x + shift[0]) +
                              p.dims[0] * (std::size_t(y + shift[1]) + p.dims[1] * std::size_t(z + shift[2]));
        p.values[j] = v.samples[i];
        p.mask[j] = v.is_active(i) ? 1 : 0;
      }
  if (edge == LodEdge::automatic)
    edge = v.active_count() == v.count() ? LodEdge::symmetric : LodEdge::background;
  if (edge == LodEdge::symmetric) extend_symmetrically(p, shift, v.dims);
  for (std::size_t a = 0; a < 3; ++a) p.gain[a].assign(p.dims[a], 1.0);
  return p;
}

// One level down: the transform's coarse band of values and gains, the dilated-halved mask.
void halve(Pyramid& p, const Transform1D& t) {
  forward(t, p.values.data(), p.dims, 1);
  const Extent half{p.dims[0] / 2, p.dims[1] / 2, p.dims[2] / 2};
  std::vector<double> values(half[0] * half[1] * half[2]);
  std::vector<std::uint8_t> mask(values.size(), 0);
  for (std::size_t z = 0; z < half[2]; ++z)
    for (std::size_t y = 0; y < half[1]; ++y)
      for (std::size_t x = 0; x < half[0]; ++x)
        values[x + half[0] * (y + half[1] * z)] = p.values[x + p.dims[0] * (y + p.dims[1] * z)];
  // Separable OR over the fine window [2c-1, 2c+1] along x, then y, then z.
  std::vector<std::uint8_t> cur = p.mask;
  Extent ext = p.dims;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    Extent next = ext;
    next[axis] = half[axis];
    std::vector<std::uint8_t> out(next[0] * next[1] * next[2], 0);
    const std::size_t in_stride = axis == 0 ? 1 : axis == 1 ? ext[0] : ext[0] * ext[1];
    const std::size_t out_stride = axis == 0 ? 1 : axis == 1 ? next[0] : next[0] * next[1];
    for (std::size_t i = 0; i < out.size(); ++i) {
      const std::size_t c = i / out_stride % next[axis];
      const std::size_t base = i - c * out_stride;  // same position with coordinate 0 on `axis`
      const std::size_t in_base =
          (base / out_stride / next[axis]) * in_stride * ext[axis] + base % out_stride;
      for (std::size_t f = (c == 0 ? 0 : 2 * c - 1); f <= std::min(2 * c + 1, ext[axis] - 1); ++f)
        out[i] = static_cast<std::uint8_t>(out[i] | cur[in_base + f * in_stride]);
    }
    cur.swap(out);
    ext = next;
  }
  for (std::size_t a = 0; a < 3; ++a) {
    t.analyze(std::span<double>(p.gain[a]));
    p.gain[a].resize(half[a]);
  }
  for (std::size_t a = 0; a < 3; ++a) p.origin[a] /= 2;
  p.dims = half;
  p.values.swap(values);
  p.mask.swap(cur);
}

// Level-k grid from the pyramid's current state.
VolumeGrid level_grid(const VolumeGrid& in, const Pyramid& p, int level, int top_level, double lo,
                      double hi) {
  VolumeGrid g;
  g.name = in.name + "_level_" + std::to_string(level);
  g.grid_class = in.grid_class;
  g.metadata = in.metadata;
  g.metadata["MultiResGrid_Level"] = MetaValue{MetaValue::Kind::float32, {}, 0, {double(level), 0, 0}};
  g.metadata["MultiResGrid_Levels"] = MetaValue{MetaValue::Kind::int64, {}, top_level + 1, {}};
  g.index_to_world = in.index_to_world;
  for (std::size_t i = 0; i < 12; ++i) g.index_to_world[i] *= std::ldexp(1.0, level);  // pre-scale
  if (level == 0 || in.volume.count() == 0) {
    g.origin = in.origin;
    g.volume = in.volume;
    return g;
  }
  g.origin = p.origin;
  g.volume = Volume(p.dims, in.volume.type);
  g.volume.background = in.volume.background;
  g.volume.active = p.mask;
  const double bg = in.volume.background;
  for (std::size_t z = 0, i = 0; z < p.dims[2]; ++z)
    for (std::size_t y = 0; y < p.dims[1]; ++y)
      for (std::size_t x = 0; x < p.dims[0]; ++x, ++i) {
        const double value = std::clamp(p.values[i] / (p.gain[0][x] * p.gain[1][y] * p.gain[2][z]), lo, hi);
        if (p.mask[i])
          g.volume.samples[i] = value;
        else if (in.grid_class == GridClass::level_set)
          g.volume.samples[i] = value < 0 ? -std::abs(bg) : std::abs(bg);
        else
          g.volume.samples[i] = bg;
      }
  return g;
}

// All requested levels of one grid, in ascending order.
std::vector<VolumeGrid> level_of_detail(const VolumeGrid& in, const Transform1D& t,
                                        const std::vector<int>& levels, LodEdge edge) {
  const int top = levels.back();
  std::vector<VolumeGrid> out;
  if (in.volume.count() == 0) {  // no active voxels: every level is empty as well
    for (int k : levels) out.push_back(level_grid(in, Pyramid{}, k, top, 0, 0));
    return out;
  }
  const auto [lo_it, hi_it] = std::minmax_element(in.volume.samples.begin(), in.volume.samples.end());
  const double lo = std::min(*lo_it, in.volume.background), hi = std::max(*hi_it, in.volume.background);
  Pyramid p = pad_to_blocks(in, top, edge);
  for (int k = 0; k <= top; ++k) {
    if (k > 0) halve(p, t);
    if (std::find(levels.begin(), levels.end(), k) == levels.end()) continue;
    for (std::size_t a = 0; a < 3; ++a)
      for (double gain : p.gain[a])
        if (!(std::abs(gain) > 1e-3))
          throw std::runtime_error("transform " + t.spec() +
                                   " has no usable coarse-band response to a constant");
    out.push_back(level_grid(in, p, k, top, lo, hi));
  }
  return out;
}

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    if (comma > start) names.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return names;
}

}  // namespace

void add_lod_command(CLI::App& app) {
  struct Options {
    std::string input, output, transform = "cdf97", range, names, edge = "auto";
    int levels = -1;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "lod",
      "Write a level-of-detail pyramid of the float/double grids of an OpenVDB file:\n"
      "level k is the wavelet low band at 2^k times the voxel size, named NAME_level_K\n"
      "as OpenVDB's vdb_lod names them (level 0 is the input). Grids of other value types\n"
      "(vec3, integer, bool, mask) are copied to OUT unchanged.");
  cmd->add_option("IN", opt->input, "input .vdb")->required();
  cmd->add_option("OUT", opt->output, "output .vdb (written atomically)")->required();
  cmd->add_option("--levels", opt->levels, "write levels 0..N (same as --range 0-N)")
      ->check(non_negative_number());
  cmd->add_option("--range", opt->range, "levels FROM[-TO[:STEP]] as vdb_lod's -range (integers)");
  cmd->add_option("--transform", opt->transform, "wavelet whose low band makes each level (default cdf97)");
  cmd->add_option("--edge", opt->edge,
                  "what lies beyond a grid's box: auto (default: symmetric for a dense grid, whose data "
                  "ends at its box; background for a sparse one, whose outside is background), symmetric, "
                  "background")
      ->transform(CLI::IsMember({"auto", "symmetric", "background"}, CLI::ignore_case));
  cmd->add_option("--name", opt->names,
                  "grid name(s) to process, comma separated (default: every float/double grid)");
  cmd->callback([opt] {
    if ((opt->levels >= 0) == !opt->range.empty())
      throw std::invalid_argument("give exactly one of --levels N and --range FROM[-TO[:STEP]]");
    const std::vector<int> levels =
        opt->range.empty() ? parse_range("0-" + std::to_string(opt->levels)) : parse_range(opt->range);
    const Transform1DPtr t = make_transform(opt->transform);
    check_output_path(opt->output);
    const auto start = std::chrono::steady_clock::now();
    std::vector<VolumeGrid> grids;
    const std::vector<std::string> names = split_names(opt->names);
    if (names.empty()) grids = read_vdb_dense(opt->input);
    for (const std::string& name : names)
      for (VolumeGrid& g : read_vdb_dense(opt->input, name)) grids.push_back(std::move(g));
    std::vector<VolumeGrid> out;
    for (const VolumeGrid& g : grids) {
      if (g.is_opaque()) {  // vector, integer, bool grids: kept as they are, never dropped
        out.push_back(g);
        continue;
      }
      const LodEdge edge = opt->edge == "symmetric"    ? LodEdge::symmetric
                           : opt->edge == "background" ? LodEdge::background
                                                       : LodEdge::automatic;
      for (VolumeGrid& level : level_of_detail(g, *t, levels, edge)) out.push_back(std::move(level));
    }
    write_vdb(out, opt->output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const VolumeGrid& g : out)
      if (g.is_opaque())
        std::cout << g.name << ": not a float or double grid, copied unchanged\n";
      else
        std::cout << g.name << ": " << g.volume.active_count() << " active voxels, voxel size "
                  << g.voxel_size()[0] << '\n';
    std::cout << opt->output << ": " << out.size() << " grid(s), " << t->spec() << ", " << seconds << " s\n";
  });
}

}  // namespace pupwave::cli
