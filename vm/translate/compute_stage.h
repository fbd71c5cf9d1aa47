// The compute stage's parts of the translation (compute_interface.h): its interface comment, the
// blocks and buffers it declares, and the start of main() that finds the vertex and reads its inputs.
// The statements between are the shared writer's (translate.cc), the same for both stages.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace vs11::translate {

struct ComputeInterfaceText {
  std::string_view source_name, target_name, float_rules, contraction;
  int constant_count = 0;
};
std::string ComputeInterfaceComment(const ComputeInterfaceText& text);

// The work-group size, the constant and layout blocks, the storage buffers and the helpers that read
// an input and store an output.
std::string ComputeDeclarations(int constant_count);

// main()'s first lines: the vertex index (vs11_vertex), the return past vertex_count, and a vec4 vN
// for every input register the program reads (`usages`: the dcl comment of each, or empty).
std::string ComputePrologue(const std::vector<bool>& inputs_read, const std::vector<std::string>& usages);

// The store of output `slot` from the vec4 variable `variable`.
std::string ComputeStore(int slot, std::string_view variable);

}  // namespace vs11::translate
