// vs11.irradiance: project and irradiance_map, through irrmap's own library call (RunIrrmap,
// irradiance/jobs/), so their numbers are irrmap's: the same level and program choice, the same
// coefficients and constants. batch is in batch_bindings.cc.
#include <cmath>
#include <cstring>
#include <type_traits>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/report/paper_program.h"
#include "python/bindings.h"
#include "python/choice_arguments.h"
#include "vm/core/checked_arithmetic.h"
#include "vm/engines/engine_factory.h"

namespace vs11::python {
namespace {

namespace fs = std::filesystem;
using irradiance::CubeMap;
using irradiance::Image;

// What project() returns.
struct Projection {
  py::array_t<double> coefficients;  // 9 x 3
  py::array_t<float> constants;      // 7 x 4, Table 1
  int level = 0;
  int level_size = 0;
  std::string order;
  PyProgram program;
  py::dict program_constants;
  py::dict errors;
  std::vector<std::string> warnings;
  py::dict metadata;  // OutputMetadata: schema_version, convention, provenance
};

// An (n, n, 3) slice of a float array at `base` with the array's strides into an image.
template <class T>
Image ImageFromStrided(const char* base, const py::ssize_t* strides, int height, int width) {
  Image image(width, height);
  const bool packed = strides[2] == sizeof(T) && strides[1] == 3 * py::ssize_t{sizeof(T)} &&
                      strides[0] == static_cast<py::ssize_t>(width) * strides[1];
  if constexpr (std::is_same_v<T, float>) {
    if (packed) {  // the layout of Image's pixels: one copy, not an element at a time
      std::memcpy(image.pixels.data(), base, image.pixels.size() * sizeof(glm::vec3));
      return image;
    }
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        image.at(x, y)[c] = static_cast<float>(*reinterpret_cast<const T*>(base + y * strides[0] + x * strides[1] + c * strides[2]));
      }
    }
  }
  return image;
}

Image ImageAt(const py::array& array, const char* base, const py::ssize_t* strides, int height, int width) {
  return array.dtype().is(py::dtype::of<float>()) ? ImageFromStrided<float>(base, strides, height, width)
                                                  : ImageFromStrided<double>(base, strides, height, width);
}

void CheckRadiance(const Image& image, const std::string& what) {
  for (const glm::vec3& texel : image.pixels) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(texel[c]) || texel[c] < 0.0f) {
        throw py::value_error(fmt::format("{}: radiance must be finite and >= 0, found {}", what, texel[c]));
      }
    }
  }
}

// (6, N, N, 3) faces in D3D order (+x -x +y -y +z -z) or an (H, 2H, 3) lat-long map, float32/64.
void SetEnvironmentArray(const py::array& array, irradiance::IrrmapOptions& options) {
  if (!array.dtype().is(py::dtype::of<float>()) && !array.dtype().is(py::dtype::of<double>())) {
    throw py::value_error(fmt::format("environment: dtype {} is not float32 or float64", std::string(py::str(array.dtype()))));
  }
  const char* base = static_cast<const char*>(array.data());
  const bool faces = array.ndim() == 4 && array.shape(0) == 6 && array.shape(1) == array.shape(2) && array.shape(3) == 3;
  const bool latlong = array.ndim() == 3 && array.shape(1) == 2 * array.shape(0) && array.shape(2) == 3;
  if (!faces && !latlong) {
    std::string shape;
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", array.shape(d));
    throw py::value_error(fmt::format(
        "environment: shape ({}) is neither (6, N, N, 3) cube faces nor an (H, 2H, 3) lat-long map", shape));
  }
  if (array.size() == 0) throw py::value_error("environment: the array is empty");
  // A view broadcast to any shape costs NumPy nothing: refuse sizes the copy below could not hold
  // before the int sizes of Image wrap around.
  if (faces && array.shape(1) > irradiance::kMaxFaceSize) {
    throw py::value_error(fmt::format("environment: faces of {0}x{0}, above the largest face size {1}", array.shape(1),
                                      irradiance::kMaxFaceSize));
  }
  const std::optional<std::size_t> pixels = CheckedMul<std::size_t>(array.shape(0), 2 * array.shape(0));
  if (latlong && (!pixels || *pixels > irradiance::kMaxImagePixels)) {
    throw py::value_error(fmt::format("environment: a lat-long map of {}x{}, more than the {} pixels of the largest "
                                      "image", 2 * array.shape(0), array.shape(0), irradiance::kMaxImagePixels));
  }
  if (faces) {
    const int size = static_cast<int>(array.shape(1));
    CubeMap cube(size);
    for (int f = 0; f < irradiance::kCubeFaceCount; ++f) {
      cube.faces[f] = ImageAt(array, base + f * array.strides(0), array.strides() + 1, size, size);
      CheckRadiance(cube.faces[f], fmt::format("environment face {}", f));
    }
    options.cube = std::move(cube);
    options.layout = irradiance::EnvironmentLayout::kFaces;
    options.environment = fmt::format("array of 6 faces {}x{}", size, size);
    return;
  }
  const int height = static_cast<int>(array.shape(0));
  Image image = ImageAt(array, base, array.strides(), height, 2 * height);
  CheckRadiance(image, "environment");
  if (const Status size = irradiance::CheckFaceSizeOption("face_size", options.face_size); !size) {
    throw py::value_error(size.message());
  }
  // Projected where it lies (irradiance/sh/latlong_projection.h), as irrmap projects a lat-long file.
  options.latlong = std::move(image);
  options.layout = irradiance::EnvironmentLayout::kLatLong;
  options.environment = fmt::format("lat-long array {}x{}", 2 * height, height);
}

irradiance::IrrmapOptions OptionsFor(const py::object& environment, const std::string& layout, int face_size,
                                     std::optional<int> level, double max_error, const std::string& error_metric,
                                     const std::string& order, const std::string& window, double window_width) {
  irradiance::IrrmapOptions options;
  options.layout = ChoiceArgument(irradiance::kLayoutNames, "layout", layout);
  options.face_size = face_size;
  options.level = level;
  options.max_error = max_error;
  options.error_metric = ChoiceArgument(irradiance::kErrorMetricNames, "error_metric", error_metric);
  options.order = ChoiceArgument(vs11::kShOrderNames, "order", order, irradiance::kAutoOrderName);
  options.window = ChoiceArgument(irradiance::kShWindowNames, "window", window);
  options.window_width = window_width;
  options.write_files = false;
  options.naming = irradiance::OptionNaming::kPythonArgument;
  options.coefficients_only = true;
  if (py::isinstance<py::array>(environment)) {
    SetEnvironmentArray(py::reinterpret_borrow<py::array>(environment), options);
  } else if (py::isinstance<py::str>(environment) || py::hasattr(environment, "__fspath__")) {
    options.environment = environment.cast<fs::path>().string();
  } else {
    throw py::value_error("environment: expected a path, a built-in name ('sky') or a NumPy array");
  }
  return options;
}

irradiance::IrrmapReport RunJob(const irradiance::IrrmapOptions& options) {
  irradiance::IrrmapReport report;
  Status ran;
  {
    py::gil_scoped_release release;
    ran = irradiance::RunIrrmap(options, report);
  }
  if (!ran.ok()) throw py::value_error(ran.message());
  for (const std::string& warning : report.warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 2) != 0) throw py::error_already_set();
  }
  return report;
}

Projection Project(const py::object& environment, const std::string& layout, int face_size, std::optional<int> level,
                   double max_error, const std::string& order, const std::string& window,
                   const std::string& error_metric, double window_width) {
  const irradiance::IrrmapOptions options =
      OptionsFor(environment, layout, face_size, level, max_error, error_metric, order, window, window_width);
  const irradiance::IrrmapReport report = RunJob(options);
  Projection result;
  result.coefficients = py::array_t<double>({vs11::kSh9Coefficients, 3});
  for (int i = 0; i < vs11::kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) result.coefficients.mutable_at(i, c) = report.coefficients.coefficients[i][c];
  }
  result.constants = py::array_t<float>({7, 4});
  for (int r = 0; r < 7; ++r) {
    for (int c = 0; c < 4; ++c) result.constants.mutable_at(r, c) = report.constants.registers[r][c];
  }
  result.level = report.level;
  result.level_size = report.levels[report.level].size;
  result.order = std::string(vs11::ShOrderName(report.order));
  const Result<irradiance::PaperProgram> program = irradiance::PaperProgram::LoadOrder(report.order);
  if (!program) throw std::runtime_error(program.message());
  result.program = PyProgram{program->program(), std::string(vs11::Info(report.order).program_file),
                             kDefaultConstantCount, true};
  for (std::size_t i = 0; i < report.program_constants.size(); ++i) {
    const glm::vec4& value = report.program_constants[i].value;
    result.program_constants[py::str(fmt::format("c{}", program->constant_base() + static_cast<int>(i)))] =
        std::vector<float>{value.x, value.y, value.z, value.w};
  }
  py::list levels;
  for (const irradiance::LevelReport& row : report.levels) {
    py::dict entry;
    entry["level"] = row.level;
    entry["size"] = row.size;
    entry["estimated_error"] = row.estimated_error;
    levels.append(entry);
  }
  result.errors["error_metric"] = std::string(irradiance::ErrorMetricName(report.error_metric));
  result.errors["estimated_error"] = report.order_estimated_error;
  result.errors["error_vs_full_order2"] = report.program_vs_full_order2;
  result.errors["levels"] = levels;
  result.warnings = report.warnings;
  result.metadata = py::module_::import("json").attr("loads")(irradiance::OutputMetadata(report, options).dump());
  return result;
}

py::array_t<float> IrradianceMap(const py::object& environment, const std::string& layout, int face_size,
                                 std::optional<int> level, double max_error, const std::string& order,
                                 const std::string& window, int map_size, const std::string& engine,
                                 const std::string& error_metric, double window_width) {
  irradiance::IrrmapOptions options =
      OptionsFor(environment, layout, face_size, level, max_error, error_metric, order, window, window_width);
  options.coefficients_only = false;
  options.no_ground_truth = true;
  options.map_size = map_size;
  options.engine = engine;
  const irradiance::IrrmapReport report = RunJob(options);
  const CubeMap& map = report.irradiance_map;
  py::array_t<float> result({6, map.face_size, map.face_size, 3});
  for (int f = 0; f < irradiance::kCubeFaceCount; ++f) {
    for (int y = 0; y < map.face_size; ++y) {
      for (int x = 0; x < map.face_size; ++x) {
        for (int c = 0; c < 3; ++c) result.mutable_at(f, y, x, c) = map.faces[f].at(x, y)[c];
      }
    }
  }
  return result;
}

std::string EnvironmentArguments() {
  return fmt::format(
      "environment: an image file (.hdr, .exr, .pfm, .dds, ...), a six-face pattern holding '{{face}}',\n"
      "  a built-in name (builtin_environments()), or a NumPy float array: (6, N, N, 3) cube faces in\n"
      "  D3D order (+x -x +y -y +z -z, N a power of two) or an (H, 2H, 3) lat-long map (projected as it\n"
      "  lies; face_size gives its coarser levels the grids of cube faces); radiance finite and >= 0,\n"
      "  else ValueError.\n"
      "layout: {} (files only; auto goes by\n"
      "  the aspect ratio, and a square image, an angular map or one cube face, must be named).\n"
      "face_size: faces of built-ins and of resampled angular maps; a lat-long map's level k >= 1 is\n"
      "  the panorama averaged to 4 (face_size >> k) x 2 (face_size >> k) (power of two).\n"
      "level: the mip level the coefficients come from; None: the coarsest within max_error.\n"
      "max_error: the error budget of the level and program choice ({} = {} %).\n"
      "error_metric: what max_error bounds: {}, the default {}, as irrmap --error-metric.\n"
      "order: {} (the program); window: {}; window_width: bands, for hanning and lanczos.\n",
      irradiance::kLayoutNames.List(), irradiance::kDefaultMaxLevelError, 100 * irradiance::kDefaultMaxLevelError,
      irradiance::kErrorMetricNames.Help(), irradiance::ErrorMetricName(irradiance::kDefaultErrorMetric),
      vs11::kShOrderNames.List(irradiance::kAutoOrderName), irradiance::kShWindowNames.List());
}

}  // namespace

void BindIrradiance(py::module_& module) {
  py::class_<Projection>(module, "Projection", "What project() computed (irrmap's coeffs.json, in arrays).")
      .def_readonly("coefficients", &Projection::coefficients,
                    "(9, 3) float64: L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22 per channel (r, g, b).")
      .def_readonly("constants", &Projection::constants,
                    "(7, 4) float32: cAr cAg cAb cBr cBg cBb cC (the paper's Table 1), for c0..c6 of the paper's\n"
                    "program: program.run({'v0': normals}, constants) when order is order2.")
      .def_readonly("level", &Projection::level, "The mip level the coefficients came from.")
      .def_readonly("level_size", &Projection::level_size, "That level's face size.")
      .def_readonly("order", &Projection::order, "The chosen program's order: order0, order1, zh3 or order2.")
      .def_readonly("program", &Projection::program, "The chosen program (a vs11.Program, a fragment).")
      .def_readonly("program_constants", &Projection::program_constants,
                    "The chosen program's constants, {'c0': [x, y, z, w], ...}: its run()'s constants.")
      .def_readonly("errors", &Projection::errors,
                    "{'error_metric': what the estimates measure (peak, rms or relative),\n"
                    " 'estimated_error': the chosen (program, level)'s estimate against the nine terms at level 0,\n"
                    " 'error_vs_full_order2': its measured difference, 'levels': [{'level', 'size',\n"
                    " 'estimated_error'}]} (fractions).")
      .def_readonly("warnings", &Projection::warnings, "What irrmap would have warned about (also issued as warnings).")
      .def_readonly("metadata", &Projection::metadata,
                    "What the numbers are and where they came from, as in coeffs.json and every batch record:\n"
                    "{'schema_version', 'convention': {'quantity', 'basis', 'coefficient_order', 'frame',\n"
                    " 'source_kind', 'units', 'scale', 'window', ...}, 'provenance': {'vs11_version', 'input',\n"
                    " 'input_kind', 'files': [{'path', 'size_bytes', 'sha256'}], 'options': {every argument\n"
                    " that changes the numbers}}}; for an array, provenance['array'] holds its shape, dtype and\n"
                    "the SHA-256 of its C-ordered bytes.")
      .def("__repr__", [](const Projection& self) {
        return fmt::format("<vs11.irradiance.Projection {} from level {} ({}x{})>", self.order, self.level,
                           self.level_size, self.level_size);
      });

  module.def("builtin_environments", &irradiance::BuiltinEnvironmentNames, "The built-in environments' names.");
  // The choices and defaults irrmap's flags have, read by vs11/irradiance.py instead of repeated there.
  const irradiance::IrrmapOptions defaults;
  const std::string layout(irradiance::LayoutName(defaults.layout));
  const std::string window(irradiance::ShWindowName(defaults.window));
  const std::string error_metric(irradiance::ErrorMetricName(defaults.error_metric));
  const std::string order(irradiance::kAutoOrderName);
  module.attr("LAYOUTS") = ChoiceNames(irradiance::kLayoutNames);
  module.attr("ORDERS") = ChoiceNames(vs11::kShOrderNames, irradiance::kAutoOrderName);
  module.attr("WINDOWS") = ChoiceNames(irradiance::kShWindowNames);
  module.attr("ERROR_METRICS") = ChoiceNames(irradiance::kErrorMetricNames);
  py::dict defaults_dict;
  defaults_dict["layout"] = layout;
  defaults_dict["face_size"] = defaults.face_size;
  defaults_dict["max_error"] = defaults.max_error;
  defaults_dict["order"] = order;
  defaults_dict["batch_order"] = std::string(vs11::ShOrderName(irradiance::kDefaultBatchOrder));
  defaults_dict["window"] = window;
  defaults_dict["error_metric"] = error_metric;
  defaults_dict["window_width"] = defaults.window_width;
  defaults_dict["map_size"] = defaults.map_size;
  defaults_dict["engine"] = defaults.engine;
  module.attr("DEFAULTS") = defaults_dict;
  module.def("project", &Project, py::arg("environment"), py::arg("layout") = layout,
             py::arg("face_size") = defaults.face_size, py::arg("level") = py::none(),
             py::arg("max_error") = defaults.max_error, py::arg("order") = order, py::arg("window") = window,
             py::arg("error_metric") = error_metric, py::arg("window_width") = defaults.window_width,
             (std::string("Projects an environment onto nine SH coefficients per channel and packs the seven\n"
                          "constants, choosing the level and the program as `irrmap --coefficients-only` does;\n"
                          "returns a Projection. Raises ValueError for bad arguments or unusable files.\n\n") +
              EnvironmentArguments() +
              "\nExample:\n  p = vs11.irradiance.project('sky', face_size=64)\n  p.coefficients.shape  # (9, 3)")
                 .c_str());
  module.def("irradiance_map", &IrradianceMap, py::arg("environment"), py::arg("layout") = layout,
             py::arg("face_size") = defaults.face_size, py::arg("level") = py::none(),
             py::arg("max_error") = defaults.max_error, py::arg("order") = order, py::arg("window") = window,
             py::arg("map_size") = defaults.map_size, py::arg("engine") = defaults.engine,
             py::arg("error_metric") = error_metric, py::arg("window_width") = defaults.window_width,
             (std::string("The irradiance cube map irrmap writes as irradiance.exr: the chosen program run on the\n"
                          "machine once per texel direction. Returns a (6, map_size, map_size, 3) float32 array\n"
                          "(faces in D3D order, rows top to bottom).\n\n") +
              EnvironmentArguments() +
              fmt::format("map_size: faces of the result (1 to {}); engine: {}.\n", irradiance::kMaxMapSize,
                          EngineNameList()) +
              "\nExample:\n  e = vs11.irradiance.irradiance_map('studio', face_size=64, map_size=16)")
                 .c_str());
  BindBatch(module);
}

}  // namespace vs11::python
