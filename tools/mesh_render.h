#pragma once
// A small software rasteriser for the LOD contact sheet of `pupwave mesh lod --sheet`: each
// mesh in its own tile, all with the same view and scale (fitted to the first mesh), flat
// Lambert shading with the triangle edges drawn darker so the level of detail shows, and the
// tile's level number in the corner.

#include <vector>

#include "codec/image/image.h"
#include "transforms/sqrt3/mesh.h"

namespace pupwave::cli {

// tiles[i] is labelled labels[i]; the sheet is tiles.size() tiles wide, `tile` pixels square.
Image render_contact_sheet(const std::vector<sqrt3::TriMesh>& tiles, const std::vector<int>& labels,
                           std::size_t tile = 320);

}  // namespace pupwave::cli
