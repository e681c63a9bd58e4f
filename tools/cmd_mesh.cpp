// `pupwave mesh ...`: sqrt(3) subdivision, multiresolution decomposition into a .pwm file,
// reconstruction of any level, and level-of-detail export with a PNG contact sheet.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "codec/mesh/mesh_codec.h"
#include "tools/atomic_file.h"
#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "tools/mesh_io.h"
#include "tools/mesh_render.h"
#include "transforms/sqrt3/hierarchy.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::cli {
namespace {

struct MeshOptions {
  std::string input, output;
  int levels = 1;
  int level = 0;
  double max_error = 0;
  std::string sheet;
  Verbosity verbosity;
};

void check_levels(int levels) {
  if (levels < 0 || levels > mesh::kMaxMeshLevels) {
    throw std::invalid_argument("--levels must be 0.." + std::to_string(mesh::kMaxMeshLevels));
  }
}

// Reads a mesh and checks it is a manifold triangle mesh (the error names the file).
sqrt3::TriMesh read_checked(const std::string& path) {
  sqrt3::TriMesh m = read_mesh(path);
  try {
    const sqrt3::Topology t(m.points.size(), m.faces);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return m;
}

std::string sizes(const sqrt3::TriMesh& m) {
  return std::to_string(m.points.size()) + " vertices, " + std::to_string(m.faces.size()) + " faces";
}

void run_subdivide(const MeshOptions& o) {
  check_levels(o.levels);
  check_output_path(o.output);
  mesh_format(o.output);
  const sqrt3::TriMesh in = read_checked(o.input);
  // Each step triples the faces: refuse before allocating a mesh larger than a .pwm file can
  // hold (2^23 vertices, about 2^24 faces).
  constexpr std::size_t kMaxSubdividedFaces = std::size_t(1) << 24;
  std::size_t faces = in.faces.size();
  for (int j = 0; j < o.levels; ++j) {
    faces *= 3;
    if (faces > kMaxSubdividedFaces) {
      throw std::runtime_error(o.input + ": " + std::to_string(o.levels) +
                               " sqrt(3) steps would give more than " + std::to_string(kMaxSubdividedFaces) +
                               " faces");
    }
  }
  const sqrt3::TriMesh out = sqrt3::subdivide(in, o.levels);
  write_mesh(out, o.output);
  o.verbosity.out() << o.input << " (" << sizes(in) << ") -> " << o.output << " (" << sizes(out) << "), "
                    << o.levels << " sqrt(3) steps\n";
}

void run_decompose(const MeshOptions& o) {
  check_levels(o.levels);
  check_output_path(o.output);
  const sqrt3::TriMesh in = read_checked(o.input);
  mesh::MeshEncodeOptions eo;
  eo.levels = o.levels;
  if (o.max_error > 0) eo.max_error = o.max_error;
  mesh::MeshEncodeResult r;
  try {
    r = mesh::encode_mesh(in, eo);
  } catch (const std::exception& e) {
    throw std::runtime_error(o.input + ": " + e.what());
  }
  write_output_bytes(o.output, r.bytes);
  const sqrt3::TriMesh& base = r.multiresolution.coarsest;
  std::FILE* status = o.verbosity.stream();
  if (status == nullptr) return;
  std::fprintf(status, "%s (%s) -> %s: %zu bytes, %d levels, coarsest %s\n", o.input.c_str(),
               sizes(in).c_str(), o.output.c_str(), r.bytes.size(), o.levels, sizes(base).c_str());
  if (eo.max_error) {
    std::fprintf(status, "quantised: step %.6g, max vertex error %.6g (bound %.6g)\n", r.step,
                 r.measured_error, o.max_error);
  } else {
    std::fprintf(status, "float64 details: max vertex error %.3g (rounding)\n", r.measured_error);
  }
  for (std::size_t v = 0; v < r.multiresolution.input_to_canonical.size(); ++v) {
    if (r.multiresolution.input_to_canonical[v] != v) {
      std::fprintf(status,
                   "note: introduced vertices are reconstructed in the canonical order (docs/sqrt3.md)\n");
      break;
    }
  }
}

std::vector<std::uint8_t> read_stream(const std::string& path) {
  std::vector<std::uint8_t> bytes = read_file_bytes(path);
  if (!mesh::is_mesh_stream(bytes)) throw std::runtime_error(path + ": not a .pwm mesh file");
  return bytes;
}

void run_reconstruct(const MeshOptions& o) {
  check_output_path(o.output);
  mesh_format(o.output);
  const std::vector<std::uint8_t> bytes = read_stream(o.input);
  sqrt3::TriMesh m;
  try {
    m = mesh::decode_mesh(bytes, o.level);
  } catch (const std::exception& e) {
    throw std::runtime_error(o.input + ": " + e.what());
  }
  write_mesh(m, o.output);
  o.verbosity.out() << o.input << " level " << o.level << " -> " << o.output << " (" << sizes(m) << ")\n";
}

void run_lod(const MeshOptions& o) {
  check_levels(o.levels);
  const sqrt3::TriMesh in = read_checked(o.input);
  std::vector<std::string> names;
  for (int j = 0; j <= o.levels; ++j) {
    names.push_back(o.output + "_level_" + std::to_string(j) + ".obj");
    check_output_path(names.back());
  }
  if (!o.sheet.empty()) check_output_path(o.sheet);
  sqrt3::Multiresolution mr;
  try {
    mr = sqrt3::decompose(in, o.levels);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(o.input + ": " + e.what());
  }
  std::vector<sqrt3::TriMesh> meshes;
  std::vector<int> labels;
  for (int j = 0; j <= o.levels; ++j) {
    meshes.push_back(sqrt3::reconstruct(mr, j));
    labels.push_back(j);
  }
  const Image sheet = o.sheet.empty() ? Image() : render_contact_sheet(meshes, labels);
  for (int j = 0; j <= o.levels; ++j) {
    write_mesh(meshes[std::size_t(j)], names[std::size_t(j)]);
    o.verbosity.out() << names[std::size_t(j)] << ": " << sizes(meshes[std::size_t(j)]) << "\n";
  }
  if (!o.sheet.empty()) {
    write_image(sheet, o.sheet);
    o.verbosity.out() << o.sheet << ": contact sheet, level 0 (input) to " << o.levels << " left to right\n";
  }
}

void run_info(const MeshOptions& o) {
  const std::vector<std::uint8_t> bytes = read_stream(o.input);
  try {
    o.verbosity.out() << mesh::describe_mesh_stream(bytes);
  } catch (const std::exception& e) {
    throw std::runtime_error(o.input + ": " + e.what());
  }
}

// Runs a mesh command on a copy of its options: "-" as input spooled from stdin, status lines
// on stderr when the output is "-".
void run_mesh(const MeshOptions& given, void (*run)(const MeshOptions&)) {
  const InputPath input(given.input);
  MeshOptions o = given;
  o.input = input.path;
  o.verbosity.to_stderr = is_stdio(o.output);
  run(o);
}

CLI::App* sub(CLI::App* mesh, const char* name, const char* help, std::shared_ptr<MeshOptions> o) {
  CLI::App* c = mesh->add_subcommand(name, help);
  c->add_option("INPUT", o->input, "input file, or - for stdin")->required();
  add_verbosity_flags(*c, o->verbosity);
  return c;
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  CLI::App* mesh = app.add_subcommand(
      "mesh", "sqrt(3) subdivision and multiresolution of triangle meshes (OBJ, OFF, PLY)");
  mesh->require_subcommand(1);
  auto o = std::make_shared<MeshOptions>();
  CLI::App* s = sub(mesh, "subdivide", "Kobbelt sqrt(3) subdivision; the output keeps old vertices first", o);
  s->add_option("OUTPUT", o->output, "output mesh")->required();
  s->add_option("--levels", o->levels, "sqrt(3) steps")->capture_default_str();
  s->callback([o] { run_mesh(*o, run_subdivide); });
  CLI::App* d = sub(mesh, "decompose", "Multiresolution of a sqrt(3)-structured mesh into a .pwm file", o);
  d->add_option("OUTPUT", o->output, "output .pwm file")->required();
  d->add_option("--levels", o->levels, "reversals")->capture_default_str();
  d->add_option("--max-error", o->max_error, "quantise so that every vertex moves at most E (Euclidean)")
      ->check(positive_number());
  d->callback([o] { run_mesh(*o, run_decompose); });
  CLI::App* r = sub(mesh, "reconstruct", "Mesh of any level of a .pwm file", o);
  r->add_option("OUTPUT", o->output, "output mesh")->required();
  r->add_option("--level", o->level, "reversals coarser than the coded mesh (0 = the mesh itself)")
      ->capture_default_str();
  r->callback([o] { run_mesh(*o, run_reconstruct); });
  CLI::App* l = sub(mesh, "lod", "Write every level as OUT_PREFIX_level_J.obj (0 = the input)", o);
  l->add_option("OUT_PREFIX", o->output, "output prefix")->required();
  l->add_option("--levels", o->levels, "reversals")->capture_default_str();
  l->add_option("--sheet", o->sheet, "also write a PNG contact sheet of the levels");
  l->callback([o] { run_mesh(*o, run_lod); });
  CLI::App* i = sub(mesh, "info", "Describe a .pwm file", o);
  i->callback([o] { run_mesh(*o, run_info); });
}

}  // namespace pupwave::cli
