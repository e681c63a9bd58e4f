// The OpenVDB module (see tools/vdb_module.h): reading, describing and writing .vdb files and
// `pupwave lod`. Built as a shared module; the CLI loads it on first use.
#include "tools/vdb_module.h"

#include <algorithm>

#include "tools/lod_pyramid.h"
#include "tools/volume_io_vdb.h"

namespace pupwave::cli {
namespace {

LodReport run_lod(const LodJob& job) {
  VdbFile file = read_vdb_file(job.input);
  for (const std::string& name : job.names)
    if (std::none_of(file.grids.begin(), file.grids.end(),
                     [&](const auto& g) { return g->getName() == name; }))
      throw std::runtime_error("cannot read " + job.input.string() + ": no grid named '" + name + "'");
  openvdb::GridPtrVec out;
  LodReport report;
  for (const openvdb::GridBase::Ptr& g : file.grids) {
    if (!job.names.empty() && std::find(job.names.begin(), job.names.end(), g->getName()) == job.names.end())
      continue;
    if (!has_lod(*g)) {  // integer, bool, mask, unknown grids: kept as they are, never dropped
      out.push_back(g);
      report.lines.push_back(g->getName() + ": " + g->valueType() + " grid, copied unchanged");
      continue;
    }
    for (openvdb::GridBase::Ptr& level : level_of_detail(g, job.low_pass, job.levels, job.edge)) {
      report.lines.push_back(level->getName() + ": " + std::to_string(level->activeVoxelCount()) +
                             " active voxels, voxel size " + std::to_string(level->voxelSize()[0]));
      out.push_back(std::move(level));
    }
  }
  write_vdb_file(out, file.metadata, job.output);
  report.grids = out.size();
  return report;
}

const VdbModule kModule{read_vdb_grids, describe_vdb_grids, write_vdb_grids, run_lod};

}  // namespace
}  // namespace pupwave::cli

extern "C" const pupwave::cli::VdbModule* pupwave_vdb_module() { return &pupwave::cli::kModule; }
