// `pupwave info` for volume streams: what the header says, checked against the whole stream.
#include <algorithm>
#include <sstream>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"

namespace pupwave {
namespace {

struct GridCounts {
  std::size_t active = 0, tiles = 0, blocks = 0, missing = 0;
};

std::size_t active_states(const MaskChunk& m) {
  return std::size_t(std::count(m.states.begin(), m.states.end(), std::uint8_t(VoxelState::active)));
}

// Active voxels (tile voxels included), active tiles and blocks of grid g, from the stream.
GridCounts count_grid(const ParsedVolumeStream& s, std::size_t g) {
  GridCounts n;
  const Volume& v = s.header.grids[g].volume;
  if (s.header.blocked[g]) {
    const BlocksChunk& l = s.layouts[g];
    n.active = active_states(l.mask);
    n.blocks = l.blocks.size();
    for (const VolumeTile& t : l.tiles)
      if (t.active) n.active += std::size_t(t.edge) * t.edge * t.edge, ++n.tiles;
  } else {
    n.active = v.is_sparse() ? s.masks[g].active : v.count();
    if (s.header.has_missing(g)) n.missing = v.count() - n.active;
  }
  return n;
}

}  // namespace

std::string describe_volume_stream(std::span<const std::uint8_t> bytes) {
  const ParsedVolumeStream s = parse_volume_stream(bytes, {}, SparseBoxCount::content);
  const VolumeStreamHeader& h = s.header;
  std::ostringstream out;
  out << "pupwave volume stream, " << bytes.size() << " bytes\n"
      << "  transform   " << h.spec << ", " << h.levels << " level(s) per brick, "
      << (h.reversible ? "reversible (lossless)" : "irreversible") << '\n'
      << "  bricks      " << (std::size_t(1) << h.brick_log2) << "^3, code-blocks "
      << (std::size_t(1) << h.block_log2) << "^3, " << s.bricks.size() << " brick chunk(s)\n";
  if (h.max_error > 0) out << "  max error   " << h.max_error << " (guaranteed on every voxel)\n";
  for (std::size_t g = 0; g < h.grids.size(); ++g) {
    const VolumeGrid& grid = h.grids[g];
    const Volume& v = grid.volume;
    if (h.blocked[g] == 2) {
      const auto type = grid.metadata.find("vdb_value_type");
      const auto active = grid.metadata.find("vdb_active_voxels");
      out << "  grid " << g << "      '" << grid.name << "', "
          << (type != grid.metadata.end() ? type->second.text : std::string("?"))
          << " values carried as OpenVDB serialises them (lossless), "
          << (active != grid.metadata.end() ? std::to_string(active->second.integer) : std::string("?"))
          << " active voxels; " << s.grid_bytes[g] << " bytes ("
          << 100.0 * double(s.grid_bytes[g]) / double(bytes.size()) << "% of the stream)\n";
      continue;
    }
    const GridCounts n = count_grid(s, g);
    const auto size = grid.voxel_size();
    // One component of an OpenVDB vector grid (the reader codes vec3 grids per component).
    const auto component = grid.metadata.find("vdb_vector_component");
    const auto vector = grid.metadata.find("vdb_vector_type");
    const std::string part = component != grid.metadata.end() && vector != grid.metadata.end()
                                 ? ", component " + std::to_string(component->second.integer) + " of a " +
                                       vector->second.text + " grid"
                                 : std::string();
    out << "  grid " << g << "      '" << grid.name << "'" << part << ", " << to_string(grid.grid_class)
        << ", " << to_string(v.type)
        << (h.blocked[g]       ? ", sparse (blocks and tiles)"
            : h.has_missing(g) ? ", dense with missing values"
            : v.is_sparse()    ? ", sparse"
                               : ", dense")
        << ", background " << v.background << '\n'
        << "              " << n.active << " active voxels, "
        << (h.has_missing(g) ? std::to_string(n.missing) + " missing voxels (NaN, infinity or fill value), "
                             : "")
        << n.tiles << " active tile(s), " << n.blocks << " block(s); bounding box (" << grid.origin[0] << ","
        << grid.origin[1] << "," << grid.origin[2] << ")..(" << grid.origin[0] + std::int64_t(v.dims[0]) - 1
        << "," << grid.origin[1] + std::int64_t(v.dims[1]) - 1 << ","
        << grid.origin[2] + std::int64_t(v.dims[2]) - 1 << "), " << v.dims[0] << " x " << v.dims[1] << " x "
        << v.dims[2] << "; voxel size " << size[0] << " x " << size[1] << " x " << size[2] << "; "
        << s.grid_bytes[g] << " bytes (" << 100.0 * double(s.grid_bytes[g]) / double(bytes.size())
        << "% of the stream)\n";
  }
  std::size_t outlier_bytes = 0, outlier_bricks = 0;
  for (const BrickChunk& b : s.bricks)
    if (!b.outliers.empty()) outlier_bytes += b.outliers.size(), ++outlier_bricks;
  out << "  outliers    " << outlier_bytes << " bytes of corrections in " << outlier_bricks << " brick(s)\n";
  return out.str();
}

}  // namespace pupwave
