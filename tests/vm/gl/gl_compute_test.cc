// The compute translation on llvmpipe through vm/gl/gl_compute.h, with layouts the gl engine does not
// use: interleaved inputs and outputs, a dispatch in two dimensions for a count that is not a multiple
// of the work group, outputs the program does not write (and memory past the last vertex) left as
// they were, and a constant buffer that lives on the GPU, read where it is. In ctest's
// vs11_tests.llvmpipe entry.
#include "vm/gl/gl_compute.h"

#include <GLES3/gl31.h>

#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/engines/random_program.h"
#include "vm/asm/assembler.h"
#include "vm/engines/engine_factory.h"
#include "vm/gl/gl_context.h"
#include "vm/gl/gl_runner.h"

namespace vs11::gl {
namespace {

using random_program::Bits;

constexpr float kUntouched = -12345.0f;

// Writes oD0 and oT1 (oT1 through .xy only), reads v0, v1 and c0, c1.
Program TwoOutputProgram() {
  AssembleOptions assemble;
  assemble.require_position = false;
  AssembleResult assembled =
      AssembleSource("vs.1.1\nmov r1, v1\nmad oD0, v0, c0, r1\nmul r0, r1, c1\nadd oT1.xy, r0, v0\n", "two_outputs.vsh", assemble);
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  return assembled.program ? std::move(*assembled.program) : Program();
}

class GlComputeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<GlContext>> context = GlContext::Create(std::nullopt);
    ASSERT_TRUE(context) << context.message();
    context_ = std::move(context).value();
    current_ = std::make_unique<ScopedCurrent>(*context_);
    ASSERT_TRUE(current_->ok()) << current_->status().message();
    if (!OffersCompute(*context_)) GTEST_SKIP() << context_->version() << " has no compute shaders";
    glGenBuffers(2, buffers_);
  }
  void TearDown() override {
    if (context_ && current_ && current_->ok()) glDeleteBuffers(2, buffers_);
    current_.reset();
    context_.reset();
  }

  std::unique_ptr<ComputeRun> Compile(const Program& program) {
    Result<std::unique_ptr<ComputeRun>> run =
        ComputeRun::Create(program, GlComputeTranslateOptions({}, kDefaultConstantCount, context_->es32()));
    EXPECT_TRUE(run) << run.message();
    return run ? std::move(run).value() : nullptr;
  }

  void Upload(unsigned buffer, const std::vector<float>& data) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
                 GL_DYNAMIC_DRAW);
  }

  std::vector<float> Read(unsigned buffer, std::size_t floats) {
    Result<std::vector<float>> data = ReadBufferFloats(buffer, floats);
    EXPECT_TRUE(data) << data.message();
    return data ? std::move(data).value() : std::vector<float>(floats);
  }

  std::unique_ptr<GlContext> context_;
  std::unique_ptr<ScopedCurrent> current_;
  unsigned buffers_[2] = {};
};

// Vertex i: 11 floats, v0 at 1..4, v1 at 6..9; outputs 10 floats a vertex, oD0 at 0..3, oT1 at 5..8
// and oD1 (which the program never writes) pointed at 4 and 9.
struct Interleaved {
  static constexpr std::uint32_t kIn = 11, kOut = 10;
};

TEST_F(GlComputeTest, InterleavedInputsAndOutputsInTwoDimensionsGiveTheReferenceBits) {
  const Program program = TwoOutputProgram();
  std::unique_ptr<ComputeRun> run = Compile(program);
  ASSERT_TRUE(run);
  run->set_max_groups_x(7);  // 5001 vertices: 79 groups as 7 x 12
  constexpr std::size_t kCount = 5001, kSpare = 100;
  std::mt19937 rng(40);
  std::uniform_real_distribution<float> value(-4.0f, 4.0f);
  ConstantBank bank;
  std::vector<float> rows;
  for (int reg = 0; reg < bank.size(); ++reg) {
    for (int c = 0; c < 4; ++c) rows.push_back(bank[reg][c] = value(rng));
  }
  const int registers[] = {0, 1};
  VertexArrays soa = MakeInputArrays(kCount, registers);
  std::vector<float> interleaved(kCount * Interleaved::kIn, kUntouched);
  for (std::size_t v = 0; v < kCount; ++v) {
    for (int reg : registers) {
      for (int c = 0; c < 4; ++c) {
        const float x = value(rng);
        soa.lane(reg, c)[v] = x;
        interleaved[v * Interleaved::kIn + 1 + static_cast<std::size_t>(reg * 5 + c)] = x;
      }
    }
  }
  translate::ComputeLayoutBlock layout;
  layout.SetInterleavedInput(0, 1, Interleaved::kIn);
  layout.SetInterleavedInput(1, 6, Interleaved::kIn);
  const int diffuse = static_cast<int>(OutputSlot::kDiffuse), specular = static_cast<int>(OutputSlot::kSpecular);
  const int texcoord1 = static_cast<int>(OutputSlot::kTexCoord0) + 1;
  layout.SetOutput(diffuse, {0, 1, 2, 3}, Interleaved::kOut);
  layout.SetOutput(texcoord1, {5, 6, 7, 8}, Interleaved::kOut);
  layout.SetOutput(specular, {4, 9, 4, 9}, Interleaved::kOut);
  const std::size_t out_floats = (kCount + kSpare) * Interleaved::kOut;
  Upload(buffers_[0], interleaved);
  Upload(buffers_[1], std::vector<float>(out_floats, kUntouched));
  ASSERT_EQ(run->SetConstants(rows).message(), "");
  ASSERT_EQ(run->Dispatch(layout, buffers_[0], buffers_[1], kCount).message(), "");
  const std::vector<float> out = Read(buffers_[1], out_floats);

  VertexArrays expected = MakeOutputArrays(kCount, program);
  ASSERT_EQ(MakeEngine("ref", program, bank).value()->Run(soa, expected).message(), "");
  for (std::size_t v = 0; v < kCount; ++v) {
    const float* vertex = out.data() + v * Interleaved::kOut;
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(Bits(vertex[c]), Bits(expected.lane(diffuse, c)[v])) << "oD0." << c << " of vertex " << v;
      ASSERT_EQ(Bits(vertex[5 + c]), Bits(expected.lane(texcoord1, c)[v])) << "oT1." << c << " of vertex " << v;
    }
    ASSERT_EQ(vertex[4], kUntouched) << "oD1, which the program does not write, was stored at vertex " << v;
    ASSERT_EQ(vertex[9], kUntouched) << "vertex " << v;
  }
  for (std::size_t f = kCount * Interleaved::kOut; f < out_floats; ++f) {
    ASSERT_EQ(out[f], kUntouched) << "float " << f << ", past the last vertex";
  }
}

// The bank is read from the caller's buffer where it is: rewriting the buffer between dispatches
// changes the outputs, with nothing uploaded through the run.
TEST_F(GlComputeTest, AConstantBufferOnTheGpuIsReadWhereItIs) {
  const Program program = TwoOutputProgram();
  std::unique_ptr<ComputeRun> run = Compile(program);
  ASSERT_TRUE(run);
  GLuint constants = 0;
  glGenBuffers(1, &constants);
  std::vector<float> rows(kDefaultConstantCount * 4, 0.0f);
  glBindBuffer(GL_UNIFORM_BUFFER, constants);
  glBufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(rows.size() * sizeof(float)), rows.data(), GL_DYNAMIC_DRAW);
  run->BindConstantBuffer(constants, 0, kDefaultConstantCount);
  translate::ComputeLayoutBlock layout;
  layout.SetInput(0, {0, 1, 2, 3}, 0);  // every vertex reads (1, 2, 3, 4): stride 0
  layout.SetInput(1, {4, 4, 4, 4}, 0);  // and (0, 0, 0, 0)
  const int diffuse = static_cast<int>(OutputSlot::kDiffuse);
  layout.SetOutput(diffuse, {0, 1, 2, 3}, 4);
  Upload(buffers_[0], {1.0f, 2.0f, 3.0f, 4.0f, 0.0f});
  Upload(buffers_[1], std::vector<float>(3 * 4, kUntouched));
  for (float scale : {2.0f, -0.5f}) {
    for (int c = 0; c < 4; ++c) rows[static_cast<std::size_t>(c)] = scale;  // c0
    glBindBuffer(GL_UNIFORM_BUFFER, constants);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, 16, rows.data());
    ASSERT_EQ(run->Dispatch(layout, buffers_[0], buffers_[1], 3).message(), "");
    const std::vector<float> out = Read(buffers_[1], 12);
    for (int k = 0; k < 12; ++k) EXPECT_EQ(out[static_cast<std::size_t>(k)], scale * static_cast<float>(k % 4 + 1)) << k;
  }
  glDeleteBuffers(1, &constants);
}

}  // namespace
}  // namespace vs11::gl
