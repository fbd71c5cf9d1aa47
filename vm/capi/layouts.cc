#include "vm/capi/layouts.h"

#include <bit>
#include <cstring>
#include <optional>

#include <fmt/format.h>

#include "vm/core/isa.h"

namespace vs11::capi {
namespace {

static_assert(sizeof(vs11c_vertex_element) == 8, "vs11c_vertex_element must be laid out as D3DVERTEXELEMENT9");

// d3d8types.h: a declaration token's type in bits 29-31 (D3DVSD_TOKENTYPESHIFT).
enum class D3d8Token : std::uint32_t { kNop = 0, kStream = 1, kStreamData = 2, kTessellator = 3, kConstMem = 4, kExt = 5, kEnd = 7 };
constexpr int kTokenTypeShift = 29;
constexpr std::uint32_t kD3d8End = 0xFFFFFFFF;             // D3DVSD_END()
constexpr std::uint32_t kStreamNumberMask = 0xF;           // D3DVSD_STREAMNUMBERMASK
constexpr std::uint32_t kStreamTessellator = 1u << 28;     // D3DVSD_STREAMTESSMASK
constexpr std::uint32_t kDataLoadSkip = 1u << 28;          // D3DVSD_DATALOADTYPEMASK: D3DVSD_SKIP
constexpr int kDataTypeShift = 16;                         // D3DVSD_DATATYPESHIFT, D3DVSD_SKIPCOUNTSHIFT
constexpr std::uint32_t kDataTypeMask = 0xF;
constexpr std::uint32_t kVertexRegMask = 0x1F;             // D3DVSD_VERTEXREGMASK
constexpr int kD3d8LastType = 7;                           // D3DVSDT_SHORT4
constexpr int kConstCountShift = 25;                       // D3DVSD_CONSTCOUNTSHIFT
constexpr std::uint32_t kConstCountMask = 0xF;
constexpr std::uint32_t kConstAddressMask = 0x7F;          // D3DVSD_CONSTADDRESSMASK
constexpr int kExtCountShift = 24;                         // D3DVSD_EXTCOUNTSHIFT
constexpr std::uint32_t kExtCountMask = 0x1F;
constexpr int kMaxStreams = 16;                            // D3D8's and D3D9's MaxStreams bound
constexpr int kInputRegisters = 16;                        // v0-v15

// d3d9types.h.
constexpr std::uint16_t kDeclEndStream = 0xFF;  // D3DDECL_END's Stream
constexpr int kMaxDeclLength = 64;              // MAXD3DDECLLENGTH
constexpr int kMaxUsageIndex = 15;
constexpr std::uint32_t kFvfXyz = 0x002, kFvfXyzRhw = 0x004, kFvfXyzW = 0x4002, kFvfPositionMask = 0x400E;
constexpr std::uint32_t kFvfNormal = 0x010, kFvfPointSize = 0x020, kFvfDiffuse = 0x040, kFvfSpecular = 0x080;
constexpr std::uint32_t kFvfTexCountMask = 0xF00;
constexpr int kFvfTexCountShift = 8, kFvfTexCoordSizeShift = 16;
// D3DFVF_TEXCOORDSIZEn's two bits, by value: D3DFVF_TEXTUREFORMAT2, 3, 4, 1.
constexpr std::array<int, 4> kFvfTexCoordSizes = {2, 3, 4, 1};
constexpr std::uint32_t kFvfTexCoordSizeBits = 0xFFFF0000;

LayoutError Error(vs11c_status status, long token, std::string message) { return {status, std::move(message), token}; }

std::optional<LayoutError> CheckWithinStride(const std::vector<OutputElement>& elements, std::size_t stride) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::size_t end = elements[i].offset + *DeclTypeSize(static_cast<int>(elements[i].type));
    if (end > stride) {
      return Error(VS11C_BAD_DECLARATION, static_cast<long>(i),
                   fmt::format("the output vertex needs {} bytes but the stride is {}", end, stride));
    }
  }
  return std::nullopt;
}

}  // namespace

LayoutResult<D3d8Declaration> ParseD3d8Declaration(std::span<const std::uint32_t> tokens, int constant_count) {
  D3d8Declaration declaration;
  int stream = -1;
  std::size_t offset = 0;
  std::array<bool, kInputRegisters> loaded{};
  for (std::size_t at = 0; at < tokens.size(); ++at) {
    const std::uint32_t token = tokens[at];
    const long where = static_cast<long>(at);
    if (token == kD3d8End) return declaration;
    switch (static_cast<D3d8Token>(token >> kTokenTypeShift)) {
      case D3d8Token::kNop:
        if (token != 0) return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x}: a NOP token with bits set", token));
        break;
      case D3d8Token::kStream:
        if (token & kStreamTessellator) return Error(VS11C_UNSUPPORTED, where, "D3DVSD_STREAM_TESS: the tessellator is not modelled");
        if (token & ~(7u << kTokenTypeShift | kStreamNumberMask)) {
          return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x}: D3DVSD_STREAM with reserved bits set", token));
        }
        stream = static_cast<int>(token & kStreamNumberMask);
        offset = 0;
        break;
      case D3d8Token::kStreamData: {
        if (stream < 0) return Error(VS11C_BAD_DECLARATION, where, "stream data before any D3DVSD_STREAM");
        const std::uint32_t data = (token >> kDataTypeShift) & kDataTypeMask;
        if (token & kDataLoadSkip) {
          if (token & ~(7u << kTokenTypeShift | kDataLoadSkip | kDataTypeMask << kDataTypeShift)) {
            return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x}: D3DVSD_SKIP with reserved bits set", token));
          }
          offset += data * sizeof(std::uint32_t);
          break;
        }
        const int reg = static_cast<int>(token & kVertexRegMask);
        if (token & ~(7u << kTokenTypeShift | kDataTypeMask << kDataTypeShift | kVertexRegMask)) {
          return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x}: D3DVSD_REG with reserved bits set", token));
        }
        if (static_cast<int>(data) > kD3d8LastType) {
          return Error(VS11C_BAD_DECLARATION, where, fmt::format("D3DVSD_REG: data type {} is not a D3DVSDT_ type", data));
        }
        if (reg >= kInputRegisters) return Error(VS11C_BAD_DECLARATION, where, fmt::format("D3DVSD_REG: there is no v{}", reg));
        if (loaded[reg]) return Error(VS11C_BAD_DECLARATION, where, fmt::format("D3DVSD_REG: v{} is loaded twice", reg));
        loaded[reg] = true;
        const DeclType type = static_cast<DeclType>(data);  // D3DVSDT_ values are D3DDECLTYPE's first eight
        declaration.inputs.push_back({stream, offset, type, reg});
        offset += *DeclTypeSize(static_cast<int>(type));
        break;
      }
      case D3d8Token::kTessellator:
        return Error(VS11C_UNSUPPORTED, where, "D3DVSD_TESSNORMAL/D3DVSD_TESSUV: the tessellator is not modelled");
      case D3d8Token::kConstMem: {
        const int first = static_cast<int>(token & kConstAddressMask);
        const int count = static_cast<int>((token >> kConstCountShift) & kConstCountMask);
        if (token & ~(7u << kTokenTypeShift | kConstCountMask << kConstCountShift | kConstAddressMask)) {
          return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x}: D3DVSD_CONST with reserved bits set", token));
        }
        if (first + count > constant_count) {
          return Error(VS11C_REGISTER_OUT_OF_RANGE, where,
                       fmt::format("D3DVSD_CONST loads c{}..c{}, beyond the {} constants", first, first + count - 1, constant_count));
        }
        if (tokens.size() - at - 1 < static_cast<std::size_t>(count) * 4) {
          return Error(VS11C_BAD_DECLARATION, where, "D3DVSD_CONST: the declaration ends inside its data");
        }
        for (int i = 0; i < count; ++i) {
          Vec4f value;
          for (int c = 0; c < 4; ++c) value[c] = std::bit_cast<float>(tokens[at + 1 + static_cast<std::size_t>(i * 4 + c)]);
          declaration.constants.emplace_back(first + i, value);
        }
        at += static_cast<std::size_t>(count) * 4;
        break;
      }
      case D3d8Token::kExt: {
        const std::size_t count = (token >> kExtCountShift) & kExtCountMask;
        if (tokens.size() - at - 1 < count) return Error(VS11C_BAD_DECLARATION, where, "D3DVSD_EXT: the declaration ends inside its data");
        at += count;
        break;
      }
      default:
        return Error(VS11C_BAD_DECLARATION, where, fmt::format("token {:#010x} is no D3DVSD_ token", token));
    }
  }
  return Error(VS11C_BAD_DECLARATION, static_cast<long>(tokens.size()), "the declaration has no D3DVSD_END token");
}

LayoutResult<std::vector<vs11c_vertex_element>> ReadD3d9Declaration(const vs11c_vertex_element* declaration) {
  std::vector<vs11c_vertex_element> elements;
  for (int i = 0;; ++i) {
    const vs11c_vertex_element& element = declaration[i];
    if (element.stream == kDeclEndStream) {
      if (element.type != static_cast<int>(DeclType::kUnused)) {
        return Error(VS11C_BAD_DECLARATION, i, "element with stream 0xFF: D3DDECL_END has type D3DDECLTYPE_UNUSED");
      }
      return elements;
    }
    if (i == kMaxDeclLength) return Error(VS11C_BAD_DECLARATION, i, "no D3DDECL_END within 64 elements (MAXD3DDECLLENGTH)");
    if (element.stream >= kMaxStreams) return Error(VS11C_BAD_DECLARATION, i, fmt::format("element {}: stream {} (at most 15)", i, element.stream));
    if (!DeclTypeSize(element.type)) return Error(VS11C_BAD_DECLARATION, i, fmt::format("element {}: type {} is no D3DDECLTYPE", i, element.type));
    if (element.method != 0) {
      return Error(VS11C_UNSUPPORTED, i, fmt::format("element {}: method {}: only D3DDECLMETHOD_DEFAULT is modelled", i, element.method));
    }
    if (element.usage > static_cast<int>(DeclUsage::kSample) || element.usage_index > kMaxUsageIndex) {
      return Error(VS11C_BAD_DECLARATION, i, fmt::format("element {}: usage {} index {} is no D3DDECLUSAGE", i, element.usage, element.usage_index));
    }
    for (const vs11c_vertex_element& earlier : elements) {
      if (earlier.usage == element.usage && earlier.usage_index == element.usage_index) {
        return Error(VS11C_BAD_DECLARATION, i, fmt::format("element {}: usage {} index {} appears twice", i, element.usage, element.usage_index));
      }
    }
    elements.push_back(element);
  }
}

std::vector<InputElement> BindD3d9Inputs(const Program& program, std::span<const vs11c_vertex_element> elements) {
  std::vector<InputElement> inputs;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode != Opcode::kDcl || instruction.dest.reg.file != RegisterFile::kInput) continue;
    for (const vs11c_vertex_element& element : elements) {
      if (element.usage == instruction.usage && element.usage_index == instruction.usage_index) {
        inputs.push_back({element.stream, element.offset, static_cast<DeclType>(element.type), instruction.dest.reg.index});
      }
    }
  }
  return inputs;
}

LayoutResult<std::vector<OutputElement>> OutputsFromFvf(std::uint32_t fvf, std::size_t stride) {
  const std::uint32_t known = kFvfPositionMask | kFvfNormal | kFvfPointSize | kFvfDiffuse | kFvfSpecular |
                              kFvfTexCountMask | kFvfTexCoordSizeBits;
  if (fvf & ~known) return Error(VS11C_BAD_DECLARATION, -1, fmt::format("FVF {:#x}: bits {:#x} are not modelled", fvf, fvf & ~known));
  std::vector<OutputElement> outputs;
  std::size_t offset = 0;
  auto add = [&](OutputSlot slot, DeclType type, bool transformed = false) {
    outputs.push_back({static_cast<int>(slot), offset, type, transformed});
    offset += *DeclTypeSize(static_cast<int>(type));
  };
  const std::uint32_t position = fvf & kFvfPositionMask;
  if (position == kFvfXyz) {
    add(OutputSlot::kPosition, DeclType::kFloat3);
  } else if (position == kFvfXyzRhw) {
    add(OutputSlot::kPosition, DeclType::kFloat4, true);
  } else if (position == kFvfXyzW) {
    add(OutputSlot::kPosition, DeclType::kFloat4);
  } else if (position != 0) {
    return Error(VS11C_UNSUPPORTED, -1, fmt::format("FVF {:#x}: blend weights (D3DFVF_XYZB1-5) are no shader output", fvf));
  }
  if (fvf & kFvfNormal) return Error(VS11C_UNSUPPORTED, -1, "FVF: D3DFVF_NORMAL is no shader output");
  if (fvf & kFvfPointSize) add(OutputSlot::kPointSize, DeclType::kFloat1);
  if (fvf & kFvfDiffuse) add(OutputSlot::kDiffuse, DeclType::kD3dColor);
  if (fvf & kFvfSpecular) add(OutputSlot::kSpecular, DeclType::kD3dColor);
  const int textures = static_cast<int>((fvf & kFvfTexCountMask) >> kFvfTexCountShift);
  if (textures > kTexCoordOutputCount) return Error(VS11C_BAD_DECLARATION, -1, fmt::format("FVF: D3DFVF_TEX{} (at most 8)", textures));
  for (int t = 0; t < textures; ++t) {
    const int size = kFvfTexCoordSizes[(fvf >> (kFvfTexCoordSizeShift + 2 * t)) & 3];
    add(static_cast<OutputSlot>(static_cast<int>(OutputSlot::kTexCoord0) + t), static_cast<DeclType>(size - 1));
  }
  if (std::optional<LayoutError> error = CheckWithinStride(outputs, stride)) return *error;
  return outputs;
}

LayoutResult<std::vector<OutputElement>> OutputsFromDeclaration(const vs11c_vertex_element* declaration,
                                                                 std::size_t stride) {
  LayoutResult<std::vector<vs11c_vertex_element>> read = ReadD3d9Declaration(declaration);
  if (LayoutError* error = std::get_if<LayoutError>(&read)) return *error;
  std::vector<OutputElement> outputs;
  const auto& elements = std::get<std::vector<vs11c_vertex_element>>(read);
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const vs11c_vertex_element& element = elements[i];
    const long where = static_cast<long>(i);
    if (element.stream != 0) return Error(VS11C_BAD_DECLARATION, where, fmt::format("output element {}: stream {} (outputs are stream 0)", i, element.stream));
    const DeclType type = static_cast<DeclType>(element.type);
    if (!IsWritableType(type)) {
      return Error(VS11C_UNSUPPORTED, where, fmt::format("output element {}: type {}: outputs are FLOAT1-4 or D3DCOLOR", i, element.type));
    }
    const std::optional<int> slot = OutputSlotOfUsage(element.usage, element.usage_index);
    if (!slot) {
      return Error(VS11C_UNSUPPORTED, where,
                   fmt::format("output element {}: usage {} index {} is no output of this shader", i, element.usage, element.usage_index));
    }
    outputs.push_back({*slot, element.offset, type, element.usage == static_cast<int>(DeclUsage::kPositionT)});
  }
  if (std::optional<LayoutError> error = CheckWithinStride(outputs, stride)) return *error;
  return outputs;
}

}  // namespace vs11::capi
