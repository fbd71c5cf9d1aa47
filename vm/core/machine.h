// What goes into and comes out of a vs_1_1 program run: constant banks, vertex inputs and outputs, and
// the engine interface both execution engines implement.
#pragma once

#include <any>
#include <array>
#include <cassert>
#include <cstddef>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <vector>

#include "vm/core/float_rules.h"
#include "vm/core/program.h"
#include "vm/core/result.h"
#include "vm/core/vertex_texture.h"

namespace vs11 {

using Vec4f = std::array<float, 4>;

// What a vertex element does not supply reads as (0, 0, 0, 1) (§1.2).
inline constexpr Vec4f kDefaultInput = {0.0f, 0.0f, 0.0f, 1.0f};

using Vec4i = std::array<int, 4>;
inline constexpr int kIntegerConstantCount = RegisterCount(RegisterFile::kConstInt, ShaderModel::kVs20);
inline constexpr int kBooleanConstantCount = RegisterCount(RegisterFile::kConstBool, ShaderModel::kVs20);

// Constant registers c0..c(N-1), N = MaxVertexShaderConst (at least 96), the later models'
// integer constants i0..i15 and boolean constants b0..b15, set by the API as c# is, and vs_3_0's
// vertex samplers. Unset registers
// read 0 (false); out-of-range i#/b# read 0 (false).
class ConstantBank {
 public:
  explicit ConstantBank(int count = kDefaultConstantCount) : values_(static_cast<std::size_t>(count), Vec4f{}) {}
  Vec4i& integer(int index) { return integers_[static_cast<std::size_t>(index)]; }
  Vec4i ReadInteger(long index) const {
    return index >= 0 && index < kIntegerConstantCount ? integers_[static_cast<std::size_t>(index)] : Vec4i{};
  }
  void SetBoolean(int index, bool value) { booleans_[static_cast<std::size_t>(index)] = value; }
  bool ReadBoolean(long index) const {
    return index >= 0 && index < kBooleanConstantCount && booleans_[static_cast<std::size_t>(index)];
  }
  int size() const { return static_cast<int>(values_.size()); }
  // At least `count` registers, the new ones 0 (a later model's device has 256 at least).
  void GrowTo(int count) {
    if (count > size()) values_.resize(static_cast<std::size_t>(count), Vec4f{});
  }
  Vec4f& operator[](int index) { return values_[static_cast<std::size_t>(index)]; }
  const Vec4f& operator[](int index) const { return values_[static_cast<std::size_t>(index)]; }
  // Out-of-range reads give (0, 0, 0, 0) (§1.4: the deterministic reading of "unpredictable").
  Vec4f Read(long index) const { return index >= 0 && index < size() ? values_[static_cast<std::size_t>(index)] : Vec4f{}; }
  const std::vector<Vec4f>& values() const { return values_; }
  // The vertex samplers s0..s3 (vs_3_0's texldl): textures and sampler states, API state that travels
  // with the constants. Unbound samplers read (0, 0, 0, 1).
  SamplerBinding& sampler(int index) { return samplers_[static_cast<std::size_t>(index)]; }
  const SamplerBinding& sampler(int index) const { return samplers_[static_cast<std::size_t>(index)]; }

 private:
  std::vector<Vec4f> values_;
  std::array<Vec4i, kIntegerConstantCount> integers_{};
  std::array<bool, kBooleanConstantCount> booleans_{};
  SamplerBank samplers_{};
};

// The one engine that runs every later model's program (vs_2_0, vs_2_x, vs_3_0): the reference engine,
// with its program counter (vm/engines/reference_flow.cc).
inline constexpr std::string_view kLaterModelEngine = "ref";
// The engines that run a later model's program specialised for its integer and boolean constants
// (vm/core/static_flow.h: static flow resolved, dynamic flow as per-vertex execution masks).
inline constexpr std::array<std::string_view, 3> kStaticFlowEngines = {"batch", "jit", "gl"};
// The engines that run texldl (vertex textures, vm/core/texture_sampling.h): ref, batch's texture
// kernel, and jit, which runs a program with texldl on the batch kernels (the IR has no texture read
// yet); the others (gl, translate) refuse it.
inline constexpr std::array<std::string_view, 3> kTexldlEngines = {"ref", "batch", "jit"};

// Success, or why `engine` ("ref", "batch", "jit", "gl", "translate") cannot run `program`
// (kEngineUnavailable; MakeEngine and translate::Translate ask here). vs_1_1 runs everywhere; the later
// models run on the ref engine, and on batch, jit and gl when StaticFlowRefusal lets them (whether the
// program then specialises for the constants, those engines find when they are made:
// MakeStaticFlowEngine); every other engine refuses them. Not texldl outside kTexldlEngines, a sampler
// declared dcl_cube or dcl_volume (only 2D vertex textures are modelled), nor a vs_3_0 output declared
// with a usage that has no output slot (dcl_normal o3): engines refuse them by name rather than run
// them wrong.
Status EngineRefusal(const Program& program, std::string_view engine);

// The bank a program sees: the API's values with the program's def, defi and defb constants written
// over them (§3.3 def). A definition beyond its bank is ignored (the validator rejects it).
ConstantBank ApplyDefinitions(const Program& program, ConstantBank api_constants);

// Output registers, flattened: oPos, oFog, oPts, oD0, oD1, oT0..oT7.
enum class OutputSlot : int { kPosition, kFog, kPointSize, kDiffuse, kSpecular, kTexCoord0 };
inline constexpr int kOutputSlotCount = 5 + kTexCoordOutputCount;
std::optional<int> OutputSlotOf(const RegisterRef& reg);  // nullopt for non-output or out-of-range registers
// The slot of an output declared with D3DDECLUSAGE `usage` and usage index `index` (a vs_3_0 o#, an
// output element of the C library's layouts): position, psize, fog, color0-1, texcoord0-7; else nullopt.
std::optional<int> OutputSlotOfUsage(int usage, int index);
// A vs_3_0 program's o0..o11 mapped to slots by its dcl_<usage> o# lines; nullopt where undeclared or
// where the usage has no slot.
inline constexpr int kOutputRegisterCountVs30 = RegisterCount(RegisterFile::kTexCoordOut, ShaderModel::kVs30);
std::array<std::optional<int>, kOutputRegisterCountVs30> DeclaredOutputSlots(const Program& program);
std::string OutputSlotName(int slot);                    // "oPos", "oD0", "oT3"
std::optional<int> OutputSlotFromName(std::string_view name);  // case-insensitive

// The value of an output lane the program never wrote (§7, implementation-defined; DXVK's choice):
// oD0 = (1,1,1,1), oD1 = (0,0,0,1) when the register is not written at all; every other lane 0.
Vec4f UnwrittenOutputValue(int slot);

// Which output lanes a program writes (for CSV headers and for the defaults above).
std::array<WriteMask, kOutputSlotCount> WrittenOutputLanes(const Program& program);

// One lane of vertex data read where it lies: vertex i's value is base[i * stride], the stride in
// floats: 1 for `count` consecutive floats, 4 for one component of an array of (x, y, z, w)
// structures (a C-contiguous (n, 4) float32 NumPy array), 0 for one value repeated.
struct StridedLane {
  const float* base = nullptr;
  std::ptrdiff_t stride = 1;
  float operator[](std::size_t i) const { return base[static_cast<std::ptrdiff_t>(i) * stride]; }
  bool contiguous() const { return stride == 1; }
};

// Vertex data as structure of arrays: lane (register, component) is `count` consecutive floats.
// Registers that are not present read kDefaultInput.
//
// A register may instead be borrowed (Borrow): its lanes are the caller's memory, read in place
// with any stride, never copied or written. The engines read a borrowed lane that is not contiguous
// a batch at a time (vm/engines/batch_engine.cc: kBatchSize vertices gathered into a lane of the
// engine's own workspace, which stays in L1); view() reads any lane, lane() only the arrays' own.
//
// Each lane starts on a cache line, and consecutive lanes start an odd number of cache lines apart.
// Lanes a whole number of pages apart (as `count` floats back to back are for a count that is a
// multiple of 1024) put the same vertex of every lane in one cache set of L1 and L2, and an engine
// that touches every lane at once (the jit's loop) then evicts its own lines: all_instructions ran
// 3-4x slower at 65536 vertices than the same code on staggered lanes.
//
// A lane filled by FillUniform is known to hold one value in every vertex until it is written
// through the non-const lane(): an engine may then use the value instead of reading the lane (the
// jit engine compiles it in, as the w of 1 nobody supplied) or rewriting it (an unwritten output
// lane that already holds its value), with the same results.
class VertexArrays {
 public:
  VertexArrays() = default;
  VertexArrays(std::size_t count, std::span<const int> registers, int register_space);
  std::size_t count() const { return count_; }
  bool has(int reg) const { return reg >= 0 && reg < static_cast<int>(slot_of_.size()) && slot_of_[reg] >= 0; }
  // A lane of the arrays' own (not borrowed): `count` consecutive floats.
  float* lane(int reg, int component) {
    assert(!borrowed(reg));
    uniform_[Index(reg, component)].reset();  // the caller may write through the pointer
    return data_.data() + Index(reg, component) * stride_;
  }
  const float* lane(int reg, int component) const {
    assert(!borrowed(reg));
    return data_.data() + Index(reg, component) * stride_;
  }
  // Any lane, the arrays' own (stride 1) or borrowed.
  StridedLane view(int reg, int component) const {
    const StridedLane& lane = borrowed_[Index(reg, component)];
    return lane.base != nullptr ? lane : StridedLane{data_.data() + Index(reg, component) * stride_, 1};
  }
  std::vector<int> registers() const;

  // Makes `reg`, which must not be present yet (and below the register space), read the caller's
  // memory in place: component c of vertex i is lanes[c][i], for i < count(). The memory must stay
  // valid and unchanged while an engine reads these arrays; nothing here writes it. A lane of
  // stride 0 counts as filled by FillUniform with its one value.
  void Borrow(int reg, const std::array<StridedLane, 4>& lanes);
  bool borrowed(int reg) const { return has(reg) && borrowed_[Index(reg, 0)].base != nullptr; }

  void FillUniform(int reg, int component, float value);
  std::optional<float> uniform(int reg, int component) const { return uniform_[Index(reg, component)]; }

 private:
  std::size_t Index(int reg, int component) const {
    return static_cast<std::size_t>(slot_of_[reg]) * 4 + static_cast<std::size_t>(component);
  }
  // std::allocator with the alignment of a cache line.
  template <class T>
  struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) {}  // NOLINT: rebinding converts implicitly
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
    friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
  };

  std::size_t count_ = 0;
  std::size_t stride_ = 0;  // floats from one lane's start to the next's
  std::vector<int> slot_of_;
  std::vector<float, CacheLineAllocator<float>> data_;
  std::vector<std::optional<float>> uniform_;  // per lane
  std::vector<StridedLane> borrowed_;          // per lane; base null: the lane is in data_
};

// Inputs: registers v0..v15. Outputs: the OutputSlot values.
VertexArrays MakeInputArrays(std::size_t count, std::span<const int> input_registers);
VertexArrays MakeOutputArrays(std::size_t count, const Program& program);  // the slots the program writes
// Every lane of every register of `outputs` NaN: what an engine whose Run fails leaves (Engine::Run).
void FillWithNaN(VertexArrays& outputs);

// Runs one program with one constant bank over many vertices.
//
// Threads: one engine is not shareable. Run and SetConstants change the engine (the batch and jit
// engines keep their workspaces, spill buffers and compiled variants from call to call), so two
// threads must never call them on one engine at once; a program that runs on several threads makes
// one engine per thread. An engine may pass from thread to thread when its calls are ordered (a
// mutex, a join). Engines are independent of each other: any number may run at once, on one shared
// Program, ConstantBank and input VertexArrays, which they only read through const references; each
// run needs its own output VertexArrays. With EngineOptions::threads > 1, Run splits a large call
// over threads of its own and returns when all of them are done. tests/vm/engines/
// engine_threads_test.cc checks this under CI's ThreadSanitizer stage (.ci/tsan).
class Engine {
 public:
  virtual ~Engine() = default;
  // `outputs` must come from MakeOutputArrays for the same program and count. Lanes the program does
  // not write get UnwrittenOutputValue.
  //
  // Both calls return the empty Status on success, as the CPU engines (ref, batch, jit) always do; an
  // engine that cannot be built is an error of MakeEngine instead. An engine that depends on a driver
  // (gl: kGlError, or kGlCompile for a bank it cannot link) or on the constants (a later model's program
  // that does not specialise for new i#/b# values: kEngineUnavailable) returns why it failed. A failed
  // Run, and every Run after a failed SetConstants, returns that Diagnostic and writes NaN to every lane
  // of `outputs` (FillWithNaN), so that outputs a caller forgets to check never pass for results. A gl
  // engine that failed stays failed: every later call returns the same Diagnostic; the static-flow
  // engine works again after a SetConstants whose constants specialise.
  virtual Status Run(const VertexArrays& inputs, VertexArrays& outputs) = 0;
  virtual Status SetConstants(const ConstantBank& api_constants) = 0;
};

class ThreadPool;  // vm/core/thread_pool.h

// Options an engine defines for itself (the jit's instruction set, the gl engine's device), one struct
// per engine, set and read by its type: the core carries them without knowing any engine. Get<T>()
// gives T{} (the engine's defaults) where nothing was set.
class EngineSettings {
 public:
  template <class T>
  EngineSettings& Set(T value) {
    values_.insert_or_assign(std::type_index(typeid(T)), std::any(std::move(value)));
    return *this;
  }
  template <class T>
  T Get() const {
    auto found = values_.find(std::type_index(typeid(T)));
    return found == values_.end() ? T{} : std::any_cast<T>(found->second);
  }

 private:
  std::map<std::type_index, std::any> values_;
};

struct EngineOptions {
  // Batch and jit engines: a call may run on up to this many threads of `pool`, where its size
  // pays for the split (vm/engines/batch_engine.cc); the results do not depend on it.
  int threads = 1;
  // The threads a split call runs on; null: ThreadPool::Default(), the process's one pool sized to
  // the cores. The pool must outlive the engine.
  ThreadPool* pool = nullptr;
  // The rule every product follows (vm/core/float_rules.h); every engine gives the same bits under either.
  FloatRules float_rules = FloatRules::kD3d9;
  // Each engine's own options (vm/engines/jit_options.h, vm/gl/gl_engine.h); the others ignore them.
  EngineSettings settings{};
};

}  // namespace vs11
