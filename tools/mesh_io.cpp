#include "tools/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "tools/atomic_file.h"
#include "tools/mesh_io_text.h"

namespace pupwave::cli {

using sqrt3::Face;
using sqrt3::TriMesh;
using sqrt3::Vec3;
using namespace mesh_text;

namespace {

std::uint32_t vertex_index(std::int64_t i, std::size_t count, const Lines& where) {
  if (i < 0 || std::uint64_t(i) >= count) {
    where.fail("vertex index " + std::to_string(i) + " out of range (" + std::to_string(count) +
               " vertices)");
  }
  return std::uint32_t(i);
}

void require_triangle(std::size_t n, const Lines& where) {
  if (n != 3) {
    where.fail("face with " + std::to_string(n) + " vertices; the sqrt(3) multiresolution needs triangles");
  }
}

// OBJ face corner "v", "v/t", "v//n" or "v/t/n": only plain vertex indices are accepted, since
// texture and normal indices would be lost. Negative indices count from the end (OBJ rule).
std::uint32_t obj_corner(std::string_view t, std::size_t count, const Lines& where) {
  if (t.find('/') != std::string_view::npos) {
    where.fail("face corner '" + std::string(t) +
               "' has texture or normal indices, which pupwave does not keep");
  }
  const std::int64_t i = to_int(t, where);
  if (i == 0) where.fail("OBJ vertex indices start at 1");
  return vertex_index(i > 0 ? i - 1 : std::int64_t(count) + i, count, where);
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string e = path.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

}  // namespace

MeshFormat mesh_format(const std::filesystem::path& path) {
  const std::string e = lower_extension(path);
  if (e == ".obj") return MeshFormat::obj;
  if (e == ".off") return MeshFormat::off;
  if (e == ".ply") return MeshFormat::ply;
  throw std::runtime_error(path.string() + ": unknown mesh format '" + e + "' (valid: .obj, .off, .ply)");
}

TriMesh parse_obj(std::string_view text, const std::string& name) {
  TriMesh m;
  Lines lines(text, name);
  for (std::string_view line; lines.next(line);) {
    const std::vector<std::string_view> t = tokens(line);
    if (t.empty() || t[0][0] == '#') continue;
    if (t[0] == "v") {
      if (t.size() != 4) lines.fail("expected 'v x y z' (no w or vertex colours)");
      if (m.points.size() >= kMaxMeshVertices) lines.fail("too many vertices");
      m.points.push_back({to_double(t[1], lines), to_double(t[2], lines), to_double(t[3], lines)});
    } else if (t[0] == "f") {
      require_triangle(t.size() - 1, lines);
      if (m.faces.size() >= kMaxMeshFaces) lines.fail("too many faces");
      m.faces.push_back({obj_corner(t[1], m.points.size(), lines), obj_corner(t[2], m.points.size(), lines),
                         obj_corner(t[3], m.points.size(), lines)});
    } else {
      lines.fail("unsupported OBJ statement '" + std::string(t[0]) +
                 "' (pupwave reads v and f only and does not drop other data silently)");
    }
  }
  return m;
}

// Next non-empty, non-comment line's tokens; fails at the end of the file.
static std::vector<std::string_view> off_tokens(Lines& lines, const char* what) {
  for (std::string_view line; lines.next(line);) {
    const std::size_t hash = line.find('#');
    std::vector<std::string_view> t = tokens(line.substr(0, hash));
    if (!t.empty()) return t;
  }
  lines.fail(std::string("file ends before ") + what);
}

TriMesh parse_off(std::string_view text, const std::string& name) {
  Lines lines(text, name);
  std::vector<std::string_view> t = off_tokens(lines, "the OFF header");
  if (t[0] != "OFF") lines.fail("not an OFF file (expected 'OFF', got '" + std::string(t[0]) + "')");
  t.erase(t.begin());
  if (t.empty()) t = off_tokens(lines, "the vertex and face counts");
  if (t.size() != 3) lines.fail("expected 'vertices faces edges'");
  const std::int64_t nv = to_int(t[0], lines), nf = to_int(t[1], lines);
  if (nv < 0 || nf < 0 || std::size_t(nv) > kMaxMeshVertices || std::size_t(nf) > kMaxMeshFaces) {
    lines.fail("vertex or face count out of range");
  }
  // Each vertex and face needs a line of at least 6 bytes: a bound before allocating.
  if (std::size_t(nv + nf) > text.size() / 6 + 1) lines.fail("counts larger than the file can hold");
  TriMesh m;
  m.points.reserve(std::size_t(nv));
  for (std::int64_t i = 0; i < nv; ++i) {
    t = off_tokens(lines, "all vertices are read");
    if (t.size() != 3) lines.fail("expected 'x y z' (no vertex colours or normals)");
    m.points.push_back({to_double(t[0], lines), to_double(t[1], lines), to_double(t[2], lines)});
  }
  m.faces.reserve(std::size_t(nf));
  for (std::int64_t i = 0; i < nf; ++i) {
    t = off_tokens(lines, "all faces are read");
    const std::int64_t n = to_int(t[0], lines);
    if (n < 0 || std::size_t(n) + 1 > t.size()) lines.fail("face lists fewer indices than its count");
    require_triangle(std::size_t(n), lines);
    if (t.size() != 4) lines.fail("face has extra values (colours), which pupwave does not keep");
    m.faces.push_back({vertex_index(to_int(t[1], lines), m.points.size(), lines),
                       vertex_index(to_int(t[2], lines), m.points.size(), lines),
                       vertex_index(to_int(t[3], lines), m.points.size(), lines)});
  }
  for (std::string_view line; lines.next(line);) {
    if (!tokens(line.substr(0, line.find('#'))).empty()) lines.fail("data after the last face");
  }
  return m;
}

TriMesh read_mesh(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format(path);
  const std::vector<std::uint8_t> bytes = read_file_bytes(path, std::uintmax_t(1) << 32);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const std::string name = path.string();
  switch (format) {
    case MeshFormat::obj: return parse_obj(text, name);
    case MeshFormat::off: return parse_off(text, name);
    case MeshFormat::ply: return parse_ply(text, name);
  }
  throw std::logic_error("read_mesh: format");
}

namespace {

void write_text(const TriMesh& m, MeshFormat format, std::ostream& out) {
  char buf[96];
  if (format == MeshFormat::off) out << "OFF\n" << m.points.size() << ' ' << m.faces.size() << " 0\n";
  for (const Vec3& p : m.points) {
    std::snprintf(buf, sizeof buf, "%s%.17g %.17g %.17g\n", format == MeshFormat::obj ? "v " : "", p.x(),
                  p.y(), p.z());
    out << buf;
  }
  const int base = format == MeshFormat::obj ? 1 : 0;
  for (const Face& f : m.faces) {
    out << (format == MeshFormat::obj ? "f " : "3 ") << f[0] + base << ' ' << f[1] + base << ' '
        << f[2] + base << '\n';
  }
}

}  // namespace

void write_ply_binary(const TriMesh& m, std::ostream& out);  // mesh_io_ply.cpp

void write_mesh(const TriMesh& m, const std::filesystem::path& path) {
  const MeshFormat format = mesh_format(path);
  write_output(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (format == MeshFormat::ply) {
      write_ply_binary(m, out);
    } else {
      write_text(m, format, out);
    }
    out.close();
    if (!out) throw_write_error(temp);
  });
}

}  // namespace pupwave::cli
