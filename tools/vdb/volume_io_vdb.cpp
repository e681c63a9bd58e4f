// The OpenVDB half of volume file I/O (see tools/volume_io.h for the contracts, and
// tools/vdb_module.h for why it lives in a module the CLI loads only for .vdb files).
#include "tools/volume_io_vdb.h"

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "tools/atomic_file.h"

namespace pupwave::cli {
namespace fs = std::filesystem;

// OpenVDB needs its type registry filled once per process before any file is read or written.
static void ensure_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// Grid metadata that describes the file rather than the grid, or is held in VolumeGrid fields.
// Vector grids travel as three scalar grids (split_vector below), tagged with these entries.
constexpr const char* kVectorComponentMeta = "vdb_vector_component";  // int32 0..2
constexpr const char* kVectorTypeMeta = "vdb_vector_type";            // "vec3s" or "vec3d"
constexpr const char* kVectorClassMeta = "vdb_vector_class";          // OpenVDB's class name

static bool is_structural_meta(const std::string& key) {
  return key == openvdb::GridBase::META_GRID_NAME || key == openvdb::GridBase::META_GRID_CLASS ||
         key.rfind("file_", 0) == 0 || key == kVectorComponentMeta || key == kVectorTypeMeta ||
         key == kVectorClassMeta;
}

template <class T>
static const T* typed_meta(const openvdb::Metadata& m) {
  const auto* t = dynamic_cast<const openvdb::TypedMetadata<T>*>(&m);
  return t ? &t->value() : nullptr;
}

// The typed value of one metadata entry, or false for types VolumeGrid does not hold.
static bool meta_from_vdb(const openvdb::Metadata& m, MetaValue& out) {
  using K = MetaValue::Kind;
  if (const auto* s = typed_meta<std::string>(m)) {
    out.kind = K::string;
    out.text = *s;
  } else if (const auto* b = typed_meta<bool>(m)) {
    out.kind = K::boolean;
    out.integer = *b ? 1 : 0;
  } else if (const auto* i = typed_meta<openvdb::Int32>(m)) {
    out.kind = K::int32;
    out.integer = *i;
  } else if (const auto* l = typed_meta<openvdb::Int64>(m)) {
    out.kind = K::int64;
    out.integer = *l;
  } else if (const auto* f = typed_meta<float>(m)) {
    out.kind = K::float32;
    out.numbers[0] = *f;
  } else if (const auto* d = typed_meta<double>(m)) {
    out.kind = K::float64;
    out.numbers[0] = *d;
  } else if (const auto* vi = typed_meta<openvdb::Vec3i>(m)) {
    out.kind = K::vec3i;
    for (int a = 0; a < 3; ++a) out.numbers[std::size_t(a)] = (*vi)[a];
  } else if (const auto* vs = typed_meta<openvdb::Vec3s>(m)) {
    out.kind = K::vec3f;
    for (int a = 0; a < 3; ++a) out.numbers[std::size_t(a)] = (*vs)[a];
  } else if (const auto* vd = typed_meta<openvdb::Vec3d>(m)) {
    out.kind = K::vec3d;
    for (int a = 0; a < 3; ++a) out.numbers[std::size_t(a)] = (*vd)[a];
  } else {
    return false;
  }
  return true;
}

static void meta_to_vdb(openvdb::MetaMap& grid, const std::string& key, const MetaValue& v) {
  using K = MetaValue::Kind;
  const auto& n = v.numbers;
  switch (v.kind) {
    case K::string: grid.insertMeta(key, openvdb::StringMetadata(v.text)); break;
    case K::boolean: grid.insertMeta(key, openvdb::BoolMetadata(v.integer != 0)); break;
    case K::int32:
      grid.insertMeta(key, openvdb::Int32Metadata(static_cast<openvdb::Int32>(v.integer)));
      break;
    case K::int64: grid.insertMeta(key, openvdb::Int64Metadata(v.integer)); break;
    case K::float32: grid.insertMeta(key, openvdb::FloatMetadata(static_cast<float>(n[0]))); break;
    case K::float64: grid.insertMeta(key, openvdb::DoubleMetadata(n[0])); break;
    case K::vec3i:
      grid.insertMeta(key, openvdb::Vec3IMetadata(openvdb::Vec3i(int(n[0]), int(n[1]), int(n[2]))));
      break;
    case K::vec3f:
      grid.insertMeta(key, openvdb::Vec3SMetadata(openvdb::Vec3s(float(n[0]), float(n[1]), float(n[2]))));
      break;
    case K::vec3d: grid.insertMeta(key, openvdb::Vec3DMetadata(openvdb::Vec3d(n[0], n[1], n[2]))); break;
  }
}

// What VolumeGrid::metadata has no kind for travels under reserved key prefixes: file-level
// entries (held by the file's first grid) and entries of the other OpenVDB metadata types (vec2,
// vec4, matrices, ...), whose text is OpenVDB's own serialisation of the value.
constexpr std::string_view kFileMetaPrefix = "vdb_file:";
constexpr std::string_view kTypedMetaPrefix = "vdb_typed:";  // vdb_typed:TYPE:key

static void keep_meta(const std::string& key, const openvdb::Metadata& m,
                      std::map<std::string, MetaValue>& out) {
  MetaValue v;
  if (meta_from_vdb(m, v)) {
    out[key] = v;
    return;
  }
  std::ostringstream bytes(std::ios::binary);
  m.write(bytes);
  v.text = bytes.str();
  out[std::string(kTypedMetaPrefix) + m.typeName() + ":" + key] = v;
}

static bool is_file_meta(std::string_view key) {
  if (key.starts_with(kTypedMetaPrefix)) {
    const std::size_t colon = key.find(':', kTypedMetaPrefix.size());
    if (colon != std::string_view::npos) key.remove_prefix(colon + 1);
  }
  return key.starts_with(kFileMetaPrefix);
}

// Undoes keep_meta: the entry goes to the file's map or the grid's, typed as it was read.
static void restore_meta(std::string key, const MetaValue& v, openvdb::MetaMap& grid,
                         openvdb::MetaMap& file) {
  std::string type;
  if (key.starts_with(kTypedMetaPrefix)) {
    const std::size_t colon = key.find(':', kTypedMetaPrefix.size());
    if (colon != std::string::npos) {
      type = key.substr(kTypedMetaPrefix.size(), colon - kTypedMetaPrefix.size());
      key.erase(0, colon + 1);
    }
  }
  openvdb::MetaMap& target = key.starts_with(kFileMetaPrefix) ? file : grid;
  if (&target == &file) key.erase(0, kFileMetaPrefix.size());
  if (type.empty()) {
    meta_to_vdb(target, key, v);
    return;
  }
  try {
    openvdb::Metadata::Ptr m = openvdb::Metadata::createMetadata(type);
    std::istringstream in(v.text, std::ios::binary);
    m->read(in);
    if (!in) throw std::runtime_error("truncated");
    target.insertMeta(key, *m);
  } catch (const std::exception& e) {
    throw std::runtime_error("metadata '" + key + "' of type " + type + " does not read back (" + e.what() +
                             ")");
  }
}

static GridClass class_from_vdb(openvdb::GridClass c) {
  if (c == openvdb::GRID_LEVEL_SET) return GridClass::level_set;
  if (c == openvdb::GRID_FOG_VOLUME) return GridClass::fog_volume;
  return GridClass::unknown;
}

static openvdb::GridClass class_to_vdb(GridClass c) {
  if (c == GridClass::level_set) return openvdb::GRID_LEVEL_SET;
  if (c == GridClass::fog_volume) return openvdb::GRID_FOG_VOLUME;
  return openvdb::GRID_UNKNOWN;
}

static void describe_transform(const openvdb::GridBase& grid, VolumeGrid& out, const fs::path& path);

// Name, class, transform and metadata of a grid (everything but the values).
static void describe_from_vdb(const openvdb::GridBase& grid, VolumeGrid& out, const fs::path& path) {
  out.name = grid.getName();
  out.grid_class = class_from_vdb(grid.getGridClass());
  describe_transform(grid, out, path);
  for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it)
    if (!is_structural_meta(it->first) && it->second) keep_meta(it->first, *it->second, out.metadata);
}

// The linear index-to-world map of a grid; frustum transforms are refused.
static void describe_transform(const openvdb::GridBase& grid, VolumeGrid& out, const fs::path& path) {
  const openvdb::math::Transform& xform = grid.transform();
  if (!xform.isLinear())
    throw std::runtime_error("cannot read " + path.string() + ": grid '" + out.name +
                             "' has a non-linear (frustum) transform, which is not supported");
  const openvdb::Mat4d m = xform.baseMap()->getAffineMap()->getMat4();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.index_to_world[std::size_t(4 * r + c)] = m(r, c);
}

// Blocks gather the leaf nodes of one 64^3 page; 64 divides OpenVDB's 128^3 internal nodes, so
// a block never straddles one and memory follows the leaves, not the bounding box.
constexpr int kPageLog2 = 6;

template <class GridT>
static VoxelType voxel_type_of() {
  return std::is_same_v<typename GridT::ValueType, double> ? VoxelType::f64 : VoxelType::f32;
}

// The leaves of one page as a block over their bounding box. Voxels no leaf covers are inactive
// background, or -background under an inactive tile of that value (a level set's inside), so the
// transform does not see a false jump there; other tiles stay in the tile list only.
template <class GridT, class LeafT>
static VolumeBlock leaf_block(const GridT& grid, const std::vector<const LeafT*>& leaves, VoxelType type,
                              double background) {
  openvdb::Coord lo = leaves.front()->origin(), hi = lo;
  for (const LeafT* leaf : leaves) {
    lo.minComponent(leaf->origin());
    hi.maxComponent(leaf->origin());
  }
  VolumeBlock b;
  Extent dims{};
  for (int a = 0; a < 3; ++a) {
    b.origin[std::size_t(a)] = lo[a];
    dims[std::size_t(a)] = std::size_t(hi[a] - lo[a]) + LeafT::DIM;
  }
  b.volume = Volume(dims, type);
  b.volume.background = background;
  std::fill(b.volume.samples.begin(), b.volume.samples.end(), background);
  b.volume.active.assign(b.volume.count(), 0);
  auto acc = grid.getConstAccessor();
  const auto inside = static_cast<typename GridT::ValueType>(-background);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const openvdb::Coord p = lo + openvdb::Coord(int(x), int(y), int(z));
        if (acc.probeConstLeaf(p) != nullptr) continue;  // filled from the leaf below
        typename GridT::ValueType v;
        if (!acc.probeValue(p, v) && v == inside) b.volume.at(x, y, z) = double(inside);
      }
  for (const LeafT* leaf : leaves)
    for (openvdb::Index n = 0; n < LeafT::SIZE; ++n) {
      const openvdb::Coord p = leaf->offsetToGlobalCoord(n) - lo;
      const std::size_t i = b.volume.index(std::size_t(p.x()), std::size_t(p.y()), std::size_t(p.z()));
      b.volume.samples[i] = double(leaf->getValue(n));
      b.volume.active[i] = leaf->isValueOn(n) ? 1 : 0;
    }
  return b;
}

// Sparse-native extraction: leaves gathered into blocks page by page, tiles kept as tiles
// (active ones, and inactive ones whose value is not the background), the active bounding box
// in origin / volume.dims. Memory follows the leaves and tiles, not the bounding box.
template <class GridT>
static void extract_sparse(const GridT& grid, VolumeGrid& out) {
  using LeafT = typename GridT::TreeType::LeafNodeType;
  const VoxelType type = voxel_type_of<GridT>();
  const double background = double(grid.background());
  out.volume = Volume({0, 0, 0}, type);
  out.volume.background = background;
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) return;
  for (int a = 0; a < 3; ++a) {
    out.volume.dims[std::size_t(a)] = std::size_t(std::int64_t(box.max()[a]) - box.min()[a] + 1);
    out.origin[std::size_t(a)] = box.min()[a];
  }
  // Pages start at the lowest leaf origin, not at 0: a small grid around the origin is one block
  // (one set of block edges) rather than up to eight.
  openvdb::Coord first(std::numeric_limits<int>::max());
  for (auto it = grid.tree().cbeginLeaf(); it; ++it) first.minComponent(it->origin());
  std::map<std::array<std::int64_t, 3>, std::vector<const LeafT*>> pages;
  for (auto it = grid.tree().cbeginLeaf(); it; ++it) {
    const openvdb::Coord o = it->origin();
    std::array<std::int64_t, 3> page{};
    for (int a = 0; a < 3; ++a) page[std::size_t(a)] = (std::int64_t(o[a]) - first[a]) >> kPageLog2;
    pages[page].push_back(&*it);
  }
  for (const auto& [page, leaves] : pages) out.blocks.push_back(leaf_block(grid, leaves, type, background));
  auto it = grid.tree().cbeginValueAll();
  it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only, not the voxels of leaves
  for (; it; ++it) {
    if (!it.isValueOn() && double(*it) == background) continue;
    openvdb::CoordBBox tile;
    it.getBoundingBox(tile);
    VolumeTile t;
    for (int a = 0; a < 3; ++a) t.origin[std::size_t(a)] = tile.min()[a];
    t.edge = std::uint32_t(tile.dim().x());
    t.value = double(*it);
    t.active = it.isValueOn();
    out.tiles.push_back(t);
  }
}

// Vector grids (vec3s, vec3d) are coded lossy as three scalar grids of the same name and
// topology, one per component, so an error bound holds per component; the metadata of the
// vector grid rides on component 0, and write_vdb joins the three back into one vector grid.
// Component c of a vector tree, leaf for leaf and tile for tile.
template <class ScalarTreeT, class VecTreeT>
static typename ScalarTreeT::Ptr component_tree(const VecTreeT& vec, int c) {
  using LeafT = typename ScalarTreeT::LeafNodeType;
  auto tree = std::make_shared<ScalarTreeT>(vec.background()[c]);
  auto it = vec.cbeginValueAll();
  it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only
  for (; it; ++it) tree->addTile(it.getLevel(), it.getCoord(), (*it)[c], it.isValueOn());
  for (auto leaf = vec.cbeginLeaf(); leaf; ++leaf) {
    auto* out = new LeafT(leaf->origin(), vec.background()[c], false);
    for (openvdb::Index n = 0; n < LeafT::SIZE; ++n) out->setValueOnly(n, leaf->getValue(n)[c]);
    out->setValueMask(leaf->getValueMask());
    tree->addLeaf(out);
  }
  return tree;
}

template <class ScalarGridT, class VecGridT>
static void split_vector(const VecGridT& vec, const fs::path& path, std::vector<VolumeGrid>& result) {
  for (int c = 0; c < 3; ++c) {
    VolumeGrid g;
    if (c == 0) describe_from_vdb(vec, g, path);
    g.name = vec.getName();
    g.grid_class = class_from_vdb(vec.getGridClass());
    describe_transform(vec, g, path);
    ScalarGridT scalar(component_tree<typename ScalarGridT::TreeType>(vec.tree(), c));
    extract_sparse(scalar, g);
    g.metadata[kVectorComponentMeta] = MetaValue{MetaValue::Kind::int32, {}, c, {}};
    g.metadata[kVectorTypeMeta] = MetaValue{MetaValue::Kind::string, vec.valueType(), 0, {}};
    if (c == 0)
      g.metadata[kVectorClassMeta] =
          MetaValue{MetaValue::Kind::string, openvdb::GridBase::gridClassToString(vec.getGridClass()), 0, {}};
    result.push_back(std::move(g));
  }
}

// A grid the codec does not transform-code, as OpenVDB serialises it (a one-grid stream), with
// its value type and active voxel count for `info`.
static VolumeGrid opaque_grid(const openvdb::GridBase& grid) {
  VolumeGrid g;
  g.name = grid.getName();
  std::ostringstream full(std::ios::binary);
  openvdb::io::Stream(full).write(openvdb::GridCPtrVec{grid.copyGrid()});
  const std::string text = full.str();
  g.opaque.assign(text.begin(), text.end());
  MetaValue type;
  type.text = grid.valueType();
  g.metadata["vdb_value_type"] = type;
  MetaValue active;
  active.kind = MetaValue::Kind::int64;
  active.integer = std::int64_t(grid.activeVoxelCount());
  g.metadata["vdb_active_voxels"] = active;
  return g;
}

// The grid an opaque VolumeGrid carries.
static openvdb::GridBase::Ptr grid_from_opaque(const VolumeGrid& g) {
  std::istringstream in(std::string(g.opaque.begin(), g.opaque.end()), std::ios::binary);
  try {
    openvdb::io::Stream stream(in);
    const openvdb::GridPtrVecPtr grids = stream.getGrids();
    if (!grids || grids->size() != 1) throw std::runtime_error("not one grid");
    return (*grids)[0];
  } catch (const std::exception& e) {
    throw std::runtime_error("grid '" + g.name + "': its carried OpenVDB bytes do not read back (" +
                             std::string(e.what()) + ")");
  }
}

static std::string available_names(const openvdb::GridPtrVec& grids) {
  std::string names;
  for (const auto& g : grids) names += (names.empty() ? "'" : ", '") + g->getName() + "'";
  return names.empty() ? "none" : names;
}

// Every grid of a file (trees included) and, if asked, its file metadata; OpenVDB errors become a
// clear runtime_error.
static openvdb::GridPtrVecPtr read_all_grids(const fs::path& path, openvdb::MetaMap* file_meta = nullptr) {
  ensure_openvdb();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::runtime_error("cannot read " + path.string() + ": no such file");
  try {
    openvdb::io::File file(path.string());
    file.open(false);  // no delayed loading: the file is read now, errors surface here
    openvdb::GridPtrVecPtr grids = file.getGrids();
    if (file_meta)
      if (const openvdb::MetaMap::Ptr meta = file.getMetadata()) *file_meta = *meta;
    file.close();
    if (!grids) throw std::runtime_error("no grids");
    return grids;
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error("cannot read " + path.string() + ": not a valid OpenVDB file (" + e.what() +
                             ")");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("cannot read " + path.string() + ": corrupt OpenVDB file (allocation failed)");
  }
}

std::vector<VolumeGrid> read_vdb_grids(const fs::path& path, std::string_view grid_name,
                                       std::vector<std::string>* skipped) {
  openvdb::MetaMap file_meta;
  const openvdb::GridPtrVecPtr grids = read_all_grids(path, &file_meta);
  if (grids->empty())
    throw std::runtime_error("cannot read " + path.string() + ": no grids (empty or truncated file)");
  std::vector<VolumeGrid> result;
  for (const openvdb::GridBase::Ptr& base : *grids) {
    if (!grid_name.empty() && base->getName() != grid_name) continue;
    VolumeGrid g;
    if (auto fg = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
      describe_from_vdb(*fg, g, path);
      extract_sparse(*fg, g);
    } else if (auto dg = openvdb::gridPtrCast<openvdb::DoubleGrid>(base)) {
      describe_from_vdb(*dg, g, path);
      extract_sparse(*dg, g);
    } else if (auto vs = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base)) {
      split_vector<openvdb::FloatGrid>(*vs, path, result);
      continue;
    } else if (auto vd = openvdb::gridPtrCast<openvdb::Vec3DGrid>(base)) {
      split_vector<openvdb::DoubleGrid>(*vd, path, result);
      continue;
    } else {
      g = opaque_grid(*base);  // integer, bool, mask or unknown values: carried verbatim
      if (skipped) skipped->push_back(base->getName());
    }
    result.push_back(std::move(g));
  }
  if (!grid_name.empty() && result.empty())
    throw std::runtime_error("cannot read " + path.string() + ": no grid named '" + std::string(grid_name) +
                             "' (grids: " + available_names(*grids) + ")");
  if (result.empty())
    throw std::runtime_error("cannot read " + path.string() + ": no float or double grid in the file");
  for (auto it = file_meta.beginMeta(); it != file_meta.endMeta(); ++it)  // the file's, on its first grid
    if (it->second) keep_meta(std::string(kFileMetaPrefix) + it->first, *it->second, result.front().metadata);
  return result;
}

VdbFile read_vdb_file(const fs::path& path) {
  VdbFile f;
  const openvdb::GridPtrVecPtr grids = read_all_grids(path, &f.metadata);
  if (grids->empty())
    throw std::runtime_error("cannot read " + path.string() + ": no grids (empty or truncated file)");
  f.grids = *grids;
  return f;
}

void write_vdb_file(const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata,
                    const fs::path& path) {
  ensure_openvdb();
  write_output(path, [&](const fs::path& tmp) {
    try {
      openvdb::io::File file(tmp.string());
      file.write(grids, metadata);
      file.close();
    } catch (const openvdb::Exception& e) {
      throw std::runtime_error("cannot write " + path.string() + ": " + e.what());
    }
  });
}

std::string describe_vdb_grids(const fs::path& path) {
  const openvdb::GridPtrVecPtr grids = read_all_grids(path);
  std::ostringstream out;
  out << path.string() << ": OpenVDB file, " << grids->size() << " grid(s)\n";
  for (std::size_t i = 0; i < grids->size(); ++i) {
    const openvdb::GridBase& g = *(*grids)[i];
    const openvdb::CoordBBox box = g.evalActiveVoxelBoundingBox();
    const openvdb::Vec3d size = g.voxelSize();
    out << "  grid " << i << " '" << g.getName() << "': class "
        << openvdb::GridBase::gridClassToString(g.getGridClass()) << ", type " << g.valueType() << ", "
        << g.activeVoxelCount() << " active voxels (" << g.baseTree().activeTileCount() << " active tile(s))";
    if (box.empty())
      out << ", no active voxels";
    else
      out << ", bounding box " << box.min() << ".." << box.max() << " (" << box.dim().x() << " x "
          << box.dim().y() << " x " << box.dim().z() << ")";
    out << ", voxel size " << size.x() << " x " << size.y() << " x " << size.z() << '\n';
  }
  return out.str();
}

// A sparse OpenVDB grid from a VolumeGrid: only voxels that differ from the implicit background
// (or are active) are touched, then uniform leaves are pruned back into tiles.
// Writes the voxels of a box volume placed at `at` that are active or not the background.
template <class GridT>
static void put_voxels(GridT& grid, const VolumeGrid& g, const Volume& vol,
                       const std::array<std::int64_t, 3>& at) {
  using V = typename GridT::ValueType;
  if (vol.samples.size() != vol.count() || (vol.is_sparse() && vol.active.size() != vol.count()))
    throw std::invalid_argument("write_vdb: grid '" + g.name + "' has inconsistent sizes");
  const V background = grid.background();
  auto acc = grid.getAccessor();
  const openvdb::Coord origin{int(at[0]), int(at[1]), int(at[2])};
  std::size_t i = 0;
  for (std::size_t z = 0; z < vol.dims[2]; ++z)
    for (std::size_t y = 0; y < vol.dims[1]; ++y)
      for (std::size_t x = 0; x < vol.dims[0]; ++x, ++i) {
        const openvdb::Coord ijk = origin + openvdb::Coord(int(x), int(y), int(z));
        const V value = static_cast<V>(vol.samples[i]);
        if (vol.is_active(i))
          acc.setValueOn(ijk, value);
        else if (value != background)
          acc.setValueOff(ijk, value);
      }
}

template <class GridT>
static typename GridT::Ptr build_grid(const VolumeGrid& g, bool prune = true) {
  using V = typename GridT::ValueType;
  typename GridT::Ptr grid = GridT::create(static_cast<V>(g.volume.background));
  for (const VolumeTile& t : g.tiles) {
    const openvdb::Coord o(int(t.origin[0]), int(t.origin[1]), int(t.origin[2]));
    grid->tree().fill(openvdb::CoordBBox::createCube(o, int(t.edge)), static_cast<V>(t.value), t.active);
  }
  for (const VolumeBlock& b : g.blocks) put_voxels(*grid, g, b.volume, b.origin);
  if (!g.is_blocked()) put_voxels(*grid, g, g.volume, g.origin);
  if (prune) openvdb::tools::prune(grid->tree());
  return grid;
}

// The vector grid whose three components are parts (split_vector): tiles and leaves of any
// component, each value from all three, then pruned.
template <class VecGridT, class ScalarGridT>
static typename VecGridT::Ptr join_vector(const std::array<const VolumeGrid*, 3>& parts) {
  using V = typename VecGridT::ValueType;
  using LeafT = typename VecGridT::TreeType::LeafNodeType;
  const std::array<typename ScalarGridT::Ptr, 3> comp{build_grid<ScalarGridT>(*parts[0], false),
                                                      build_grid<ScalarGridT>(*parts[1], false),
                                                      build_grid<ScalarGridT>(*parts[2], false)};
  const V background(comp[0]->background(), comp[1]->background(), comp[2]->background());
  typename VecGridT::Ptr vec = VecGridT::create(background);
  auto a0 = comp[0]->getConstAccessor(), a1 = comp[1]->getConstAccessor(), a2 = comp[2]->getConstAccessor();
  const auto value_at = [&](const openvdb::Coord& p) {
    return V(a0.getValue(p), a1.getValue(p), a2.getValue(p));
  };
  auto acc = vec->getAccessor();
  for (const auto& c : comp) {
    auto it = c->tree().cbeginValueAll();
    it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only
    for (; it; ++it)
      if (it.isValueOn() || *it != c->background())
        acc.addTile(it.getLevel(), it.getCoord(), value_at(it.getCoord()), it.isValueOn());
  }
  for (const auto& c : comp)
    for (auto leaf = c->tree().cbeginLeaf(); leaf; ++leaf) {
      if (acc.probeConstLeaf(leaf->origin())) continue;
      auto* out = new LeafT(leaf->origin(), background, false);
      for (openvdb::Index n = 0; n < LeafT::SIZE; ++n) {
        const openvdb::Coord p = leaf->offsetToGlobalCoord(n);
        out->setValueOnly(n, value_at(p));
        out->setActiveState(n, a0.isValueOn(p) || a1.isValueOn(p) || a2.isValueOn(p));
      }
      acc.addLeaf(out);
    }
  openvdb::tools::prune(vec->tree());
  return vec;
}

// True when grids i, i+1, i+2 are components 0, 1, 2 of one vector grid (same name and type).
static bool starts_vector(const std::vector<VolumeGrid>& grids, std::size_t i) {
  const auto tag = [&](std::size_t j, const char* key) -> const MetaValue* {
    const auto it = grids[j].metadata.find(key);
    return it == grids[j].metadata.end() ? nullptr : &it->second;
  };
  if (i + 2 >= grids.size()) return false;
  for (std::size_t c = 0; c < 3; ++c) {
    const MetaValue* component = tag(i + c, kVectorComponentMeta);
    const MetaValue* type = tag(i + c, kVectorTypeMeta);
    if (!component || component->integer != std::int64_t(c) || !type || grids[i + c].is_opaque() ||
        grids[i + c].name != grids[i].name || type->text != tag(i, kVectorTypeMeta)->text)
      return false;
  }
  return true;
}

static void describe_to_vdb(const VolumeGrid& g, openvdb::GridBase& grid, openvdb::MetaMap& file_meta) {
  for (const auto& [key, value] : g.metadata)
    if (!is_structural_meta(key) && !is_file_meta(key)) restore_meta(key, value, grid, file_meta);
  grid.setName(g.name);
  grid.setGridClass(class_to_vdb(g.grid_class));
  openvdb::Mat4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = g.index_to_world[std::size_t(4 * r + c)];
  try {
    auto map = openvdb::math::simplify(std::make_shared<openvdb::math::AffineMap>(m));
    grid.setTransform(std::make_shared<openvdb::math::Transform>(map));
  } catch (const openvdb::Exception& e) {
    throw std::invalid_argument("write_vdb: grid '" + g.name + "' has an invalid transform (" + e.what() +
                                ")");
  }
}

void write_vdb_grids(const std::vector<VolumeGrid>& grids, const fs::path& path) {
  ensure_openvdb();
  openvdb::GridPtrVec out;
  openvdb::MetaMap file_meta;
  for (std::size_t i = 0; i < grids.size(); ++i) {
    const VolumeGrid& g = grids[i];
    for (const auto& [key, value] : g.metadata)
      if (is_file_meta(key)) restore_meta(key, value, file_meta, file_meta);
    if (g.is_opaque()) {
      out.push_back(grid_from_opaque(g));
      continue;
    }
    const bool dbl = g.volume.type == VoxelType::f64;
    openvdb::GridBase::Ptr grid;
    if (starts_vector(grids, i)) {
      const std::array<const VolumeGrid*, 3> parts{&g, &grids[i + 1], &grids[i + 2]};
      if (g.metadata.at(kVectorTypeMeta).text == openvdb::typeNameAsString<openvdb::Vec3d>())
        grid = join_vector<openvdb::Vec3DGrid, openvdb::DoubleGrid>(parts);
      else
        grid = join_vector<openvdb::Vec3SGrid, openvdb::FloatGrid>(parts);
      const auto cls = g.metadata.find(kVectorClassMeta);
      describe_to_vdb(g, *grid, file_meta);
      if (cls != g.metadata.end()) grid->setGridClass(openvdb::GridBase::stringToGridClass(cls->second.text));
      for (std::size_t c = 1; c < 3; ++c)
        for (const auto& [key, value] : grids[i + c].metadata)
          if (is_file_meta(key)) restore_meta(key, value, file_meta, file_meta);
      i += 2;
    } else {
      grid = dbl ? openvdb::GridBase::Ptr(build_grid<openvdb::DoubleGrid>(g))
                 : openvdb::GridBase::Ptr(build_grid<openvdb::FloatGrid>(g));
      describe_to_vdb(g, *grid, file_meta);
    }
    out.push_back(grid);
  }
  write_output(path, [&](const fs::path& tmp) {
    try {
      openvdb::io::File file(tmp.string());
      file.write(out, file_meta);
      file.close();
    } catch (const openvdb::Exception& e) {
      throw std::runtime_error("cannot write " + path.string() + ": " + e.what());
    }
  });
}

}  // namespace pupwave::cli
