// The batch engine: the program is compiled once into a plan of kernel steps (vm/engines/batch_plan.h), and
// Run applies each step to a batch of kBatchSize vertices at a time, structure of arrays. The
// kernels are compiled for every Highway target, each in its own vm/engines/batch_kernels_<target>.cc (see
// vm/engines/batch_kernels-inl.h for why), and the best one the CPU supports is chosen when the engine is
// made (HWY_DYNAMIC_DISPATCH).

// Declare the per-target kernel tables once per Highway target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "vm/engines/batch_engine.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "vm/engines/batch_plan.h"

namespace vs11::batch {
namespace HWY_NAMESPACE {
const KernelTable* GetKernelTable(FloatRules rules);  // defined by vm/engines/batch_kernels_<target>.cc
}  // namespace HWY_NAMESPACE
}  // namespace vs11::batch

#if HWY_ONCE

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "hwy/aligned_allocator.h"
#include "hwy/cache_control.h"
#include "vm/core/thread_pool.h"
#include "vm/engines/batch_engine.h"
#include "vm/engines/jit_compiler.h"
#include "vm/engines/jit_options.h"

namespace vs11 {
namespace batch {

// Every target Highway compiles for needs its vm/engines/batch_kernels_<target>.cc.
static_assert((HWY_TARGETS & ~(HWY_SCALAR | HWY_EMU128 | HWY_SSSE3 | HWY_SSE4 | HWY_AVX2 | HWY_AVX3)) == 0,
              "add a vm/engines/batch_kernels_<target>.cc for the new Highway target");
HWY_EXPORT(GetKernelTable);

namespace {

// A call is split over threads only into pieces of at least kMinTaskNanoseconds of estimated work.
// Handing a piece to a sleeping pool worker costs a futex wake (a few microseconds, more on a busy or
// virtual machine) and the worker then misses in cache on the caller's arrays; a piece of 20 us
// keeps that a small part of it, and the caller takes pieces too, so a late worker costs at most
// the piece it takes. The work is estimated from the program's instruction slots (§2.7) at
// kNanosecondsPerSlot, a little below the cheapest slot measured with the jit on one thread
// (BM_Program/<program>/threads:1/65536 on a 2-core AMD EPYC with AVX-512: 0.12 ns/slot for
// sh9_irradiance_as_printed, 0.22 for sh9_irradiance, 0.28 for sh_order0, 0.5-1 for
// all_instructions and skinning), so the estimate is low and a call splits only when it surely pays:
// sh_order1 (3 slots) in pieces of 66 000 vertices or more, the paper's program (11 slots) 18 000,
// all_instructions (67) 3 000. The kernels (batch engine) are slower per slot, which only makes the
// pieces larger than they need be. 1024 vertices never split (67 slots x 1024 x 0.1 ns = 7 us).
constexpr double kMinTaskNanoseconds = 20000;
constexpr double kNanosecondsPerSlot = 0.1;
// A program of one slot (sh_order0: one mov) only moves memory: one thread already streams its
// vertices at about the machine's bandwidth, and a second only competes for it. Measured with
// BM_Program/<program>/threads:T/1048576 on a 2-core AMD EPYC (AVX2, load under 1.3, medians of 9):
// sh_order0 (1 slot) 794 us on one thread, 1203 us on two (0.66x); sh_order1 (3 slots) 1.35x,
// sh_zh3 (6) 1.79x, the paper's program (11) 1.82x. So a program splits only from two slots on.
constexpr int kMinSlotsToSplit = 2;
// Pieces per thread, at most: the caller takes pieces too, so when a worker is late (the cores are
// busy with other processes) the caller runs its share, and the call is never much slower than on
// one thread.
constexpr std::size_t kTasksPerThread = 4;

// Floats from one arena lane to the next: a batch plus one cache line, so that lanes do not sit a
// multiple of 4 KiB apart (loads would then wait on unrelated stores: "4K aliasing").
constexpr std::size_t kFloatsPerCacheLine = 64 / sizeof(float);
constexpr std::size_t kLaneStride = kBatchSize + kFloatsPerCacheLine;

constexpr std::size_t RoundUp(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

void FillLane(float* lane, std::size_t count, float value) {
  if (std::bit_cast<std::uint32_t>(value) == 0) {
    std::memset(lane, 0, count * sizeof(float));  // +0.0f: the C library's widest stores
  } else {
    std::fill_n(lane, count, value);
  }
}

// Vertices [start, start + n) of `lane` into `out`.
void Gather(const StridedLane& lane, std::size_t start, std::size_t n, float* out) {
  if (lane.contiguous()) {
    std::memcpy(out, lane.base + start, n * sizeof(float));
    return;
  }
  const float* from = lane.base + static_cast<std::ptrdiff_t>(start) * lane.stride;
  for (std::size_t i = 0; i < n; ++i, from += lane.stride) out[i] = *from;
}

// The state one thread runs batches with: the lane table and the lanes the engine owns (the plan's
// arena lanes, then a padded copy of each input and output lane for a batch shorter than kBatchSize).
struct Workspace {
  explicit Workspace(const BatchPlan& plan)
      : arena_lanes(plan.arena_lanes),
        arena(hwy::AllocateAligned<float>(
            (plan.arena_lanes + plan.input_lanes.size() + plan.output_lanes.size()) * kLaneStride)),
        address(hwy::AllocateAligned<std::int32_t>(4 * kBatchSize)),  // a0's four lanes
        read_lanes(kArenaLaneBase + plan.arena_lanes, nullptr),
        write_lanes(kArenaLaneBase + plan.arena_lanes, nullptr),
        input_arrays(plan.input_lanes.size()),
        output_arrays(plan.output_lanes.size(), nullptr) {
    unstored.reserve(4 * kOutputSlotCount);
    std::fill_n(arena.get(), (plan.arena_lanes + input_arrays.size() + output_arrays.size()) * kLaneStride, 0.0f);
    std::fill_n(ArenaLane(kOneLane - kArenaLaneBase), kBatchSize, 1.0f);
    for (int lane = 0; lane < plan.arena_lanes; ++lane) {
      read_lanes[kArenaLaneBase + lane] = write_lanes[kArenaLaneBase + lane] = ArenaLane(lane);
    }
  }

  float* ArenaLane(std::size_t lane) { return arena.get() + lane * kLaneStride; }
  float* InputCopy(std::size_t k) { return ArenaLane(arena_lanes + k); }
  float* OutputCopy(std::size_t k) { return ArenaLane(arena_lanes + input_arrays.size() + k); }
  void ReserveSpill(std::size_t floats) {
    if (floats <= spill_floats) return;
    spill = hwy::AllocateAligned<float>(floats);
    spill_floats = floats;
  }

  std::size_t arena_lanes;
  hwy::AlignedFreeUniquePtr<float[]> spill;  // the compiled program's spilled registers
  std::size_t spill_floats = 0;
  hwy::AlignedFreeUniquePtr<float[]> arena;
  hwy::AlignedFreeUniquePtr<std::int32_t[]> address;
  std::vector<const float*> read_lanes;
  std::vector<float*> write_lanes;
  // Per Run: the caller's array behind each plan input and output lane, null (base) when absent.
  std::vector<StridedLane> input_arrays;
  std::vector<float*> output_arrays;
  // Per Run: output lanes no instruction stores, with the value they keep (filled batch by batch).
  std::vector<std::pair<float*, float>> unstored;
};

class BatchEngine final : public Engine {
 public:
  BatchEngine(const Program& program, const ConstantBank& api_constants, const EngineOptions& options,
              bool compile_program)
      : program_(program),
        plan_(BuildBatchPlan(program, *HWY_DYNAMIC_DISPATCH(GetKernelTable)(options.float_rules))),
        written_(WrittenOutputLanes(program)),
        min_vertices_per_task_(MinVerticesPerPiece(program)),
        threads_(static_cast<std::size_t>(std::max(1, options.threads))),
        // The default pool's threads start only in a process whose engines may split a call.
        pool_(options.pool != nullptr ? options.pool : threads_ > 1 ? &ThreadPool::Default() : nullptr),
        isa_(options.settings.Get<JitOptions>().isa),
        rules_(options.float_rules) {
    if (compile_program) {
      std::string why_not;
      variants_.emplace_back(std::vector<jit::UniformInput>{}, jit::Compile(program, why_not, isa_, {}, rules_));
      if (variants_.back().second) {
        compiled_ = variants_.back().second.get();
      } else {
        variants_.clear();
      }
    }
    LoadConstants(api_constants);
  }

  Status SetConstants(const ConstantBank& api_constants) override {
    LoadConstants(api_constants);
    return {};
  }

  Status Run(const VertexArrays& inputs, VertexArrays& outputs) override {
    const std::size_t count = inputs.count();
    assert(outputs.count() >= count);
    if (count == 0) return {};

    // Whole batches per piece, so that only the last piece has a short batch.
    // kNeverSplit is the largest size_t: any count divided by it is 0, so one task.
    const std::size_t max_tasks = std::max<std::size_t>(1, count / min_vertices_per_task_);
    const std::size_t threads =
        pool_ == nullptr ? 1 : std::min({threads_, static_cast<std::size_t>(pool_->threads()), max_tasks});
    const std::size_t tasks = std::min(max_tasks, threads * kTasksPerThread);
    const std::size_t per_task = RoundUp((count + tasks - 1) / tasks, kBatchSize);
    if (compiled_) SelectCompiled(inputs);
    while (workspaces_.size() < threads) workspaces_.emplace_back(plan_);
    for (std::size_t t = 0; t < threads && compiled_; ++t) workspaces_[t].ReserveSpill(compiled_->spill_floats());
    // Taking the output lanes writes `outputs`' bookkeeping: done here, before any thread starts.
    for (std::size_t t = 0; t < threads; ++t) BindOutputs(workspaces_[t], outputs);
    if (threads == 1) {
      RunRange(workspaces_[0], inputs, 0, count);
      return {};
    }
    pool_->Run((count + per_task - 1) / per_task, static_cast<int>(threads),
              [this, per_task, count, &inputs](std::size_t task, int slot) {
                const std::size_t begin = task * per_task;
                RunRange(workspaces_[static_cast<std::size_t>(slot)], inputs, begin, std::min(count, begin + per_task));
              });
    return {};
  }

 private:
  void LoadConstants(const ConstantBank& api_constants) {
    const ConstantBank bank = ApplyDefinitions(program_, api_constants);
    const int rows = std::max(bank.size(), plan_.max_static_constant + 1);
    constants_.assign(4 * static_cast<std::size_t>(kFirstConstantRow + rows), 0.0f);
    for (int reg = 0; reg < bank.size(); ++reg) {
      for (int c = 0; c < 4; ++c) constants_[ConstantIndex(reg, c)] = bank[reg][c];
    }
    constant_count_ = bank.size();
    // texldl's samplers: the textures are shared, never written, and kept alive by samplers_.
    for (int s = 0; s < kVertexSamplerCount; ++s) {
      samplers_[static_cast<std::size_t>(s)] = bank.sampler(s);
      const SamplerBinding& binding = samplers_[static_cast<std::size_t>(s)];
      texture_views_[static_cast<std::size_t>(s)] = {ShapeOf(binding), binding.texture ? binding.texture->texels.data() : nullptr};
    }
  }

  // The compiled program for this run's inputs: the input lanes that hold one value throughout
  // (absent registers' defaults, lanes VertexArrays::FillUniform filled) are compiled in, not read.
  void SelectCompiled(const VertexArrays& inputs) {
    std::vector<jit::UniformInput>& uniform = uniform_inputs_;  // its storage kept: no allocation per call
    uniform.clear();
    for (const std::uint16_t lane : plan_.input_lanes) {
      const int reg = (lane - kInputLaneBase) / 4, c = (lane - kInputLaneBase) % 4;
      if (!inputs.has(reg)) {
        uniform.push_back({reg, c, kDefaultInput[c]});
      } else if (const std::optional<float> value = inputs.uniform(reg, c)) {
        uniform.push_back({reg, c, *value});
      }
    }
    for (const auto& [key, compiled] : variants_) {
      if (key == uniform) {
        compiled_ = compiled.get();
        return;
      }
    }
    std::string why_not;
    std::unique_ptr<jit::CompiledProgram> compiled = jit::Compile(program_, why_not, isa_, uniform, rules_);
    if (!compiled) return;  // keep the one that reads every lane
    if (variants_.size() == kMaxVariants) variants_.erase(variants_.begin() + 1);  // the first reads every lane
    variants_.emplace_back(uniform, std::move(compiled));
    compiled_ = variants_.back().second.get();
  }

  // Absent outputs go to scratch, in every batch.
  void BindOutputs(Workspace& workspace, VertexArrays& outputs) const {
    for (std::size_t k = 0; k < plan_.output_lanes.size(); ++k) {
      const std::uint16_t lane = plan_.output_lanes[k];
      const int slot = (lane - kOutputLaneBase) / 4, c = (lane - kOutputLaneBase) % 4;
      workspace.output_arrays[k] = outputs.has(slot) ? outputs.lane(slot, c) : nullptr;
      if (!outputs.has(slot)) workspace.read_lanes[lane] = workspace.write_lanes[lane] = workspace.OutputCopy(k);
    }

    // Output lanes no instruction stores keep the reference engine's initial value (written unless
    // the lane is known to hold it already).
    workspace.unstored.clear();
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      if (!outputs.has(slot)) continue;
      const Vec4f initial = written_[slot].bits() ? Vec4f{} : UnwrittenOutputValue(slot);
      for (int c = 0; c < 4; ++c) {
        if (plan_.stored_lanes[slot] & (1 << c)) continue;
        const std::optional<float> holds = outputs.uniform(slot, c);
        if (holds && std::bit_cast<std::uint32_t>(*holds) == std::bit_cast<std::uint32_t>(initial[c])) continue;
        workspace.unstored.emplace_back(outputs.lane(slot, c), initial[c]);
      }
    }
  }

  void RunRange(Workspace& workspace, const VertexArrays& inputs, std::size_t begin, std::size_t end) const {
    // Absent inputs read (0, 0, 0, 1), in every batch.
    for (std::size_t k = 0; k < plan_.input_lanes.size(); ++k) {
      const std::uint16_t lane = plan_.input_lanes[k];
      const int reg = (lane - kInputLaneBase) / 4, c = (lane - kInputLaneBase) % 4;
      workspace.input_arrays[k] = inputs.has(reg) ? inputs.view(reg, c) : StridedLane{};
      if (!inputs.has(reg)) workspace.read_lanes[lane] = workspace.read_lanes[kDefaultInput[c] == 0.0f ? kZeroLane : kOneLane];
    }

    Frame frame{workspace.read_lanes.data(), workspace.write_lanes.data(), constants_.data(),
                workspace.address.get(), constant_count_, 0, texture_views_.data()};
    // The kernels go through L1-sized batches; the compiled loop keeps its values in registers and
    // takes every whole granule at once, when it reads and writes only the caller's arrays (an absent
    // input's constant lane and an absent output's scratch lane hold one batch). A short rest runs on
    // padded copies.
    // (The compiled program reads no absent input: their values are compiled in.) An input lane that
    // is not contiguous (borrowed with a stride, VertexArrays::Borrow) is gathered batch by batch
    // into its padded copy, which stays in L1: the caller's array is never copied whole.
    const bool whole_range =
        compiled_ && std::ranges::none_of(workspace.output_arrays, [](const float* a) { return a == nullptr; }) &&
        std::ranges::all_of(workspace.input_arrays,
                            [](const StridedLane& a) { return a.base == nullptr || a.contiguous(); });
    for (std::size_t start = begin, n = 0; start < end; start += n) {
      const std::size_t left = end - start;
      bool full;
      if (whole_range && left >= kVertexGranule) {
        n = left - left % kVertexGranule;
        full = true;
      } else {
        n = std::min(kBatchSize, left);
        full = n == kBatchSize;
      }
      for (std::size_t k = 0; k < plan_.input_lanes.size(); ++k) {
        const StridedLane& array = workspace.input_arrays[k];
        if (array.base == nullptr) continue;
        const bool in_place = full && array.contiguous();
        if (!in_place) Gather(array, start, n, workspace.InputCopy(k));
        workspace.read_lanes[plan_.input_lanes[k]] = in_place ? array.base + start : workspace.InputCopy(k);
      }
      for (std::size_t k = 0; k < plan_.output_lanes.size(); ++k) {
        float* array = workspace.output_arrays[k];
        if (array == nullptr) continue;
        float* target = full ? array + start : workspace.OutputCopy(k);
        workspace.read_lanes[plan_.output_lanes[k]] = workspace.write_lanes[plan_.output_lanes[k]] = target;
      }
      // The caller's arrays stream from memory: ask for the next batch while this one computes.
      if (!whole_range && start + kBatchSize < end) {
        for (const StridedLane& array : workspace.input_arrays) {
          if (array.base == nullptr || !array.contiguous()) continue;  // strided: the hardware's prefetcher
          for (std::size_t k = 0; k < kBatchSize; k += kFloatsPerCacheLine) {
            hwy::Prefetch(array.base + start + kBatchSize + k);
          }
        }
      }
      frame.count = RoundUp(n, kVertexGranule);
      if (compiled_) {
        compiled_->Run({.read_lanes = frame.read_lanes, .write_lanes = frame.write_lanes, .constants = frame.constants,
                        .count = frame.count, .literals = nullptr, .spill = workspace.spill.get(),
                        .constant_count = frame.constant_count});
      } else {
        for (const Step& step : plan_.steps) step.kernel(step, frame);
      }
      for (const auto& [array, value] : workspace.unstored) FillLane(array + start, n, value);
      if (full) continue;
      for (std::size_t k = 0; k < plan_.output_lanes.size(); ++k) {
        float* array = workspace.output_arrays[k];
        if (array != nullptr) std::memcpy(array + start, workspace.OutputCopy(k), n * sizeof(float));
      }
    }
  }

  Program program_;
  BatchPlan plan_;
  std::array<WriteMask, kOutputSlotCount> written_;
  std::size_t min_vertices_per_task_;  // see kMinTaskNanoseconds
  std::size_t threads_;
  ThreadPool* pool_;  // null: every call runs on its caller
  std::vector<float> constants_;
  std::int32_t constant_count_ = 0;
  SamplerBank samplers_;
  std::array<TextureView, kVertexSamplerCount> texture_views_{};
  // Compiled programs by the input lanes compiled in as constants (the first: none); null
  // compiled_: the plan's kernels run the program.
  static constexpr std::size_t kMaxVariants = 8;
  JitIsa isa_;
  FloatRules rules_;
  std::vector<std::pair<std::vector<jit::UniformInput>, std::unique_ptr<jit::CompiledProgram>>> variants_;
  const jit::CompiledProgram* compiled_ = nullptr;
  std::vector<jit::UniformInput> uniform_inputs_;  // SelectCompiled's
  std::vector<Workspace> workspaces_;
};

}  // namespace
}  // namespace batch

std::size_t MinVerticesPerPiece(const Program& program) {
  const int slots = ComputeStats(program).slots;
  if (slots < batch::kMinSlotsToSplit) return kNeverSplit;
  return static_cast<std::size_t>(batch::kMinTaskNanoseconds / (batch::kNanosecondsPerSlot * slots));
}

std::unique_ptr<Engine> MakeBatchEngine(const Program& program, const ConstantBank& api_constants,
                                        const EngineOptions& options) {
  return std::make_unique<batch::BatchEngine>(program, api_constants, options, /*compile_program=*/false);
}

std::unique_ptr<Engine> MakeJitEngine(const Program& program, const ConstantBank& api_constants,
                                      const EngineOptions& options) {
  return std::make_unique<batch::BatchEngine>(program, api_constants, options, /*compile_program=*/true);
}

}  // namespace vs11

#endif  // HWY_ONCE
