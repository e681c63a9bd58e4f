#pragma once
// Triangle mesh files <-> sqrt3::TriMesh: OBJ, OFF and PLY (ASCII and binary), our own small
// readers with the validation standard of the image readers: every count, index and number
// checked, sizes bounded, and anything the mesh cannot hold (polygons, normals, colours,
// texture coordinates, extra properties) refused with a message rather than dropped.

#include <filesystem>
#include <string>

#include "transforms/sqrt3/mesh.h"

namespace pupwave::cli {

enum class MeshFormat { obj, off, ply };

// Largest mesh accepted on read, so a hostile header cannot make us allocate without bound.
inline constexpr std::size_t kMaxMeshVertices = std::size_t(1) << 26;
inline constexpr std::size_t kMaxMeshFaces = std::size_t(1) << 27;

// Format from the file extension (.obj, .off, .ply, any case); throws std::runtime_error.
MeshFormat mesh_format(const std::filesystem::path& path);

// Reads positions and triangles. Throws std::runtime_error("FILE:LINE: reason") for anything
// malformed or unsupported. Does not check manifoldness (sqrt3::Topology does).
sqrt3::TriMesh read_mesh(const std::filesystem::path& path);

// Writes a mesh with round-trip exact coordinates (%.17g text, or binary double PLY),
// atomically (tools/atomic_file.h).
void write_mesh(const sqrt3::TriMesh& mesh, const std::filesystem::path& path);

// Parsers on a file's bytes (exposed for tests); `name` prefixes error messages.
sqrt3::TriMesh parse_obj(std::string_view text, const std::string& name);
sqrt3::TriMesh parse_off(std::string_view text, const std::string& name);
sqrt3::TriMesh parse_ply(std::string_view bytes, const std::string& name);

}  // namespace pupwave::cli
