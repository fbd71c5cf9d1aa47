// vs11.irradiance.batch: `irrmap batch` (RunBatch, irradiance/jobs/batch_job.h) on a thread of its
// own, its records handed to Python as they are written. vs11/irradiance.py wraps the stream in a
// generator whose close() stops the work.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/batch_output.h"
#include "python/bindings.h"
#include "python/choice_arguments.h"

namespace vs11::python {
namespace {

namespace fs = std::filesystem;

// A scratch folder, removed by Remove() or when it goes out of scope: RunBatch writes its JSON
// Lines file there.
struct ScratchFolder {
  fs::path path;
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "vs11-batch-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder for the batch output");
    path = pattern;
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() { Remove(); }
  void Remove() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// One batch run. The worker thread never touches a Python object; next() waits for the next item
// with the GIL released.
class BatchStream {
 public:
  explicit BatchStream(irradiance::BatchOptions options) : options_(std::move(options)) {
    options_.output = scratch_.path / "batch.jsonl";
    options_.stop = &stop_;
    worker_ = std::thread([this] { Work(); });
  }
  BatchStream(const BatchStream&) = delete;
  BatchStream& operator=(const BatchStream&) = delete;
  ~BatchStream() { Close(); }

  // The next record as a dict; a failed input is a UserWarning on the way; StopIteration at the end,
  // ValueError when the run could not start (the options, a pattern matching nothing).
  py::object Next() {
    for (;;) {
      std::optional<Item> item = WaitForItem();
      if (!item) {
        // Ctrl-C reaches Python only where it holds the GIL: looked at every kPollInterval.
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        continue;
      }
      switch (item->kind) {
        case Item::kRecord:
          return py::module_::import("json").attr("loads")(item->text);
        case Item::kFailure:
          if (PyErr_WarnEx(PyExc_UserWarning, item->text.c_str(), 1) != 0) throw py::error_already_set();
          continue;
        case Item::kEnd:
          if (!item->text.empty()) throw py::value_error(item->text);
          throw py::stop_iteration();
        case Item::kOutOfMemory:
          PyErr_SetString(PyExc_MemoryError, item->text.c_str());
          throw py::error_already_set();
        case Item::kCrashed:
          throw std::runtime_error(item->text);
      }
    }
  }

  // Stops the run: no input starts after this, and it returns when the inputs already running are
  // done (at most `threads` of them). Records not yet taken are dropped, and the scratch folder
  // removed. Idempotent.
  void Close() {
    stop_ = true;
    if (worker_.joinable()) {
      py::gil_scoped_release release;
      worker_.join();
    }
    scratch_.Remove();
    std::lock_guard lock(mutex_);
    items_.clear();
    items_.push_back({Item::kEnd, ""});
  }

  // For the tests: inputs whose record or failure has come back so far.
  std::size_t finished() const {
    std::lock_guard lock(mutex_);
    return finished_;
  }

  // (input, reason) of every input that failed so far, in the order they failed.
  std::vector<std::pair<std::string, std::string>> failures() const {
    std::lock_guard lock(mutex_);
    return failures_;
  }

 private:
  struct Item {
    enum Kind { kRecord, kFailure, kEnd, kOutOfMemory, kCrashed } kind;  // the last three end the stream
    std::string text;  // the record's JSON line, "input: reason", or the run's error
  };
  static constexpr std::chrono::milliseconds kPollInterval{100};

  // An exception must not leave this thread (std::terminate would end the interpreter): the run's
  // own shortage of memory ends the stream with MemoryError, anything else with RuntimeError. (An
  // input that runs out of memory is that input's failure, a UserWarning, and the others go on.)
  void Work() {
    Item end{Item::kEnd, ""};
    try {
      irradiance::BatchSummary summary;
      const Status ran = irradiance::RunBatch(
          options_, summary, {},
          [this](const irradiance::BatchFailure& failure) {
            {
              std::lock_guard lock(mutex_);
              failures_.emplace_back(failure.input, failure.reason);
            }
            Push({Item::kFailure, fmt::format("{}: {}", failure.input, failure.reason)});
          },
          [this](const std::string& line) { Push({Item::kRecord, line}); });
      end.text = ran.message();
    } catch (const std::bad_alloc&) {
      end = {Item::kOutOfMemory, "out of memory while running the batch"};
    } catch (const std::exception& e) {
      end = {Item::kCrashed, e.what()};
    }
    std::lock_guard lock(mutex_);
    items_.push_back(std::move(end));
    ready_.notify_all();
  }

  void Push(Item item) {
    std::lock_guard lock(mutex_);
    ++finished_;
    items_.push_back(std::move(item));
    ready_.notify_all();
  }

  // The next item, or nullopt after kPollInterval without one. The end stays queued for later calls.
  std::optional<Item> WaitForItem() {
    py::gil_scoped_release release;
    std::unique_lock lock(mutex_);
    if (!ready_.wait_for(lock, kPollInterval, [this] { return !items_.empty(); })) return std::nullopt;
    Item item = items_.front();
    if (item.kind == Item::kRecord || item.kind == Item::kFailure) items_.pop_front();
    return item;
  }

  ScratchFolder scratch_;
  irradiance::BatchOptions options_;
  std::atomic<bool> stop_ = false;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Item> items_;
  std::size_t finished_ = 0;
  std::vector<std::pair<std::string, std::string>> failures_;
  std::thread worker_;  // last: it starts after everything it uses
};

std::unique_ptr<BatchStream> StartBatch(const std::vector<std::string>& paths, int threads, const std::string& layout,
                                        int face_size, std::optional<int> level, double max_error,
                                        const std::string& error_metric, const std::string& order,
                                        const std::string& window, double window_width) {
  if (threads < 0) throw py::value_error(fmt::format("threads={} must be >= 0 (0: every core)", threads));
  irradiance::BatchOptions options;
  options.inputs = paths;
  options.threads = threads;
  options.layout = ChoiceArgument(irradiance::kLayoutNames, "layout", layout);
  options.face_size = face_size;
  options.level = level;
  options.max_error = max_error;
  options.error_metric = ChoiceArgument(irradiance::kErrorMetricNames, "error_metric", error_metric);
  options.order = ChoiceArgument(vs11::kShOrderNames, "order", order, irradiance::kAutoOrderName);
  options.window = ChoiceArgument(irradiance::kShWindowNames, "window", window);
  options.window_width = window_width;
  options.naming = irradiance::OptionNaming::kPythonArgument;
  return std::make_unique<BatchStream>(std::move(options));
}

}  // namespace

void BindBatch(py::module_& module) {
  py::class_<BatchStream>(module, "_BatchStream",
                          "One `irrmap batch` run on a thread of its own; use vs11.irradiance.batch(), which\n"
                          "wraps it in a generator.")
      .def(py::init(&StartBatch), py::arg("paths"), py::arg("threads"), py::arg("layout"), py::arg("face_size"),
           py::arg("level"), py::arg("max_error"),
           py::arg("error_metric"), py::arg("order"), py::arg("window"), py::arg("window_width"))
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &BatchStream::Next)
      .def("close", &BatchStream::Close,
           "Stops the run: no input starts after it; returns when the running ones are done.")
      .def_property_readonly("finished", &BatchStream::finished,
                             "Inputs whose record or failure has come back so far (for the tests).")
      .def_property_readonly("failures", &BatchStream::failures,
                             "[(input, reason)] of the inputs that failed so far, in the order they failed.");
  module.def(
      "_expand_inputs",
      [](const std::vector<std::string>& inputs) {
        Result<std::vector<std::string>> expanded = irradiance::ExpandBatchInputs(inputs, {});
        if (!expanded) throw py::value_error(expanded.message());
        return std::move(expanded).value();
      },
      py::arg("inputs"), "irrmap batch's expansion of paths and glob patterns: sorted, de-duplicated.");
  module.def("_input_key", &irradiance::InputKey, py::arg("input"), "An input's record \"path\" (its canonical path).");
}

}  // namespace vs11::python
