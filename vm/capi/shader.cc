#include "vm/capi/shader.h"

#include <algorithm>
#include <cstring>

#include "vm/asm/bytecode.h"
#include "vm/asm/validator.h"
#include "vm/engines/engine_factory.h"

namespace vs11::capi {
namespace {

constexpr std::string_view kD3d8DeclarationCode = "d3d8-declaration";

void Copy(std::string_view text, char* into, std::size_t capacity) {
  const std::size_t length = std::min(text.size(), capacity - 1);
  std::memcpy(into, text.data(), length);
  into[length] = '\0';
}

vs11c_message Message(Severity severity, std::string_view code, std::string_view text, long instruction, long token) {
  vs11c_message message{};
  message.severity = severity == Severity::kError ? VS11C_ERROR : VS11C_WARNING;
  Copy(code, message.code, sizeof message.code);
  Copy(text, message.text, sizeof message.text);
  message.instruction = instruction;
  message.token = token;
  return message;
}

long InstructionAtWord(const Program& program, long word) {
  const auto found = std::find(program.word_offsets.begin(), program.word_offsets.end(), word);
  return found == program.word_offsets.end() ? -1 : static_cast<long>(found - program.word_offsets.begin());
}

// Each input register the program reads, with the first instruction that reads it.
std::vector<std::pair<int, int>> InputsRead(const Program& program) {
  std::vector<std::pair<int, int>> read;
  for (int index = 0; index < static_cast<int>(program.instructions.size()); ++index) {
    const Instruction& instruction = program.instructions[static_cast<std::size_t>(index)];
    for (int s = 0; s < instruction.info().source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[static_cast<std::size_t>(s)].reg;
      if (reg.file == RegisterFile::kInput &&
          std::none_of(read.begin(), read.end(), [&](const auto& seen) { return seen.first == reg.index; })) {
        read.emplace_back(reg.index, index);
      }
    }
  }
  return read;
}

// The one place the library builds an engine: engine_factory.h's MakeEngine; null where the engine
// cannot be made.
Result<std::unique_ptr<Engine>> BuildEngine(std::string_view name, const Program& program,
                                            const ConstantBank& constants, FloatRules rules) {
  EngineOptions options;
  options.float_rules = rules;
  return MakeEngine(name, program, constants, options);
}

std::string_view FastestEngine() { return FindEngine("jit") ? "jit" : "batch"; }

// D3D's screen position of a clip-space position (the viewport transform of ProcessVertices).
Vec4f ScreenPosition(const Vec4f& clip, const vs11c_viewport& viewport) {
  const float rhw = 1.0f / clip[3];
  return {viewport.x + (1.0f + clip[0] * rhw) * viewport.width * 0.5f,
          viewport.y + (1.0f - clip[1] * rhw) * viewport.height * 0.5f,
          viewport.min_z + clip[2] * rhw * (viewport.max_z - viewport.min_z), rhw};
}

}  // namespace

std::optional<int> ConstantCountOf(const vs11c_shader_options* options) {
  if (options == nullptr || options->constant_count == 0) return kDefaultConstantCount;
  if (options->constant_count < 0 || options->constant_count > kMaxConstantCount) return std::nullopt;
  return options->constant_count;
}

Validation ValidateShader(Api api, std::span<const std::uint32_t> declaration, std::span<const std::uint32_t> tokens,
                          int constant_count) {
  Validation result;
  if (api == Api::kD3d8) {
    LayoutResult<D3d8Declaration> parsed = ParseD3d8Declaration(declaration, constant_count);
    if (const LayoutError* error = std::get_if<LayoutError>(&parsed)) {
      result.status = error->status;
      result.messages.push_back(Message(Severity::kError, kD3d8DeclarationCode, error->message, -1, error->token));
    } else {
      result.d3d8_declaration = std::get<D3d8Declaration>(std::move(parsed));
    }
  }
  DecodeResult decoded = Decode(tokens);
  for (const Diagnostic& diagnostic : decoded.diagnostics.all()) {
    result.messages.push_back(Message(diagnostic.severity, DiagnosticCodeName(diagnostic.code), diagnostic.message, -1,
                                      diagnostic.word_offset));
  }
  if (!decoded.program) {
    if (result.status == VS11C_OK) result.status = VS11C_MALFORMED_TOKENS;
    return result;
  }
  ValidatorOptions options;
  options.constant_count = constant_count;
  options.dialect = api == Api::kD3d8 ? ValidatorOptions::Dialect::kDx8 : ValidatorOptions::Dialect::kDx9;
  const Diagnostics diagnostics = Validate(*decoded.program, options);
  for (const Diagnostic& diagnostic : diagnostics.all()) {
    result.messages.push_back(Message(diagnostic.severity, DiagnosticCodeName(diagnostic.code), diagnostic.message,
                                      InstructionAtWord(*decoded.program, diagnostic.word_offset), diagnostic.word_offset));
  }
  if (diagnostics.HasErrors() && result.status == VS11C_OK) result.status = VS11C_INVALID_SHADER;
  if (result.d3d8_declaration) {
    // D3D8 binds registers, not usages: a register the declaration does not load reads (0, 0, 0, 1).
    for (const std::pair<int, int>& read : InputsRead(*decoded.program)) {
      const int reg = read.first, index = read.second;  // not a structured binding: clang 14 cannot capture one
      const auto& inputs = result.d3d8_declaration->inputs;
      if (std::none_of(inputs.begin(), inputs.end(), [&](const InputElement& input) { return input.reg == reg; })) {
        result.messages.push_back(Message(Severity::kWarning, kD3d8DeclarationCode,
                                          "instruction " + std::to_string(index) + " reads v" + std::to_string(reg) +
                                              ", which the declaration does not load: it reads (0, 0, 0, 1)",
                                          index, decoded.program->WordOffsetOf(index)));
      }
    }
  }
  result.program = std::move(decoded.program);
  return result;
}

Shader::Shader(Api api, Program program, std::optional<D3d8Declaration> declaration, int constant_count)
    : api_(api), program_(std::move(program)), d3d8_declaration_(std::move(declaration)), constants_(constant_count),
      engine_name_(FastestEngine()) {
  if (d3d8_declaration_) {
    for (const auto& [reg, value] : d3d8_declaration_->constants) constants_[reg] = value;
  }
}

vs11c_status Shader::SetConstants(unsigned start, const float* values, std::size_t vector_count) {
  if (values == nullptr && vector_count > 0) return VS11C_INVALID_ARGUMENT;
  if (start > static_cast<unsigned>(constants_.size()) || vector_count > constants_.size() - start) {
    return VS11C_REGISTER_OUT_OF_RANGE;
  }
  for (std::size_t i = 0; i < vector_count; ++i) {
    std::memcpy(constants_[static_cast<int>(start + i)].data(), values + 4 * i, sizeof(Vec4f));
  }
  constants_changed_ = true;
  return VS11C_OK;
}

namespace {

std::optional<TextureAddress> TextureAddressOf(int d3d_address) {
  switch (d3d_address) {
    case VS11C_ADDRESS_WRAP: return TextureAddress::kWrap;
    case VS11C_ADDRESS_CLAMP: return TextureAddress::kClamp;
    case VS11C_ADDRESS_BORDER: return TextureAddress::kBorder;
    default: return std::nullopt;
  }
}

}  // namespace

vs11c_status Shader::SetTexture(unsigned sampler, int format, unsigned width, unsigned height, const float* texels,
                                int address_u, int address_v) {
  if (sampler >= static_cast<unsigned>(kVertexSamplerCount)) return VS11C_REGISTER_OUT_OF_RANGE;
  const std::optional<TextureAddress> u = TextureAddressOf(address_u), v = TextureAddressOf(address_v);
  if (!u || !v) return address_u >= 1 && address_u <= 5 && address_v >= 1 && address_v <= 5 ? VS11C_UNSUPPORTED
                                                                                              : VS11C_INVALID_ARGUMENT;
  SamplerBinding binding{nullptr, {*u, *v}};
  if (texels != nullptr) {
    if (format != VS11C_TEXTURE_R32F && format != VS11C_TEXTURE_A32B32G32R32F) return VS11C_INVALID_ARGUMENT;
    const TextureFormat texture_format = format == VS11C_TEXTURE_R32F ? TextureFormat::kR32F : TextureFormat::kA32B32G32R32F;
    if (width == 0 || height == 0 || width > kMaxTextureTexels || height > kMaxTextureTexels ||
        std::size_t{width} * height > kMaxTextureTexels) {
      return VS11C_INVALID_ARGUMENT;
    }
    const std::size_t floats = std::size_t{width} * height * static_cast<std::size_t>(ChannelCount(texture_format));
    Result<VertexTexture> made = VertexTexture::Make(texture_format, static_cast<int>(width), static_cast<int>(height),
                                                     std::vector<float>(texels, texels + floats));
    if (!made) return VS11C_INVALID_ARGUMENT;
    binding.texture = std::make_shared<const VertexTexture>(std::move(made).value());
  }
  constants_.sampler(static_cast<int>(sampler)) = std::move(binding);
  constants_changed_ = true;
  return VS11C_OK;
}

vs11c_status Shader::SetEngine(const char* name, int rules) {
  if (rules != VS11C_FLOAT_RULES_D3D9 && rules != VS11C_FLOAT_RULES_LEGACY) return VS11C_INVALID_ARGUMENT;
  const std::optional<EngineInfo> info = name == nullptr ? FindEngine(FastestEngine()) : FindEngine(name);
  if (!info) return VS11C_INVALID_ARGUMENT;
  engine_name_ = info->name;
  float_rules_ = rules == VS11C_FLOAT_RULES_LEGACY ? FloatRules::kLegacy : FloatRules::kD3d9;
  engine_.reset();
  return VS11C_OK;
}

Status Shader::EnsureEngine() {
  if (!engine_) {
    Result<std::unique_ptr<Engine>> built = BuildEngine(engine_name_, program_, constants_, float_rules_);
    if (!built) return built.error();
    engine_ = std::move(built).value();
  } else if (constants_changed_) {
    constants_changed_ = false;
    return engine_->SetConstants(constants_);
  }
  constants_changed_ = false;
  return {};
}

vs11c_status Shader::EngineFailed(const Status& status) {
  engine_error_ = status.message();
  return VS11C_ENGINE_FAILED;
}

vs11c_status Shader::Process(const vs11c_vertex_element* declaration, std::span<const vs11c_stream> streams,
                             std::size_t vertex_count, const vs11c_output& output) {
  std::vector<InputElement> inputs;
  if (api_ == Api::kD3d8) {
    if (declaration != nullptr) return VS11C_INVALID_ARGUMENT;
    inputs = d3d8_declaration_->inputs;
  } else {
    if (declaration == nullptr) return VS11C_INVALID_ARGUMENT;
    LayoutResult<std::vector<vs11c_vertex_element>> elements = ReadD3d9Declaration(declaration);
    if (const LayoutError* error = std::get_if<LayoutError>(&elements)) return error->status;
    inputs = BindD3d9Inputs(program_, std::get<std::vector<vs11c_vertex_element>>(elements));
  }
  for (const InputElement& input : inputs) {
    if (static_cast<std::size_t>(input.stream) >= streams.size() || streams[input.stream].data == nullptr) {
      return VS11C_INVALID_ARGUMENT;
    }
  }
  if ((output.fvf != 0) == (output.declaration != nullptr) || (output.data == nullptr && vertex_count > 0)) {
    return VS11C_INVALID_ARGUMENT;
  }
  LayoutResult<std::vector<OutputElement>> laid_out = output.fvf != 0
                                                          ? OutputsFromFvf(output.fvf, output.stride)
                                                          : OutputsFromDeclaration(output.declaration, output.stride);
  if (const LayoutError* error = std::get_if<LayoutError>(&laid_out)) return error->status;
  const auto& outputs = std::get<std::vector<OutputElement>>(laid_out);
  if (const Status ensured = EnsureEngine(); !ensured) return EngineFailed(ensured);

  std::vector<int> registers;
  for (const InputElement& input : inputs) registers.push_back(input.reg);
  std::vector<float> screen;  // the screen positions of a chunk, lane after lane
  VertexArrays in, out;
  for (std::size_t first = 0; first < vertex_count; first += kProcessChunk) {
    const std::size_t count = std::min(kProcessChunk, vertex_count - first);
    // The arrays of one chunk serve the next of the same size: every input lane is rewritten, and
    // the engine writes the same output lanes each run.
    if (in.count() != count) {
      in = MakeInputArrays(count, registers);
      out = MakeOutputArrays(count, program_);
    }
    for (const InputElement& input : inputs) {
      const vs11c_stream& stream = streams[input.stream];
      const auto* bytes = static_cast<const std::uint8_t*>(stream.data) + first * stream.stride + input.offset;
      std::array<float*, 4> lanes;
      for (int c = 0; c < 4; ++c) lanes[c] = in.lane(input.reg, c);
      ReadElements(input.type, bytes, stream.stride, count, lanes);
    }
    if (const Status ran = engine_->Run(in, out); !ran) return EngineFailed(ran);
    auto* destination = static_cast<std::uint8_t*>(output.data) + first * output.stride;
    for (const OutputElement& element : outputs) {
      // An unwritten register reads its one value (stride 0); a screen position, lanes of its own.
      const Vec4f unwritten = UnwrittenOutputValue(element.slot);
      std::array<StridedLane, 4> lanes;
      for (int c = 0; c < 4; ++c) {
        lanes[c] = out.has(element.slot) ? out.view(element.slot, c) : StridedLane{&unwritten[c], 0};
      }
      if (element.transformed && output.viewport != nullptr) {
        screen.resize(4 * count);
        for (std::size_t i = 0; i < count; ++i) {
          const Vec4f position = ScreenPosition({lanes[0][i], lanes[1][i], lanes[2][i], lanes[3][i]}, *output.viewport);
          for (int c = 0; c < 4; ++c) screen[c * count + i] = position[c];
        }
        for (int c = 0; c < 4; ++c) lanes[c] = StridedLane{screen.data() + c * count, 1};
      }
      WriteElements(element.type, lanes, destination + element.offset, output.stride, count);
    }
  }
  return VS11C_OK;
}

}  // namespace vs11::capi
