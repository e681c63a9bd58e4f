#pragma once
// The OpenVDB half of volume file I/O lives in a module (tools/vdb/, built as a shared module
// next to the `pupwave` binary) that is loaded on first use. Linked into the CLI, OpenVDB (with
// Boost, Blosc, TBB, log4cplus) would make ld.so resolve its symbols at every start: about 30 ms
// of CPU, twice zfp's whole run on a 91^3 volume. Commands that touch no .vdb file never load it.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "codec/volume/volume.h"
#include "tools/lod_low_pass.h"

namespace pupwave::cli {

// One `pupwave lod` run: the levels of the named grids (all when empty) of input, to output.
struct LodJob {
  std::filesystem::path input, output;
  LowPass low_pass;
  std::vector<int> levels;
  std::vector<std::string> names;
  LodEdge edge = LodEdge::automatic;
};

// What `pupwave lod` prints: a line per output grid, and how many grids were written.
struct LodReport {
  std::vector<std::string> lines;
  std::size_t grids = 0;
};

// The operations the module provides (contracts in tools/volume_io.h and tools/cmd_lod.cpp).
// Each throws std::runtime_error (or std::invalid_argument) with the reason.
struct VdbModule {
  std::vector<VolumeGrid> (*read)(const std::filesystem::path& path, std::string_view grid_name,
                                  std::vector<std::string>* skipped);
  std::string (*describe)(const std::filesystem::path& path);
  void (*write)(const std::vector<VolumeGrid>& grids, const std::filesystem::path& path);
  LodReport (*lod)(const LodJob& job);
};

// The module, loaded on first call (next to the running executable, else where the build put
// it). Throws std::runtime_error if it cannot be loaded.
const VdbModule& vdb_module();

}  // namespace pupwave::cli

// The module's one exported symbol.
extern "C" const pupwave::cli::VdbModule* pupwave_vdb_module();
