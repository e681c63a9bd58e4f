// `pupwave info` for volume streams: what the header says, checked against the whole stream.
#include <sstream>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"

namespace pupwave {

std::string describe_volume_stream(std::span<const std::uint8_t> bytes) {
  const ParsedVolumeStream s = parse_volume_stream(bytes);
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
    out << "  grid " << g << "      '" << grid.name << "', " << to_string(grid.grid_class) << ", "
        << v.dims[0] << " x " << v.dims[1] << " x " << v.dims[2] << ", " << to_string(v.type)
        << (v.is_sparse() ? ", sparse" : ", dense") << ", background " << v.background << '\n';
  }
  std::size_t outlier_bytes = 0, outlier_bricks = 0;
  for (const BrickChunk& b : s.bricks)
    if (!b.outliers.empty()) outlier_bytes += b.outliers.size(), ++outlier_bricks;
  out << "  outliers    " << outlier_bytes << " bytes of corrections in " << outlier_bricks << " brick(s)\n";
  return out.str();
}

}  // namespace pupwave
