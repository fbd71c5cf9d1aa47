#include "vm/gl/gl_compute_engine.h"

#include <GLES3/gl31.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "vm/gl/gl_compute.h"
#include "vm/gl/gl_engine.h"
#include "vm/gl/gl_runner.h"
#include "vm/translate/shader_graph.h"

namespace vs11::gl {
namespace {

// Vertices per dispatch: bounds the staging and storage buffers (16 input and 13 output registers of
// 4 floats at most: 464 MB at 1M vertices is the worst case; a typical program is under 100 MB)
// whatever the call's size. One dispatch covers any count (ComputeDispatchSize), so this is memory's
// bound, not the API's.
constexpr std::size_t kVerticesPerDispatch = std::size_t{1} << 20;

class GlComputeEngine final : public Engine, public GlPathOwner {
 public:
  GlComputeEngine(const Program& program, const EngineOptions& options, std::unique_ptr<GlContext> context)
      : program_(program), options_(options), context_(std::move(context)) {
    const translate::ShaderGraph shader = translate::RecordShader(program_, kDefaultConstantCount, options_.float_rules);
    for (int reg = 0; reg < kInputRegisterCount; ++reg) {
      if (shader.inputs_read[static_cast<std::size_t>(reg)]) inputs_read_.push_back(reg);
    }
    const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program_);
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      if (written[static_cast<std::size_t>(slot)].bits() != 0) written_.push_back(slot);
    }
  }
  ~GlComputeEngine() override {
    ScopedCurrent current(*context_);
    if (current.ok()) DeleteObjects();
  }

  // Translates for a bank of `constant_count` registers, links, and makes the buffers.
  Status Build(int constant_count) {
    ScopedCurrent current(*context_);
    if (!current.ok()) return current.status();
    DeleteObjects();
    constant_count_ = constant_count;
    Result<std::unique_ptr<ComputeRun>> run =
        ComputeRun::Create(program_, GlComputeTranslateOptions(options_, constant_count, context_->es32()));
    if (!run) {
      GLint block_size = 0;
      glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block_size);
      Diagnostic error = run.error();
      error.message += fmt::format(" (the constant bank is c[{}], --max-constants; '{}' allows uniform blocks of {} bytes)",
                                   constant_count, context_->renderer(), block_size);
      return error;
    }
    run_ = std::move(run).value();
    glGenBuffers(1, &input_buffer_);
    glGenBuffers(1, &output_buffer_);
    return GlOk("creating the storage buffers");
  }

  GlPath path() const override { return GlPath::kCompute; }

  Status SetConstants(const ConstantBank& api_constants) override {
    if (!failure_) return failure_;
    if (api_constants.size() != constant_count_ && !Keep(Build(api_constants.size()))) return failure_;
    ScopedCurrent current(*context_);
    if (!Keep(current.status())) return failure_;
    std::vector<float> rows;
    rows.reserve(static_cast<std::size_t>(api_constants.size()) * 4);
    for (const Vec4f& row : api_constants.values()) rows.insert(rows.end(), row.begin(), row.end());
    Keep(run_->SetConstants(rows));
    return failure_;
  }

  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    if (failure_ && inputs.count() > 0) {
      ScopedCurrent current(*context_);
      for (std::size_t first = 0; Keep(current.status()) && first < inputs.count(); first += kVerticesPerDispatch) {
        if (!Keep(RunDispatch(inputs, first, std::min(kVerticesPerDispatch, inputs.count() - first), outputs))) break;
      }
    }
    if (!failure_) FillWithNaN(outputs);
    return failure_;
  }

 private:
  // Keeps a failed `status` as failure_, which every later call returns; whether it succeeded.
  bool Keep(const Status& status) {
    if (!status) failure_ = status;
    return status.ok();
  }

  void DeleteObjects() {
    run_.reset();
    glDeleteBuffers(1, &input_buffer_);
    glDeleteBuffers(1, &output_buffer_);
    input_buffer_ = output_buffer_ = 0;
  }

  // The inputs the shader reads, lane after lane (structure of arrays), into the input buffer.
  void UploadInputs(const VertexArrays& inputs, std::size_t first, std::size_t count,
                    translate::ComputeLayoutBlock& layout) {
    std::size_t supplied = 0;
    for (int reg : inputs_read_) supplied += inputs.has(reg);
    staging_.resize(std::max<std::size_t>(supplied * 4 * count, 1));
    std::size_t offset = 0;
    for (int reg : inputs_read_) {
      if (!inputs.has(reg)) continue;  // reads (0, 0, 0, 1): the layout's stride[1] stays 0
      translate::ComputeLayoutBlock::UVec4 base{};
      for (int c = 0; c < 4; ++c) {
        const StridedLane lane = inputs.view(reg, c);
        float* to = staging_.data() + offset;
        if (lane.contiguous()) {
          std::memcpy(to, lane.base + first, count * sizeof(float));
        } else {
          for (std::size_t v = 0; v < count; ++v) to[v] = lane[first + v];
        }
        base[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(offset);
        offset += count;
      }
      layout.SetInput(reg, base, 1);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, input_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(staging_.size() * sizeof(float)), staging_.data(),
                 GL_STREAM_DRAW);
  }

  Status RunDispatch(const VertexArrays& inputs, std::size_t first, std::size_t count, VertexArrays& outputs) {
    translate::ComputeLayoutBlock layout;
    UploadInputs(inputs, first, count, layout);
    std::vector<int> wanted;
    for (int slot : written_) {
      if (!outputs.has(slot)) continue;
      const auto base = static_cast<std::uint32_t>(wanted.size() * 4 * count);
      const auto n = static_cast<std::uint32_t>(count);
      layout.SetOutput(slot, {base, base + n, base + 2 * n, base + 3 * n}, 1);
      wanted.push_back(slot);
    }
    if (wanted.empty()) return {};
    const std::size_t floats = wanted.size() * 4 * count;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, output_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(floats * sizeof(float)), nullptr, GL_STREAM_READ);
    if (Status dispatched = run_->Dispatch(layout, input_buffer_, output_buffer_, count); !dispatched) return dispatched;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, output_buffer_);
    const void* mapped =
        glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(floats * sizeof(float)), GL_MAP_READ_BIT);
    if (mapped == nullptr) {
      if (Status mapping = GlOk("glMapBufferRange"); !mapping) return mapping;
      return Failure(DiagnosticCode::kGlError, "glMapBufferRange returned no pointer");
    }
    const auto* stored = static_cast<const float*>(mapped);
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      for (int c = 0; c < 4; ++c) {
        std::memcpy(outputs.lane(wanted[k], c) + first, stored + (k * 4 + static_cast<std::size_t>(c)) * count,
                    count * sizeof(float));
      }
    }
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    return GlOk("reading the output buffer");
  }

  Program program_;
  EngineOptions options_;
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<ComputeRun> run_;
  Status failure_;
  int constant_count_ = 0;
  std::vector<int> inputs_read_, written_;
  GLuint input_buffer_ = 0, output_buffer_ = 0;
  std::vector<float> staging_;
};

}  // namespace

Result<std::unique_ptr<Engine>> MakeGlComputeEngine(const Program& program, const ConstantBank& api_constants,
                                                    const EngineOptions& options, std::unique_ptr<GlContext> context) {
  auto engine = std::make_unique<GlComputeEngine>(program, options, std::move(context));
  if (Status built = engine->Build(api_constants.size()); !built) return built.error();
  if (Status set = engine->SetConstants(api_constants); !set) return set.error();
  return std::unique_ptr<Engine>(std::move(engine));
}

}  // namespace vs11::gl
