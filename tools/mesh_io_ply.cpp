// PLY reader (ASCII, binary little and big endian) and binary writer for triangle meshes.
// Accepted: element vertex with exactly the properties x, y, z; element face with one list
// property vertex_indices (or vertex_index); other elements only when empty.
#include <array>
#include <bit>
#include <cstring>
#include <map>
#include <ostream>

#include "tools/mesh_io.h"
#include "tools/mesh_io_text.h"

namespace pupwave::cli {

using sqrt3::Face;
using sqrt3::TriMesh;
using namespace mesh_text;

namespace {

enum class Encoding { ascii, little, big };

const std::map<std::string_view, int>& type_sizes() {
  static const std::map<std::string_view, int> sizes = {
      {"char", 1},   {"int8", 1},    {"uchar", 1},  {"uint8", 1},  {"short", 2}, {"int16", 2},
      {"ushort", 2}, {"uint16", 2},  {"int", 4},    {"int32", 4},  {"uint", 4},  {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  return sizes;
}

struct Property {
  std::string name, type, count_type;  // count_type non-empty: a list
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
};

void check_type(const std::string& type, const Lines& where) {
  if (!type_sizes().count(type)) where.fail("unknown PLY type '" + type + "'");
}

Header parse_header(Lines& lines) {
  Header h;
  std::string_view line;
  if (!lines.next(line) || line != "ply") lines.fail("not a PLY file (first line must be 'ply')");
  bool have_format = false;
  while (true) {
    if (!lines.next(line)) lines.fail("file ends inside the PLY header");
    const std::vector<std::string_view> t = tokens(line);
    if (t.empty()) continue;
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() != 3 || t[2] != "1.0") lines.fail("expected 'format TYPE 1.0'");
      if (t[1] == "ascii")
        h.encoding = Encoding::ascii;
      else if (t[1] == "binary_little_endian")
        h.encoding = Encoding::little;
      else if (t[1] == "binary_big_endian")
        h.encoding = Encoding::big;
      else
        lines.fail("unknown PLY format '" + std::string(t[1]) + "'");
      have_format = true;
    } else if (t[0] == "element") {
      if (t.size() != 3) lines.fail("expected 'element NAME COUNT'");
      const std::int64_t n = to_int(t[2], lines);
      if (n < 0 || std::size_t(n) > kMaxMeshFaces) lines.fail("element count out of range");
      h.elements.push_back({std::string(t[1]), n, {}});
    } else if (t[0] == "property") {
      if (h.elements.empty()) lines.fail("property before any element");
      Property p;
      if (t.size() == 5 && t[1] == "list") {
        p = {std::string(t[4]), std::string(t[3]), std::string(t[2])};
        check_type(p.count_type, lines);
      } else if (t.size() == 3) {
        p = {std::string(t[2]), std::string(t[1]), ""};
      } else {
        lines.fail("malformed property line");
      }
      check_type(p.type, lines);
      h.elements.back().properties.push_back(p);
    } else {
      lines.fail("unknown PLY header line '" + std::string(t[0]) + "'");
    }
  }
  if (!have_format) lines.fail("PLY header has no format line");
  return h;
}

// Checks the elements are what a triangle mesh holds; returns the x, y, z property order.
std::array<int, 3> check_elements(const Header& h, const Lines& where) {
  std::array<int, 3> xyz = {-1, -1, -1};
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      if (e.properties.size() != 3)
        where.fail("vertex element must have exactly x, y, z (normals, colours are not kept)");
      for (int i = 0; i < 3; ++i) {
        const Property& p = e.properties[std::size_t(i)];
        const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
        if (axis < 0 || !p.count_type.empty() || xyz[std::size_t(axis)] >= 0)
          where.fail("vertex properties must be x, y, z");
        xyz[std::size_t(axis)] = i;
      }
      if (std::size_t(e.count) > kMaxMeshVertices) where.fail("too many vertices");
    } else if (e.name == "face") {
      if (e.properties.size() != 1 || e.properties[0].count_type.empty() ||
          (e.properties[0].name != "vertex_indices" && e.properties[0].name != "vertex_index")) {
        where.fail("face element must have exactly one list property vertex_indices (colours are not kept)");
      }
    } else if (e.count > 0) {
      where.fail("PLY element '" + e.name + "' is not supported (pupwave keeps vertices and faces only)");
    }
  }
  if (xyz[0] < 0) where.fail("PLY file has no vertex element");
  return xyz;
}

// Reads scalars from binary data, bounds checked.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, bool big, const Lines& where) : data_(data), big_(big), where_(where) {}
  double read(const std::string& type) {
    const int n = type_sizes().at(type);
    if (data_.size() - pos_ < std::size_t(n)) where_.fail("binary PLY data ends early");
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, std::size_t(n));
    pos_ += std::size_t(n);
    if (big_ != (std::endian::native == std::endian::big)) std::reverse(b, b + n);
    return decode(type, b);
  }
  bool at_end() const { return pos_ == data_.size(); }

 private:
  static double decode(const std::string& type, const unsigned char* b) {
    auto as = [&](auto v) {
      std::memcpy(&v, b, sizeof v);
      return double(v);
    };
    if (type == "char" || type == "int8") return as(std::int8_t());
    if (type == "uchar" || type == "uint8") return as(std::uint8_t());
    if (type == "short" || type == "int16") return as(std::int16_t());
    if (type == "ushort" || type == "uint16") return as(std::uint16_t());
    if (type == "int" || type == "int32") return as(std::int32_t());
    if (type == "uint" || type == "uint32") return as(std::uint32_t());
    if (type == "float" || type == "float32") return as(float());
    return as(double());
  }
  std::string_view data_;
  bool big_;
  const Lines& where_;
  std::size_t pos_ = 0;
};

// One element's rows as numbers (a list row is its count then its entries).
class RowSource {
 public:
  RowSource(Lines& lines, BinaryCursor* bin) : lines_(lines), bin_(bin) {}
  std::vector<double> row(const Element& e) {
    std::vector<double> v;
    if (bin_) {
      for (const Property& p : e.properties) {
        if (p.count_type.empty()) {
          v.push_back(bin_->read(p.type));
          continue;
        }
        const double n = bin_->read(p.count_type);
        if (n < 0 || n > 64) lines_.fail("list with " + std::to_string(n) + " entries");
        v.push_back(n);
        for (int i = 0; i < int(n); ++i) v.push_back(bin_->read(p.type));
      }
      return v;
    }
    std::string_view line;
    std::vector<std::string_view> t;
    while (t.empty()) {
      if (!lines_.next(line)) lines_.fail("file ends before all PLY elements are read");
      t = tokens(line);
    }
    for (std::string_view s : t) v.push_back(to_double(s, lines_));
    return v;
  }

 private:
  Lines& lines_;
  BinaryCursor* bin_;
};

void read_face(const std::vector<double>& v, TriMesh& m, const Lines& where) {
  if (v.empty() || v[0] != 3.0) {
    where.fail("face with " + std::to_string(v.empty() ? 0 : v[0]) +
               " vertices; the sqrt(3) multiresolution needs triangles");
  }
  if (v.size() != 4) where.fail("face row has " + std::to_string(v.size()) + " values, expected 4");
  Face f{};
  for (int i = 0; i < 3; ++i) {
    const double x = v[std::size_t(i) + 1];
    if (x < 0 || x != std::floor(x) || x >= double(m.points.size())) where.fail("vertex index out of range");
    f[std::size_t(i)] = std::uint32_t(x);
  }
  m.faces.push_back(f);
}

}  // namespace

TriMesh parse_ply(std::string_view bytes, const std::string& name) {
  Lines lines(bytes, name);
  const Header h = parse_header(lines);
  const std::array<int, 3> xyz = check_elements(h, lines);
  BinaryCursor cursor(bytes.substr(lines.position() > bytes.size() ? bytes.size() : lines.position()),
                      h.encoding == Encoding::big, lines);
  RowSource rows(lines, h.encoding == Encoding::ascii ? nullptr : &cursor);
  TriMesh m;
  const std::size_t budget = bytes.size();  // every row takes at least one byte
  for (const Element& e : h.elements) {
    if (std::size_t(e.count) > budget) lines.fail("element count larger than the file can hold");
    for (std::int64_t i = 0; i < e.count; ++i) {
      const std::vector<double> v = rows.row(e);
      if (e.name == "vertex") {
        if (v.size() != 3) lines.fail("vertex row must have 3 values");
        for (double x : v)
          if (!std::isfinite(x)) lines.fail("vertex coordinate is not finite");
        m.points.push_back({v[std::size_t(xyz[0])], v[std::size_t(xyz[1])], v[std::size_t(xyz[2])]});
      } else if (e.name == "face") {
        read_face(v, m, lines);
      }
    }
  }
  if (h.encoding != Encoding::ascii && !cursor.at_end()) lines.fail("data after the last PLY element");
  return m;
}

// Binary little-endian PLY with double coordinates: exact round trip.
void write_ply_binary(const TriMesh& m, std::ostream& out) {
  out << "ply\nformat binary_little_endian 1.0\ncomment written by pupwave\nelement vertex "
      << m.points.size() << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << m.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](auto v) {
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    if (std::endian::native == std::endian::big) std::reverse(b, b + sizeof v);
    out.write(b, sizeof v);
  };
  for (const auto& p : m.points) {
    put(p.x());
    put(p.y());
    put(p.z());
  }
  for (const Face& f : m.faces) {
    put(std::uint8_t(3));
    for (std::uint32_t v : f) put(std::int32_t(v));
  }
}

}  // namespace pupwave::cli
