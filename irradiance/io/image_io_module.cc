#include "irradiance/io/image_io_module.h"

#include <dlfcn.h>
#include <link.h>

#include <system_error>

#include <fmt/format.h>

#include "vm/core/leak_check.h"

// Set for this file by irradiance/CMakeLists.txt.
#ifndef VS11_IMAGE_IO_LIBDIR
#error "VS11_IMAGE_IO_LIBDIR (CMAKE_INSTALL_LIBDIR) must be defined"
#endif

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

using EntryPoint = const ImageIoApi* (*)();

// The file of the executable or shared object this code was linked into: the main program has no
// name in its link map, so /proc/self/exe stands for it.
std::optional<fs::path> ThisObjectFile() {
  Dl_info info;
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&ThisObjectFile), &info, reinterpret_cast<void**>(&map),
              RTLD_DL_LINKMAP) == 0 ||
      map == nullptr) {
    return std::nullopt;
  }
  std::error_code ec;
  const fs::path file = (map->l_name && map->l_name[0]) ? fs::path(map->l_name) : fs::read_symlink("/proc/self/exe", ec);
  if (ec || file.empty()) return std::nullopt;
  return fs::absolute(file, ec);
}

std::string JoinPaths(const std::vector<fs::path>& paths) {
  std::string text;
  for (const fs::path& path : paths) text += (text.empty() ? "" : ", ") + path.string();
  return text;
}

}  // namespace

std::vector<fs::path> ImageIoModuleCandidates() {
  std::vector<fs::path> candidates;
  if (const std::optional<fs::path> object = ThisObjectFile()) {
    const fs::path folder = object->parent_path();
    candidates.push_back(folder / kImageIoModuleFileName);
    candidates.push_back((folder / ".." / VS11_IMAGE_IO_LIBDIR / "vs11" / kImageIoModuleFileName).lexically_normal());
  }
#ifdef VS11_IMAGE_IO_BUILD_DIR
  std::error_code ec;
  if (fs::is_directory(VS11_IMAGE_IO_BUILD_DIR, ec)) {
    candidates.push_back(fs::path(VS11_IMAGE_IO_BUILD_DIR) / kImageIoModuleFileName);
  }
#endif
#ifdef VS11_IMAGE_IO_INSTALL_DIR
  candidates.push_back(fs::path(VS11_IMAGE_IO_INSTALL_DIR) / kImageIoModuleFileName);
#endif
  return candidates;
}

Result<const ImageIoApi*> LoadImageIoModule(const std::vector<fs::path>& candidates) {
  for (const fs::path& candidate : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(candidate, ec)) continue;
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the global scope, where a Python extension
    // loaded later could bind to them.
    void* handle = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
      const char* reason = dlerror();
      return Failure(DiagnosticCode::kImageIoModule,
                     fmt::format("cannot load the OpenImageIO module {} ({})", candidate.string(),
                                 reason ? reason : "no reason given"));
    }
    CheckForLeaksBeforeLoadedLibrariesUnload();  // before log4cplus's pool ends (vm/core/leak_check.h)
    const auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, kImageIoEntryPoint));
    if (!entry) {
      return Failure(DiagnosticCode::kImageIoModule,
                     fmt::format("the OpenImageIO module {} has no {}: it is from another vs11 version",
                                 candidate.string(), kImageIoEntryPoint));
    }
    return entry();
  }
  return Failure(DiagnosticCode::kImageIoModule,
                 fmt::format("OpenImageIO is needed for this file, but vs11's OpenImageIO module {} is missing "
                             "(looked for {}); reinstall vs11 or rebuild it (cmake --build build)",
                             kImageIoModuleFileName, JoinPaths(candidates)));
}

Result<const ImageIoApi*> ImageIo() {
  static const Result<const ImageIoApi*> loaded = LoadImageIoModule(ImageIoModuleCandidates());
  return loaded;
}

}  // namespace vs11::irradiance
