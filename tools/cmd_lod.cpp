// `pupwave lod IN.vdb OUT.vdb --levels N`: a level-of-detail pyramid of every float, double and
// vec3 grid, written in the conventions of OpenVDB's vdb_lod (tools::MultiResGrid), so tools
// that read its output read ours:
//   - level k of grid NAME is named NAME_level_K (level 0 is the input), with the metadata
//     MultiResGrid_Level (float k) and MultiResGrid_Levels (int64, highest level + 1) added;
//   - its transform is the input's pre-scaled by 2^k: coarse voxel i lies where fine voxel 2^k i
//     lies, so world placement is kept (the coarse samples of the symmetric odd-length CDF low
//     passes are centred on the even fine samples, which is exactly this lattice);
//   - coarse voxel c is active when a fine voxel of [2c-1, 2c+1]^3 is (vdb_lod's one-voxel
//     dilation followed by injection of the even voxels); background and grid class are kept.
// The values differ from vdb_lod on purpose: level k is the low band of the chosen wavelet applied
// to level k-1 (vdb_lod uses the (1/4, 1/2, 1/4) full-weighting filter), normalised by its
// response to a constant so constant fields stay constant, and clamped to the input's value
// range (per component for vectors). Beyond a sparse grid's data lies its background (inactive
// values and tiles as stored); a dense grid (more than 90% of the voxels on the six faces of its
// active box active and not the background) is extended symmetrically at its box instead (--edge).
// Level sets keep a meaningful narrow band: inactive voxels take +-background by the sign of the
// low band. The work is sparse (tools/lod_pyramid.h): coarse leaf by coarse leaf, only where fine
// leaves or non-background tiles reach.
// Integer grids are rounded to the nearest integer (vdb_lod makes levels of them too); bool,
// mask and unknown grids are copied unchanged (vdb_lod skips them); file metadata is kept.
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
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/vdb_module.h"
#include "transforms/spec.h"

namespace pupwave::cli {
namespace {

// Highest level accepted (a 4096^3 grid is one voxel at level 12).
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
    Verbosity verbosity;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "lod",
      "Write a level-of-detail pyramid of the float, double and vec3 grids of an OpenVDB\n"
      "file (and integer ones): level k is the wavelet low band at 2^k times the voxel size\n"
      "(per component for vectors), named NAME_level_K as OpenVDB's vdb_lod names them (level 0 is the "
      "input).\n"
      "Integer grids are rounded; bool and mask grids are copied to OUT unchanged.");
  cmd->add_option("IN", opt->input, "input .vdb, or - for stdin")->required();
  cmd->add_option("OUT", opt->output, "output .vdb, or - for stdout")->required();
  cmd->add_option("--levels", opt->levels, "write levels 0..N (same as --range 0-N)")
      ->check(non_negative_number());
  cmd->add_option("--range", opt->range, "levels FROM[-TO[:STEP]] as vdb_lod's -range (integers)");
  cmd->add_option("--transform", opt->transform, "wavelet whose low band makes each level (default cdf97)");
  cmd->add_option("--edge", opt->edge,
                  "what lies beyond a grid's box: auto (default: symmetric for a dense grid, whose data "
                  "ends at its box: more than 90% of the voxels on the six faces of its active box are "
                  "active and not the background; background otherwise, the outside of a sparse grid), "
                  "symmetric, background")
      ->transform(CLI::IsMember({"auto", "symmetric", "background"}, CLI::ignore_case));
  cmd->add_option("--name", opt->names, "grid name(s) to process, comma separated (default: every grid)");
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    if ((opt->levels >= 0) == !opt->range.empty())
      throw std::invalid_argument("give exactly one of --levels N and --range FROM[-TO[:STEP]]");
    const std::vector<int> levels =
        opt->range.empty() ? parse_range("0-" + std::to_string(opt->levels)) : parse_range(opt->range);
    const Transform1DPtr t = make_transform(opt->transform);
    const LowPass low_pass = low_pass_of(*t);
    check_output_path(opt->output);
    opt->verbosity.to_stderr = is_stdio(opt->output);
    const InputPath input(opt->input);
    const auto start = std::chrono::steady_clock::now();
    const LodEdge edge = opt->edge == "symmetric"    ? LodEdge::symmetric
                         : opt->edge == "background" ? LodEdge::background
                                                     : LodEdge::automatic;
    const LodReport report =
        vdb_module().lod({input.path, opt->output, low_pass, levels, split_names(opt->names), edge});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostream& status = opt->verbosity.out();
    for (const std::string& line : report.lines) status << line << '\n';
    status << opt->output << ": " << report.grids << " grid(s), " << t->spec() << ", " << seconds << " s\n";
  });
}

}  // namespace pupwave::cli
