// `pupwave convert-volume IN OUT`: raw dense volumes <-> OpenVDB grids through the library's
// Volume / VolumeGrid (the same path the volume codec uses), e.g. to give a simulation dump to
// `pupwave lod` or to inspect a grid's dense active box as raw floats.
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "tools/atomic_file.h"
#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/volume_io.h"

namespace pupwave::cli {
namespace {

struct ConvertVolumeOptions {
  std::string input, output, dims, dtype, grid, name;
  double voxel_size = 1.0;
  Verbosity verbosity;
};

// The grids the input holds: every float/double grid of a .vdb (or the --grid one), or one dense
// grid from a raw file described by --dims and --dtype.
std::vector<VolumeGrid> read_input(const ConvertVolumeOptions& o) {
  if (is_vdb_path(o.input)) {
    if (!o.dims.empty()) throw std::invalid_argument("--dims applies to raw input only");
    return read_vdb(o.input, o.grid);
  }
  if (o.dims.empty() || o.dtype.empty())
    throw std::invalid_argument("raw input " + o.input + " needs --dims X,Y,Z and --dtype u8|u16|f32|f64");
  VolumeGrid g;
  g.name = o.name.empty() ? std::filesystem::path(o.input).stem().string() : o.name;
  for (std::size_t a = 0; a < 3; ++a) g.index_to_world[5 * a] = o.voxel_size;
  g.volume = read_raw_volume(o.input, parse_dims(o.dims), parse_voxel_type(o.dtype));
  return {std::move(g)};
}

void write_volume_output(std::vector<VolumeGrid> grids, const ConvertVolumeOptions& o) {
  if (is_vdb_path(o.output)) {
    write_vdb(grids, o.output);
    return;
  }
  if (grids.size() != 1)
    throw std::invalid_argument(o.input + " holds " + std::to_string(grids.size()) +
                                " grids; choose one with --grid NAME for raw output");
  make_dense_box(grids[0], kMaxVdbBoxVoxels);  // raw output is the dense active bounding box
  Volume& v = grids[0].volume;
  if (v.count() == 0) throw std::runtime_error("grid '" + grids[0].name + "' has no active voxels");
  if (!o.dtype.empty() && is_vdb_path(o.input))
    v.type = parse_voxel_type(o.dtype);  // raw input: its own type
  write_raw_volume(v, o.output);
}

}  // namespace

void add_convert_volume_command(CLI::App& app) {
  auto opt = std::make_shared<ConvertVolumeOptions>();
  auto* cmd = app.add_subcommand(
      "convert-volume",
      "Convert a volume between raw (little endian, x fastest) and OpenVDB (.vdb, by extension).\n"
      "Raw input needs --dims and --dtype and becomes one dense grid with every voxel active.\n"
      "Raw output holds the dense active bounding box of one grid (its origin is printed).");
  cmd->add_option("IN", opt->input, "input .raw or .vdb, or - for stdin")->required();
  cmd->add_option("OUT", opt->output, "output .raw or .vdb, or - for raw on stdout")->required();
  cmd->add_option("--dims", opt->dims, "raw input extent X,Y,Z");
  cmd->add_option("--dtype", opt->dtype,
                  "raw input sample type (u8, u16, f32, f64); for .vdb -> raw, the output type");
  cmd->add_option("--grid", opt->grid, "the .vdb grid to convert (default: all)");
  cmd->add_option("--name", opt->name, "grid name for raw input (default: the file's stem)");
  cmd->add_option("--voxel-size", opt->voxel_size, "voxel size for raw input (world units)")
      ->check(positive_number());
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    check_output_path(opt->output);
    opt->verbosity.to_stderr = is_stdio(opt->output);
    const InputPath input(opt->input);
    ConvertVolumeOptions o = *opt;
    o.input = input.path;
    if (o.name.empty() && is_stdio(opt->input)) o.name = "volume";  // not the spooled file's name
    std::vector<VolumeGrid> grids = read_input(o);
    for (const VolumeGrid& g : grids) {
      const Extent& d = g.volume.dims;
      o.verbosity.out() << g.name << ": " << d[0] << 'x' << d[1] << 'x' << d[2] << " at (" << g.origin[0]
                        << ',' << g.origin[1] << ',' << g.origin[2] << "), " << g.active_voxels()
                        << " active, " << to_string(g.volume.type) << ", " << to_string(g.grid_class) << '\n';
    }
    write_volume_output(std::move(grids), o);
  });
}

}  // namespace pupwave::cli
