#include "python/array_conversion.h"

#include <cctype>
#include <cstdint>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "vm/core/register_names.h"

namespace vs11::python {
namespace {

// "texcoord1" -> usage texcoord, index 1; "normal" -> normal, 0. The register the program's dcl binds.
std::optional<int> RegisterOfUsage(const Program& program, const std::string& name) {
  std::size_t digits = name.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
  std::optional<int> usage = DeclUsageFromName(std::string_view(name).substr(0, digits));
  if (!usage) return std::nullopt;
  const int usage_index = digits < name.size() && name.size() - digits <= 2 ? std::stoi(name.substr(digits)) : 0;
  if (digits < name.size() && name.size() - digits > 2) return std::nullopt;
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode == Opcode::kDcl && instruction.usage == *usage && instruction.usage_index == usage_index) {
      return instruction.dest.reg.index;
    }
  }
  return std::nullopt;
}

int InputRegister(const Program& program, const std::string& key) {
  if (std::optional<int> reg = ParseInputRegister(key)) return *reg;
  if (std::optional<int> reg = RegisterOfUsage(program, key)) return *reg;
  throw py::value_error(fmt::format(
      "inputs['{}']: not an input register (v0 to v{}) nor a dcl usage the program declares (such as 'position' "
      "or 'texcoord1')",
      key, kInputRegisterCount - 1));
}

template <class T>
void CopyLanes(const py::array& array, std::size_t count, int columns, VertexArrays& arrays, int reg) {
  const char* base = static_cast<const char*>(array.data());
  const py::ssize_t row_stride = array.strides(0), column_stride = array.strides(1);
  for (int c = 0; c < columns; ++c) {
    float* lane = arrays.lane(reg, c);
    const char* column = base + c * column_stride;
    for (std::size_t i = 0; i < count; ++i) {
      lane[i] = static_cast<float>(*reinterpret_cast<const T*>(column + static_cast<py::ssize_t>(i) * row_stride));
    }
  }
  if (columns == 3) arrays.FillUniform(reg, 3, 1.0f);
}

// Whether the engines can read `array` where it lies (VertexArrays::Borrow): float32 whose strides
// are whole floats (of either sign) and whose data is float-aligned.
bool ReadableInPlace(const py::array& array) {
  constexpr auto kFloat = static_cast<py::ssize_t>(sizeof(float));
  return array.dtype().is(py::dtype::of<float>()) && array.shape(0) > 0 && array.strides(0) % kFloat == 0 &&
         array.strides(1) % kFloat == 0 && reinterpret_cast<std::uintptr_t>(array.data()) % alignof(float) == 0;
}

// The w of every vertex of an (n, 3) array read in place: one float, read with stride 0.
constexpr float kImpliedW = 1.0f;

void BorrowLanes(const py::array& array, int columns, VertexArrays& arrays, int reg) {
  const auto* base = static_cast<const float*>(array.data());
  const std::ptrdiff_t row_stride = array.strides(0) / static_cast<py::ssize_t>(sizeof(float));
  const std::ptrdiff_t column_stride = array.strides(1) / static_cast<py::ssize_t>(sizeof(float));
  std::array<StridedLane, 4> lanes;
  for (int c = 0; c < columns; ++c) lanes[c] = {base + c * column_stride, row_stride};
  if (columns == 3) lanes[3] = {&kImpliedW, 0};
  arrays.Borrow(reg, lanes);
}

// A float32 or float64 NumPy array of shape (rows, columns-in-`allowed`), or a ValueError naming `what`.
py::array CheckedArray(const py::handle& value, const std::string& what, std::initializer_list<int> allowed_columns) {
  if (!py::isinstance<py::array>(value)) {
    throw py::value_error(fmt::format("{}: expected a NumPy array, got {}", what, std::string(py::str(value.get_type()))));
  }
  py::array array = py::reinterpret_borrow<py::array>(value);
  const bool is_float = array.dtype().is(py::dtype::of<float>()) || array.dtype().is(py::dtype::of<double>());
  if (!is_float) {
    throw py::value_error(fmt::format("{}: dtype {} is not float32 or float64", what, std::string(py::str(array.dtype()))));
  }
  bool columns_ok = false;
  for (int columns : allowed_columns) columns_ok = columns_ok || (array.ndim() == 2 && array.shape(1) == columns);
  if (!columns_ok) {
    std::string shape;
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", array.shape(d));
    std::string wanted;
    for (int columns : allowed_columns) wanted += fmt::format("{}(n, {})", wanted.empty() ? "" : " or ", columns);
    throw py::value_error(fmt::format("{}: shape ({}) is not {}", what, shape, wanted));
  }
  return array;
}

}  // namespace

RunInputs InputsFromPython(const Program& program, const py::dict& inputs) {
  if (inputs.empty()) throw py::value_error("inputs: no arrays given (map 'v0' or a dcl usage name to an (n, 4) array)");
  struct Supplied {
    std::string key;
    int reg;
    py::array array;
  };
  std::vector<Supplied> supplied;
  for (const auto& [key_handle, value] : inputs) {
    if (!py::isinstance<py::str>(key_handle)) throw py::value_error("inputs: keys must be strings such as 'v0' or 'normal'");
    const std::string key = key_handle.cast<std::string>();
    const int reg = InputRegister(program, key);
    for (const Supplied& other : supplied) {
      if (other.reg == reg) throw py::value_error(fmt::format("inputs['{}'] and inputs['{}'] are both v{}", other.key, key, reg));
    }
    supplied.push_back({key, reg, CheckedArray(value, fmt::format("inputs['{}']", key), {3, 4})});
  }
  const std::size_t count = static_cast<std::size_t>(supplied.front().array.shape(0));
  RunInputs result;
  std::vector<int> converted;  // the registers whose values are converted into lanes of their own
  for (const Supplied& entry : supplied) {
    if (static_cast<std::size_t>(entry.array.shape(0)) != count) {
      throw py::value_error(fmt::format("inputs['{}'] has {} vertices but inputs['{}'] has {}", entry.key,
                                        entry.array.shape(0), supplied.front().key, count));
    }
    result.registers.push_back(entry.reg);
    if (!ReadableInPlace(entry.array)) converted.push_back(entry.reg);
  }
  result.arrays = MakeInputArrays(count, converted);
  for (const Supplied& entry : supplied) {
    const int columns = static_cast<int>(entry.array.shape(1));
    if (ReadableInPlace(entry.array)) {
      BorrowLanes(entry.array, columns, result.arrays, entry.reg);
      result.borrowed.push_back(entry.array);
    } else if (entry.array.dtype().is(py::dtype::of<float>())) {
      CopyLanes<float>(entry.array, count, columns, result.arrays, entry.reg);
    } else {
      CopyLanes<double>(entry.array, count, columns, result.arrays, entry.reg);
    }
  }
  return result;
}

ConstantBank ConstantsFromPython(const py::object& constants, int constant_count, std::vector<int>& given) {
  ConstantBank bank(constant_count);
  if (constants.is_none()) return bank;
  auto out_of_range = [&](const std::string& what, const std::string& index) {
    return py::value_error(fmt::format("{}: c{} is out of range (the program has c0 to c{})", what, index, constant_count - 1));
  };
  auto set_row = [&](int index, const py::handle& row, const std::string& what) {
    if (index < 0 || index >= constant_count) throw out_of_range(what, std::to_string(index));
    py::array_t<double, py::array::forcecast> values;
    try {
      values = py::array_t<double, py::array::forcecast>::ensure(row);
    } catch (const py::error_already_set&) {
      values = {};
    }
    if (!values || values.size() != 4) throw py::value_error(fmt::format("{}: expected 4 numbers", what));
    for (int c = 0; c < 4; ++c) bank[index][c] = static_cast<float>(values.data()[c]);
    given.push_back(index);
  };
  if (py::isinstance<py::dict>(constants)) {
    for (const auto& [key, row] : constants.cast<py::dict>()) {
      std::optional<int> index;
      std::string name;
      if (py::isinstance<py::int_>(key)) {
        const long long value = SaturatedInt(key);
        name = fmt::format("constants[{}]", std::string(py::str(key)));
        if (value < 0 || value >= constant_count) throw out_of_range(name, std::string(py::str(key)));
        index = static_cast<int>(value);
      } else if (py::isinstance<py::str>(key)) {
        name = fmt::format("constants['{}']", key.cast<std::string>());
        index = ParseConstantRegister(key.cast<std::string>());
        if (!index) throw py::value_error(name + ": not a constant register such as 'c4'");
      } else {
        throw py::value_error("constants: keys must be register names ('c4') or numbers (4)");
      }
      set_row(*index, row, name);
    }
    return bank;
  }
  py::array array = CheckedArray(constants, "constants", {4});
  if (array.shape(0) > constant_count) {
    throw py::value_error(fmt::format("constants: {} rows but the program has {} constant registers", array.shape(0), constant_count));
  }
  for (py::ssize_t row = 0; row < array.shape(0); ++row) set_row(static_cast<int>(row), array[py::int_(row)], "constants");
  return bank;
}

py::dict OutputsToPython(std::unique_ptr<VertexArrays> outputs) {
  const VertexArrays& view = *outputs;
  const std::vector<int> slots = view.registers();
  py::capsule owner(outputs.release(), [](void* p) { delete static_cast<VertexArrays*>(p); });
  py::dict result;
  for (int slot : slots) {
    const float* x = view.lane(slot, 0);
    const py::ssize_t lane_stride = static_cast<py::ssize_t>((view.lane(slot, 1) - x) * sizeof(float));
    py::array_t<float> array({static_cast<py::ssize_t>(view.count()), py::ssize_t{4}},
                             {static_cast<py::ssize_t>(sizeof(float)), lane_stride}, x, owner);
    result[py::str(OutputSlotName(slot))] = array;
  }
  return result;
}

}  // namespace vs11::python
