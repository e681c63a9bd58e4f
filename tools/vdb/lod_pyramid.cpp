#include "tools/lod_pyramid.h"

#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace pupwave::cli {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int ceil_div(int a, int b) { return -floor_div(-a, b); }

// Whole-sample symmetric reflection of i into [lo, hi]: the extension of the CDF banks.
int reflect_into(int i, int lo, int hi) {
  const std::int64_t n = std::int64_t(hi) - lo + 1;
  if (n <= 1) return lo;
  const std::int64_t period = 2 * (n - 1);
  std::int64_t d = (std::int64_t(i) - lo) % period;
  if (d < 0) d += period;
  return int(lo + (d < n ? d : period - d));
}

template <class V>
constexpr int kComponents = openvdb::VecTraits<V>::Size;

template <class V>
double component(const V& v, int c) {
  if constexpr (openvdb::VecTraits<V>::IsVec)
    return double(v[c]);
  else
    return double(v);
}

template <class V>
void set_component(V& v, int c, double x) {
  using E = typename openvdb::VecTraits<V>::ElementType;
  if constexpr (std::is_integral_v<V>)  // integer grids: the nearest integer, as vdb_lod keeps them
    v = V(std::clamp(std::round(x), double(std::numeric_limits<V>::lowest()),
                     std::nextafter(double(std::numeric_limits<V>::max()), 0.0)));
  else if constexpr (openvdb::VecTraits<V>::IsVec)
    v[c] = E(x);
  else
    v = V(x);
}

// Coarse cells are the 8^3 leaves of the coarse level; a cell reads the 16^3 fine voxels under it
// plus `margin` on each side (the filter radius, at least 1 for the one-voxel dilation).
constexpr int kCell = 8;

// Per-component value range of the input (all values and the background): levels are clamped to
// it, as the low pass's overshoot must not invent values the grid never had.
template <class V>
struct Range {
  std::array<double, 3> lo{}, hi{};
  V clamp(V v) const {
    for (int c = 0; c < kComponents<V>; ++c)
      set_component(v, c, std::clamp(component(v, c), lo[std::size_t(c)], hi[std::size_t(c)]));
    return v;
  }
};

template <class TreeT>
Range<typename TreeT::ValueType> value_range(const TreeT& tree) {
  using V = typename TreeT::ValueType;
  Range<V> r;
  for (int c = 0; c < kComponents<V>; ++c)
    r.lo[std::size_t(c)] = r.hi[std::size_t(c)] = component(tree.background(), c);
  const auto take = [&](const V& v) {
    for (int c = 0; c < kComponents<V>; ++c) {
      r.lo[std::size_t(c)] = std::min(r.lo[std::size_t(c)], component(v, c));
      r.hi[std::size_t(c)] = std::max(r.hi[std::size_t(c)], component(v, c));
    }
  };
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf)
    for (openvdb::Index n = 0; n < TreeT::LeafNodeType::SIZE; ++n) take(leaf->getValue(n));
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only
  for (; it; ++it) take(*it);
  return r;
}

// One halving step: the coarse working tree (the normalised low band, inactive voxels included,
// from which the next level is made) and the output level (clamped, inactive voxels set to the
// background, or to +-background by sign for a level set).
template <class TreeT>
class Halving {
 public:
  using V = typename TreeT::ValueType;
  using LeafT = typename TreeT::LeafNodeType;
  static constexpr int kC = kComponents<V>;

  // Symmetric edges (a dense grid): beyond the data's box lies its mirror image. At the fine
  // level, `mirror` is the data's box, `known` where the fine values are known (the box at level
  // 0, then the extension computed by the previous level); coarse cells cover `region` only.
  struct Edges {
    CoordBBox mirror, known, region;
  };

  Halving(const TreeT& fine, const LowPass& h, const Edges* edges, bool level_set, const Range<V>& range)
      : fine_(fine),
        h_(h),
        margin_(std::max(h.radius, 1)),
        n_(2 * kCell + 2 * margin_),
        symmetric_(edges != nullptr),
        edges_(edges ? *edges : Edges{}),
        level_set_(level_set),
        range_(range),
        scale_(1.0 / (h.gain * h.gain * h.gain)) {}

  // Builds work and out; throws when more than max_leaves cells are needed.
  void run(TreeT& work, TreeT& out, std::size_t max_leaves, const std::string& what) {
    std::vector<Coord> cells = collect_cells(max_leaves, what);
    for (const Fill& f : fills_) {
      work.fill(f.box, f.value, f.active);
      out.fill(f.box, output_value(f.value, f.active), f.active);
    }
    std::vector<Result> results(cells.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 16), [&](const auto& r) {
      Scratch s(n_);
      openvdb::tree::ValueAccessor<const TreeT> acc(fine_);
      for (std::size_t i = r.begin(); i != r.end(); ++i) results[i] = compute(cells[i], acc, s);
    });
    for (std::size_t i = 0; i < cells.size(); ++i) {
      Result& res = results[i];
      if (res.work) {
        work.addLeaf(res.work.release());
        out.addLeaf(res.out.release());
      } else {
        work.addTile(1, cells[i], res.value, res.active);
        out.addTile(1, cells[i], output_value(res.value, res.active), res.active);
      }
    }
    openvdb::tools::prune(out);
  }

 private:
  struct Fill {
    CoordBBox box;
    V value;
    bool active;
  };
  struct Result {
    std::unique_ptr<LeafT> work, out;  // null: the cell is uniform (value, active)
    V value{};
    bool active = false;
  };
  struct Scratch {
    explicit Scratch(int n)
        : on(std::size_t(n * n * n)), on1(std::size_t(kCell * n * n)), on2(std::size_t(kCell * kCell * n)) {
      for (int c = 0; c < kC; ++c) in[std::size_t(c)].resize(std::size_t(n * n * n));
      x.resize(std::size_t(kCell * n * n));
      y.resize(std::size_t(kCell * kCell * n));
    }
    std::array<std::vector<double>, 3> in;
    std::vector<std::uint8_t> on, on1, on2;
    std::vector<double> x, y;
  };

  V output_value(const V& v, bool active) const {
    if (active) return range_.clamp(v);
    if (!level_set_) return fine_.background();
    const double bg = std::abs(component(fine_.background(), 0));
    V r{};
    set_component(r, 0, component(v, 0) < 0 ? -bg : bg);
    return r;
  }

  bool matters(const V& v, bool active) const { return active || !(v == fine_.background()); }

  // Coarse cells within reach of the fine leaves and of the tiles that are active or not the
  // background; the interiors of large tiles go to fills_ instead of cells.
  std::vector<Coord> collect_cells(std::size_t max_leaves, const std::string& what) {
    std::vector<Coord> cells;
    const auto settle = [&] {
      std::sort(cells.begin(), cells.end());
      cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
      if (cells.size() > max_leaves)
        throw std::runtime_error(what + " needs " + std::to_string(cells.size()) +
                                 " coarse leaves, more than the limit of " + std::to_string(max_leaves));
    };
    const auto add = [&](const CoordBBox& fine, const CoordBBox* interior) {
      Coord lo, hi;
      for (int a = 0; a < 3; ++a) {
        lo[a] = ceil_div(fine.min()[a] - margin_, 2) & ~(kCell - 1);
        hi[a] = floor_div(fine.max()[a] + margin_, 2);
      }
      for (int z = lo.z(); z <= hi.z(); z += kCell)
        for (int y = lo.y(); y <= hi.y(); y += kCell)
          for (int x = lo.x(); x <= hi.x(); x += kCell) {
            const Coord c(x, y, z);
            if (interior && interior->isInside(CoordBBox(c, c.offsetBy(kCell - 1)))) continue;
            cells.push_back(c);
            if (cells.size() > 8 * max_leaves) settle();
          }
    };
    if (symmetric_) {  // a dense grid: every cell of the region (its box and the extension)
      const CoordBBox& r = edges_.region;
      for (int z = r.min().z() & ~(kCell - 1); z <= r.max().z(); z += kCell)
        for (int y = r.min().y() & ~(kCell - 1); y <= r.max().y(); y += kCell)
          for (int x = r.min().x() & ~(kCell - 1); x <= r.max().x(); x += kCell) {
            cells.emplace_back(x, y, z);
            if (cells.size() > max_leaves) settle();
          }
      settle();
      return cells;
    }
    for (auto leaf = fine_.cbeginLeaf(); leaf; ++leaf) add(leaf->getNodeBoundingBox(), nullptr);
    auto it = fine_.cbeginValueAll();
    it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only
    for (; it; ++it) {
      if (!matters(*it, it.isValueOn())) continue;
      CoordBBox tile;
      it.getBoundingBox(tile);
      CoordBBox interior(Coord(ceil_div(tile.min().x() + margin_, 2), ceil_div(tile.min().y() + margin_, 2),
                               ceil_div(tile.min().z() + margin_, 2)),
                         Coord(floor_div(tile.max().x() - margin_, 2), floor_div(tile.max().y() - margin_, 2),
                               floor_div(tile.max().z() - margin_, 2)));
      // A big tile's interior is its value at the coarse level too (reads stay inside the tile).
      const bool fill = tile.dim().x() >= 8 * kCell && !interior.empty();
      if (fill) fills_.push_back({interior, *it, it.isValueOn()});
      add(tile, fill ? &interior : nullptr);
    }
    settle();
    return cells;
  }

  // Reads the fine voxels under cell c into s.in / s.on; returns true when they are all equal
  // (value and active state), then also in `first`.
  bool gather(const Coord& c, openvdb::tree::ValueAccessor<const TreeT>& acc, Scratch& s, V& first,
              bool& first_on) const {
    const Coord start(2 * c.x() - margin_, 2 * c.y() - margin_, 2 * c.z() - margin_);
    const Coord end = start.offsetBy(n_ - 1);
    bool uniform = true, have = false;
    const auto record = [&](std::size_t i, const V& v, bool on) {
      for (int k = 0; k < kC; ++k) s.in[std::size_t(k)][i] = component(v, k);
      s.on[i] = on ? 1 : 0;
      if (!have) {
        first = v, first_on = on, have = true;
      } else if (uniform && (on != first_on || !(v == first))) {
        uniform = false;
      }
    };
    const auto index = [&](int x, int y, int z) {
      return std::size_t(x - start.x()) +
             std::size_t(n_) * (std::size_t(y - start.y()) + std::size_t(n_) * std::size_t(z - start.z()));
    };
    if (symmetric_ && !edges_.known.isInside(CoordBBox(start, end))) {
      // Per axis: the mirrored coordinate and whether the coordinate itself is known.
      const CoordBBox& b = edges_.mirror;
      std::array<std::vector<int>, 3> mirrored;
      std::array<std::vector<char>, 3> known;
      for (int a = 0; a < 3; ++a)
        for (int i = start[a]; i <= end[a]; ++i) {
          mirrored[std::size_t(a)].push_back(reflect_into(i, b.min()[a], b.max()[a]));
          known[std::size_t(a)].push_back(i >= edges_.known.min()[a] && i <= edges_.known.max()[a]);
        }
      for (int k = 0; k < n_; ++k)
        for (int j = 0; j < n_; ++j)
          for (int i = 0; i < n_; ++i) {
            const std::size_t at =
                std::size_t(i) + std::size_t(n_) * (std::size_t(j) + std::size_t(n_) * std::size_t(k));
            const Coord p = start.offsetBy(i, j, k);
            if (known[0][std::size_t(i)] && known[1][std::size_t(j)] && known[2][std::size_t(k)]) {
              record(at, acc.getValue(p), acc.isValueOn(p));
              continue;
            }
            // Beyond what is known: the mirror image, inactive (the topology is not extended).
            const Coord q(mirrored[0][std::size_t(i)], mirrored[1][std::size_t(j)],
                          mirrored[2][std::size_t(k)]);
            record(at, acc.getValue(q), false);
          }
      return uniform;
    }
    for (int bz = start.z() & ~7; bz <= end.z(); bz += 8)
      for (int by = start.y() & ~7; by <= end.y(); by += 8)
        for (int bx = start.x() & ~7; bx <= end.x(); bx += 8) {
          const Coord o(bx, by, bz);
          const Coord lo = Coord::maxComponent(o, start), hi = Coord::minComponent(o.offsetBy(7), end);
          if (const LeafT* leaf = acc.probeConstLeaf(o)) {
            for (int z = lo.z(); z <= hi.z(); ++z)
              for (int y = lo.y(); y <= hi.y(); ++y)
                for (int x = lo.x(); x <= hi.x(); ++x) {
                  const openvdb::Index off = LeafT::coordToOffset(Coord(x, y, z));
                  record(index(x, y, z), leaf->getValue(off), leaf->isValueOn(off));
                }
          } else {
            V v;
            const bool on = acc.probeValue(o, v);
            for (int z = lo.z(); z <= hi.z(); ++z)
              for (int y = lo.y(); y <= hi.y(); ++y)
                for (int x = lo.x(); x <= hi.x(); ++x) record(index(x, y, z), v, on);
          }
        }
    return uniform;
  }

  // Coarse voxel j of the cell: the low pass centred on fine voxel 2j (at offset margin_), along x,
  // then y, then z; active when a fine voxel of [2j-1, 2j+1]^3 is.
  Result compute(const Coord& c, openvdb::tree::ValueAccessor<const TreeT>& acc, Scratch& s) const {
    Result res;
    if (gather(c, acc, s, res.value, res.active)) return res;
    const int n = n_, m = margin_, r = h_.radius;
    const double* taps = h_.taps.data() + r;  // taps[d] for d in [-r, r]
    std::array<std::array<double, kCell * kCell * kCell>, 3> coarse{};
    for (int k = 0; k < kC; ++k) {
      const std::vector<double>& in = s.in[std::size_t(k)];
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < kCell; ++x) {
            const double* line = in.data() + std::size_t(2 * x + m) +
                                 std::size_t(n) * (std::size_t(y) + std::size_t(n) * std::size_t(z));
            double sum = 0.0;
            for (int d = -r; d <= r; ++d) sum += taps[d] * line[d];
            s.x[std::size_t(x + kCell * (y + n * z))] = sum;
          }
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < kCell; ++y)
          for (int x = 0; x < kCell; ++x) {
            double sum = 0.0;
            for (int d = -r; d <= r; ++d)
              sum += taps[d] * s.x[std::size_t(x + kCell * (2 * y + m + d + n * z))];
            s.y[std::size_t(x + kCell * (y + kCell * z))] = sum;
          }
      for (int z = 0; z < kCell; ++z)
        for (int y = 0; y < kCell; ++y)
          for (int x = 0; x < kCell; ++x) {
            double sum = 0.0;
            for (int d = -r; d <= r; ++d)
              sum += taps[d] * s.y[std::size_t(x + kCell * (y + kCell * (2 * z + m + d)))];
            coarse[std::size_t(k)][std::size_t(x + kCell * (y + kCell * z))] = sum * scale_;
          }
    }
    // Dilation by one fine voxel, then the even voxels: the separable OR of three taps.
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < kCell; ++x) {
          const std::size_t i =
              std::size_t(2 * x + m) + std::size_t(n) * (std::size_t(y) + std::size_t(n) * std::size_t(z));
          s.on1[std::size_t(x + kCell * (y + n * z))] = s.on[i - 1] | s.on[i] | s.on[i + 1];
        }
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < kCell; ++y)
        for (int x = 0; x < kCell; ++x) {
          const std::size_t i = std::size_t(x + kCell * (2 * y + m + n * z));
          s.on2[std::size_t(x + kCell * (y + kCell * z))] = s.on1[i - kCell] | s.on1[i] | s.on1[i + kCell];
        }
    res.work = std::make_unique<LeafT>(c, fine_.background(), false);
    res.out = std::make_unique<LeafT>(c, fine_.background(), false);
    for (int z = 0; z < kCell; ++z)
      for (int y = 0; y < kCell; ++y)
        for (int x = 0; x < kCell; ++x) {
          const std::size_t j = std::size_t(x + kCell * y);
          const std::size_t plane = std::size_t(kCell * kCell);
          const std::size_t zi = std::size_t(2 * z + m);
          const bool on =
              (s.on2[j + plane * (zi - 1)] | s.on2[j + plane * zi] | s.on2[j + plane * (zi + 1)]) != 0;
          V v{};
          for (int k = 0; k < kC; ++k)
            set_component(v, k, coarse[std::size_t(k)][j + plane * std::size_t(z)]);
          const openvdb::Index off = LeafT::coordToOffset(c.offsetBy(x, y, z));
          res.work->setValueOnly(off, v);
          res.work->setActiveState(off, on);
          res.out->setValueOnly(off, output_value(v, on));
          res.out->setActiveState(off, on);
        }
    return res;
  }

  const TreeT& fine_;
  const LowPass& h_;
  const int margin_, n_;
  const bool symmetric_;
  const Edges edges_;
  const bool level_set_;
  const Range<V> range_;
  const double scale_;
  std::vector<Fill> fills_;
};

// --edge auto: a grid is dense (its data ends at its box) when more than this share of the voxels
// on the six faces of its active box are active and not the background; voxels inside do not
// matter. 90% leaves room for some background values on a dense field's faces, while sparse data
// meets its box in patches (5% and 11% of the faces for testimages/ sphere_ls and dodeca_fog).
constexpr double kDenseFaceFill = 0.9;

// Whether more than kDenseFaceFill of the voxels on the faces of `box` are active and not the background.
template <class TreeT>
bool dense_at_faces(const TreeT& tree, const CoordBBox& box) {
  CoordBBox inner = box;
  inner.expand(-1);  // empty when the box is at most 2 voxels thick: then every voxel is on a face
  const auto volume = [](const CoordBBox& b) {
    return b.empty() ? std::uint64_t(0) : std::uint64_t(b.volume());
  };
  const auto on_faces = [&](CoordBBox b) {  // voxels of b (inside box) outside the inner box
    const std::uint64_t all = volume(b);
    b.intersect(inner);
    return all - volume(b);
  };
  std::uint64_t filled = 0;
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
    if (inner.isInside(leaf->getNodeBoundingBox())) continue;  // no face voxel: skip the interior fast
    for (auto v = leaf->cbeginValueOn(); v; ++v)
      if (!inner.isInside(v.getCoord()) && *v != tree.background()) ++filled;
  }
  auto tile = tree.cbeginValueOn();
  tile.setMaxDepth(tile.getLeafDepth() - 1);  // active tiles only
  for (; tile; ++tile)
    if (*tile != tree.background()) filled += on_faces(tile.getBoundingBox());
  return double(filled) > kDenseFaceFill * double(on_faces(box));
}

// The grid of level k: the input's name, class, metadata and transform pre-scaled by 2^k (coarse
// voxel i lies where fine voxel 2^k i lies), plus vdb_lod's MultiResGrid metadata.
template <class GridT>
openvdb::GridBase::Ptr level_grid(const GridT& in, typename GridT::TreeType::Ptr tree, int k, int top) {
  typename GridT::Ptr g = GridT::create(tree);
  for (auto it = in.beginMeta(); it != in.endMeta(); ++it)
    if (it->second && it->first.rfind("file_", 0) != 0) g->insertMeta(it->first, *it->second);
  g->setName(in.getName() + "_level_" + std::to_string(k));
  g->setTransform(in.transform().copy());
  g->transform().preScale(std::ldexp(1.0, k));
  g->insertMeta("MultiResGrid_Level", openvdb::FloatMetadata(float(k)));
  g->insertMeta("MultiResGrid_Levels", openvdb::Int64Metadata(top + 1));
  return g;
}

CoordBBox halve_box(const CoordBBox& b) {
  Coord lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = ceil_div(b.min()[a], 2);
    hi[a] = std::max(lo[a], floor_div(b.max()[a], 2));
  }
  return {lo, hi};
}

template <class GridT>
openvdb::GridPtrVec lod_typed(GridT& in, const LowPass& h, const std::vector<int>& levels, LodEdge edge,
                              std::size_t max_leaves) {
  using TreeT = typename GridT::TreeType;
  const int top = levels.back();
  const CoordBBox box = in.evalActiveVoxelBoundingBox();
  const bool dense = !box.empty() && dense_at_faces(in.tree(), box);
  const bool symmetric =
      !box.empty() && (edge == LodEdge::symmetric || (edge == LodEdge::automatic && dense));
  const bool level_set =
      in.getGridClass() == openvdb::GRID_LEVEL_SET && kComponents<typename GridT::ValueType> == 1;
  const auto range = value_range(in.tree());
  // Symmetric edges: level k is computed over its box widened by reach[k] coarse voxels, what the
  // active voxels of the levels above need (1 at the top, 2 reach[k+1] + radius + 2 below), but at
  // most 2 radius + 4 (reads beyond mirror at the box: near exact, the mirror image of the low band
  // being the low band of the mirror image up to half a sample; keeps --levels 8 on a dense grid
  // from computing a box many times the grid's).
  std::vector<int> reach(std::size_t(top + 1), 1);
  std::vector<CoordBBox> boxes{box};
  for (int k = 1; k <= top; ++k) boxes.push_back(halve_box(boxes.back()));
  for (int k = top - 1; k >= 1; --k)
    reach[std::size_t(k)] = std::min(2 * reach[std::size_t(k + 1)] + h.radius + 2, 2 * h.radius + 4);
  typename Halving<TreeT>::Edges edges{box, box, {}};
  openvdb::GridPtrVec out;
  typename TreeT::ConstPtr work = in.constTreePtr();
  if (levels.front() == 0) out.push_back(level_grid(in, in.treePtr(), 0, top));
  for (int k = 1; k <= top; ++k) {
    auto next = std::make_shared<TreeT>(in.background());
    auto shown = std::make_shared<TreeT>(in.background());
    edges.region = boxes[std::size_t(k)].expandBy(reach[std::size_t(k)]);
    Halving<TreeT>(*work, h, symmetric ? &edges : nullptr, level_set, range)
        .run(*next, *shown, max_leaves, "grid '" + in.getName() + "' level " + std::to_string(k));
    edges.mirror = boxes[std::size_t(k)];
    edges.known = edges.region;
    work = next;
    if (std::find(levels.begin(), levels.end(), k) != levels.end())
      out.push_back(level_grid(in, shown, k, top));
  }
  return out;
}

}  // namespace

bool has_lod(const openvdb::GridBase& grid) {
  return grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>() ||
         grid.isType<openvdb::Vec3SGrid>() || grid.isType<openvdb::Vec3DGrid>() ||
         grid.isType<openvdb::Int32Grid>() || grid.isType<openvdb::Int64Grid>();
}

openvdb::GridPtrVec level_of_detail(const openvdb::GridBase::Ptr& grid, const LowPass& low_pass,
                                    const std::vector<int>& levels, LodEdge edge, std::size_t max_leaves) {
  if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(grid))
    return lod_typed(*f, low_pass, levels, edge, max_leaves);
  if (auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(grid))
    return lod_typed(*d, low_pass, levels, edge, max_leaves);
  if (auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid))
    return lod_typed(*v, low_pass, levels, edge, max_leaves);
  if (auto w = openvdb::gridPtrCast<openvdb::Vec3DGrid>(grid))
    return lod_typed(*w, low_pass, levels, edge, max_leaves);
  if (auto i = openvdb::gridPtrCast<openvdb::Int32Grid>(grid))
    return lod_typed(*i, low_pass, levels, edge, max_leaves);
  if (auto l = openvdb::gridPtrCast<openvdb::Int64Grid>(grid))
    return lod_typed(*l, low_pass, levels, edge, max_leaves);
  throw std::invalid_argument("level_of_detail: grid '" + grid->getName() + "' has no pyramid (type " +
                              grid->valueType() + ")");
}

}  // namespace pupwave::cli
