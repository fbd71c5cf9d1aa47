#include "vm/cli/vertex_sources.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "vm/asm/program_file.h"
#include "vm/cli/cli_support.h"
#include "vm/cli/streamed_output.h"
#include "vm/core/input_file.h"
#include "vm/core/register_names.h"
#include "vm/mesh/mesh_export.h"
#include "vm/mesh/npy.h"
#include "vm/mesh/vertex_buffer.h"

namespace vs11::cli {
namespace {

void Warn(const std::string& message) { std::fprintf(stderr, "warning: %s\n", message.c_str()); }

void WarnNonFinite(const std::string& source, const std::vector<Vec4f>& rows) {
  std::size_t nonfinite = 0;
  for (const Vec4f& row : rows) {
    if (!std::isfinite(row[0]) || !std::isfinite(row[1]) || !std::isfinite(row[2]) || !std::isfinite(row[3])) ++nonfinite;
  }
  if (nonfinite > 0) Warn(fmt::format("{}: {} of {} vertices hold NaN or infinity", source, nonfinite, rows.size()));
}

// "v3=FILE.npy" -> {3, "FILE.npy"}.
std::pair<int, std::string> SplitRegisterAssignment(const std::string& flag) {
  const std::size_t equals = flag.find('=');
  if (equals == std::string::npos) FailUsage(fmt::format("--npy '{}': expected v#=FILE.npy", flag));
  std::optional<int> reg = ParseInputRegister(flag.substr(0, equals));
  if (!reg) FailUsage(fmt::format("--npy '{}': '{}' is not an input register v0-v15", flag, flag.substr(0, equals)));
  return {*reg, flag.substr(equals + 1)};
}

int ConstantRegisterFromName(const std::string& name) {
  const int index = ParseConstantRegister(name).value_or(-1);
  if (index < 0) FailUsage(fmt::format("--bone-palette '{}': expected a constant register such as c6", name));
  return index;
}

std::optional<mesh::Mesh> LoadBoundMesh(const VertexSourceFlags& flags, const Program& program,
                                        ConstantBank& constants, mesh::RegisterData& supplied) {
  if (flags.mesh.empty()) {
    if (!flags.binds.empty() || !flags.bone_palette.empty()) FailUsage("--bind and --bone-palette need --mesh");
    return std::nullopt;
  }
  mesh::MeshLoadOptions options;
  options.compute_normals = flags.compute_normals;
  options.compute_tangents = flags.compute_tangents;
  options.timeout_seconds = flags.mesh_timeout;
  Result<mesh::Mesh> loaded = mesh::LoadMesh(flags.mesh, options);
  if (!loaded) Fail(loaded.message());
  for (const std::string& warning : loaded->warnings) Warn(fmt::format("{}: {}", flags.mesh, warning));

  std::vector<mesh::RegisterBinding> overrides, bindings;
  for (const std::string& bind : flags.binds) {
    if (const Status parsed = mesh::ParseBindings(bind, overrides); !parsed) FailUsage("--bind " + parsed.message());
  }
  if (const Status resolved = mesh::ResolveBindings(program, overrides, bindings); !resolved) Fail(resolved.message());
  if (bindings.empty()) {
    Fail("the program declares no inputs (a DX8 program has no dcl): bind them, e.g. "
         "--bind v0=position,v3=normal,v7=texcoord0");
  }
  mesh::BindOptions bind_options;
  bind_options.blend_index_scale = flags.blend_index_scale;
  bind_options.mesh_name = flags.mesh;
  if (const Status bound = mesh::BindMesh(*loaded, bindings, bind_options, supplied); !bound) {
    Fail(bound.message());
  }
  if (!flags.bone_palette.empty()) {
    const int base = ConstantRegisterFromName(flags.bone_palette);
    if (const Status written = mesh::WriteBonePalette(*loaded, base, constants); !written) {
      Fail(fmt::format("--bone-palette {}: {}", flags.bone_palette, written.message()));
    }
  }
  return std::move(loaded).value();
}

void ReadNpyInputs(const VertexSourceFlags& flags, mesh::RegisterData& supplied) {
  std::vector<int> given;
  for (const std::string& flag : flags.npy_inputs) NoteRegisterOnce("--npy", 'v', SplitRegisterAssignment(flag).first, given);
  for (const std::string& flag : flags.npy_inputs) {
    auto [reg, file] = SplitRegisterAssignment(flag);
    const Result<mesh::NpyArray> array = mesh::ReadNpy(file);
    if (!array) Fail(array.message());
    std::vector<Vec4f> rows(array->rows);
    for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = array->Row(i);
    WarnNonFinite(file, rows);
    // A structured binding cannot be captured before C++20's P1091 (clang 14 lacks it).
    const auto& target = reg;
    std::erase_if(supplied, [&target](const auto& entry) { return entry.first == target; });
    supplied.emplace_back(reg, std::move(rows));
  }
}

void ReadBufferInput(const VertexSourceFlags& flags, mesh::RegisterData& supplied) {
  if (flags.buffer.empty()) {
    if (!flags.elements.empty() || flags.stride != 0) FailUsage("--stride and --element need --buffer");
    return;
  }
  std::vector<mesh::BufferElement> elements;
  for (const std::string& text : flags.elements) {
    mesh::BufferElement element;
    if (const Status parsed = mesh::ParseBufferElement(text, element); !parsed) FailUsage(parsed.message());
    elements.push_back(element);
  }
  if (const Status layout = mesh::CheckBufferLayout(flags.stride, elements); !layout) FailUsage(layout.message());
  if (const Status why = InputFileProblem(flags.buffer, /*pipes_allowed=*/false); !why.ok()) {
    Fail(fmt::format("{}: {}", flags.buffer, why.message()));
  }
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(flags.buffer, error);
  if (error) Fail(fmt::format("{}: cannot read the buffer file", flags.buffer));
  if (size / flags.stride > mesh::kMaxMeshVertices) {
    Fail(fmt::format("{}: more than {} vertices (the limit)", flags.buffer, mesh::kMaxMeshVertices));
  }
  std::optional<std::string> bytes = ReadWholeFile(flags.buffer);
  if (!bytes) Fail(fmt::format("{}: cannot read the buffer file", flags.buffer));
  if (const Status read = mesh::ReadInterleaved({reinterpret_cast<const std::uint8_t*>(bytes->data()), bytes->size()},
                                                flags.stride, elements, flags.buffer, supplied);
      !read) {
    Fail(read.message());
  }
  for (const mesh::BufferElement& element : elements) {
    for (const auto& [reg, rows] : supplied) {
      if (reg == element.reg) WarnNonFinite(fmt::format("{} element v{}", flags.buffer, reg), rows);
    }
  }
}

// Each output register the program writes: four lanes (oFog and oPts: one value).
struct OutputColumn {
  int slot;
  std::string name;
  int components;
};

std::vector<OutputColumn> OutputColumns(const Program& program, const VertexArrays& outputs) {
  std::vector<OutputColumn> columns;
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    if (written[slot].bits() == 0 || !outputs.has(slot)) continue;
    const bool scalar = slot == static_cast<int>(OutputSlot::kFog) || slot == static_cast<int>(OutputSlot::kPointSize);
    columns.push_back({slot, OutputSlotName(slot), scalar ? 1 : 4});
  }
  return columns;
}

// The column's values as rows of four (what the mesh writer takes; a mesh is at most kMaxMeshVertices).
std::vector<Vec4f> ColumnRows(const OutputColumn& column, const VertexArrays& outputs) {
  std::vector<Vec4f> rows(outputs.count());
  for (int lane = 0; lane < column.components; ++lane) {
    const float* values = outputs.lane(column.slot, lane);
    for (std::size_t i = 0; i < outputs.count(); ++i) rows[i][lane] = values[i];
  }
  return rows;
}

void AddNpyOutputs(const std::string& dir, const std::vector<OutputColumn>& columns, const VertexArrays& outputs,
                   std::vector<StreamedFile>& files) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) Fail(fmt::format("{}: cannot create the folder ({})", dir, error.message()));
  for (const OutputColumn& column : columns) {
    files.push_back({std::filesystem::path(dir) / (column.name + ".npy"), [&outputs, &column](const ByteSink& sink) {
                       sink(mesh::NpyHeader(outputs.count(), column.components));
                       StreamInterleaved(outputs, {{column.slot, column.components}}, sink);
                     }});
  }
}

// Returns the line that describes the buffer's layout, printed once it is written.
std::string AddBufferOutput(const std::string& file, const std::vector<OutputColumn>& columns,
                            const VertexArrays& outputs, std::vector<StreamedFile>& files) {
  std::vector<InterleavedColumn> interleaved;
  std::string layout;
  std::size_t offset = 0;
  for (const OutputColumn& column : columns) {
    interleaved.push_back({column.slot, column.components});
    layout += fmt::format(" {}={}:{}", column.name, offset, column.components);
    offset += 4 * static_cast<std::size_t>(column.components);
  }
  files.push_back({file, [&outputs, interleaved](const ByteSink& sink) { StreamInterleaved(outputs, interleaved, sink); }});
  return fmt::format("{}: {} vertices, stride {}:{}\n", file, outputs.count(), offset, layout);
}

void WriteMeshOutput(const std::string& file, const mesh::Mesh& mesh, const std::vector<OutputColumn>& columns,
                     const VertexArrays& outputs) {
  mesh::ExportAttributes attributes;
  std::string carried;
  int uv_set = 0;
  std::vector<std::vector<Vec4f>> rows;
  rows.reserve(columns.size());  // the attributes point into it
  for (const OutputColumn& column : columns) {
    if (column.slot == static_cast<int>(OutputSlot::kDiffuse)) {
      attributes.color = &rows.emplace_back(ColumnRows(column, outputs));
      carried += " oD0 -> vertex colour 0 (RGBA);";
    } else if (column.slot >= static_cast<int>(OutputSlot::kTexCoord0)) {
      const int set = column.slot - static_cast<int>(OutputSlot::kTexCoord0);
      attributes.texcoords[set] = &rows.emplace_back(ColumnRows(column, outputs));
      carried += fmt::format(" {}.xy -> UV set {};", column.name, uv_set++);
    }
  }
  attributes.note = "positions and normals are the input mesh's (root space), not oPos (clip space);" + carried;
  if (carried.empty()) Warn(fmt::format("{}: the program writes neither oD0 nor oT#: the mesh carries no output", file));
  if (const Status exported = mesh::ExportMesh(mesh, attributes, file); !exported) Fail(exported.message());
}

}  // namespace

void VertexSourceFlags::AddTo(CLI::App& command) {
  // The mesh text goes before the command's "Examples:" list, the mesh examples at its end.
  const std::string footer = command.get_footer();
  const std::size_t examples = footer.find("Examples:");
  const std::string text =
      "Meshes: --mesh FILE binds inputs from the program's dcl_* (position, normal, texcoord<n>, color<n>,\n"
      "tangent, binormal, blendweight, blendindices), or --bind v#=ATTRIBUTE for DX8 programs. Positions and\n"
      "normals are in the scene's root space (each part moved by its node transform, normals by its\n"
      "inverse transpose); skinned parts stay in mesh space for --bone-palette. The program reads the file's\n"
      "normals as they are (none: an error; zero: a warning); --compute-normals computes them all. Raw\n"
      "buffers: --buffer FILE --stride BYTES --element v#=OFFSET:COUNT. .npy: --npy v#=FILE.npy, float32\n"
      "(N, k), k 1-4. With --out-npy, --out-buffer or --out-mesh and no --out, no CSV is printed.\n\n";
  const std::string lines =
      "\n  vs11 run programs/directional_light.vsh --mesh /usr/share/assimp/models/PLY/Wuson.ply "
      "--const c0=1,0,0,0 --const c1=0,1,0,0 --const c2=0,0,1,0 --const c3=0,0,0,1 --const c4=1,0,0,0 "
      "--const c5=0,1,0,0 --const c6=0,0,1,0 --const c7=0,0.6,0.8,0 --const c8=0,0,5,1 --const c9=1,0.8,0.6,1 "
      "--const c10=0,0,0,0 --const c11=0,0,0,0 --const c12=0,0,0,16 --out-mesh wuson_lit.ply --out-npy wuson_out"
      "\n  vs11 run programs/directional_light.vsh --npy v0=wuson_out/oPos.npy --npy v1=wuson_out/oD0.npy --missing zeros "
      "--out-npy again"
      "\n  vs11 run programs/skinning.vsh --mesh /usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf "
      "--compute-normals --blend-index-scale 3 --bone-palette c6 --const c0=1,0,0,0 --const c1=0,1,0,0 "
      "--const c2=0,0,1,0 --const c3=0,0,0,1 --const c4=0,0,1,0 --const c5=1,1,1,1";
  command.footer(examples == std::string::npos ? footer + "\n" + text + "Examples:" + lines
                                               : footer.substr(0, examples) + text + footer.substr(examples) + lines);
  command.add_option("--mesh", mesh, "Vertices from a mesh file (OBJ, PLY, glTF/GLB, FBX, Collada, 3DS, ...)");
  command.add_option("--bind", binds, "Mesh attribute for an input register, e.g. v0=position,v3=normal,v7=texcoord0 "
                                      "(default: the program's dcl_* declarations)");
  command.add_option("--mesh-timeout", mesh_timeout,
                     "Stop reading --mesh after this many seconds (default 60 plus 1 per MiB): Assimp reads in a "
                     "separate process, and some corrupt files make it loop")
      ->check(CLI::PositiveNumber);
  command.add_flag("--compute-normals", compute_normals, "Compute smooth normals for every part (area-weighted, from its triangles), replacing the file's, zero ones included");
  command.add_flag("--compute-tangents", compute_tangents, "Generate tangents and binormals from texcoord0");
  command.add_option("--blend-index-scale", blend_index_scale,
                     "Multiply blendindices by this (3 for a palette of 4x3 matrices addressed as c[a0.x + base])");
  command.add_option("--bone-palette", bone_palette, "Write each bone's 4x3 skin matrix into c[BASE + 3b], e.g. c6");
  command.add_option("--npy", npy_inputs, "Input register from a float32 .npy array (N, k), e.g. v0=positions.npy");
  command.add_option("--buffer", buffer, "Vertices from a raw interleaved float32 buffer (with --stride, --element)");
  command.add_option("--stride", stride, "Bytes per vertex in --buffer")->check(SizeNumber());
  command.add_option("--element", elements, "Register, byte offset and float count in --buffer, e.g. v3=12:3");
  command.add_option("--out-npy", out_npy_dir, "Write each written output register to DIR/oPos.npy, DIR/oD0.npy, ...");
  command.add_option("--out-buffer", out_buffer, "Write the written output registers interleaved as raw float32");
  command.add_option("--out-mesh", out_mesh, "Write the --mesh with oD0 as vertex colour and oT# as UVs (.ply or .glb)");
}

VertexSources CollectVertexSources(const VertexSourceFlags& flags, const Program& program, ConstantBank& constants,
                                   mesh::RegisterData& supplied) {
  VertexSources sources;
  sources.mesh = LoadBoundMesh(flags, program, constants, supplied);
  ReadNpyInputs(flags, supplied);
  ReadBufferInput(flags, supplied);
  if (!flags.out_mesh.empty() && !sources.mesh) FailUsage("--out-mesh needs --mesh (it writes the input mesh)");
  return sources;
}

void WriteVertexOutputs(const VertexSourceFlags& flags, const VertexSources& sources, const Program& program,
                        const VertexArrays& outputs) {
  if (!flags.WritesOutputFiles()) return;
  const std::vector<OutputColumn> columns = OutputColumns(program, outputs);
  std::vector<StreamedFile> files;  // all or none: a full disk leaves no subset of them
  if (!flags.out_npy_dir.empty()) AddNpyOutputs(flags.out_npy_dir, columns, outputs, files);
  const std::string layout = flags.out_buffer.empty() ? "" : AddBufferOutput(flags.out_buffer, columns, outputs, files);
  if (const Status written = WriteStreamedFilesAtomically(files); !written) Fail(written.message());
  std::fputs(layout.c_str(), stderr);
  if (!flags.out_mesh.empty()) WriteMeshOutput(flags.out_mesh, *sources.mesh, columns, outputs);
}

}  // namespace vs11::cli
