// The OpenImageIO module (irradiance/io/image_io_module.h): where it is looked for, and what a
// missing or foreign module says.
#include "irradiance/io/image_io_module.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(ImageIoModule, MissingModuleNamesEveryFileLookedFor) {
  const std::vector<fs::path> candidates = {"/nonexistent/a/libvs11_image_io.so",
                                            "/nonexistent/b/libvs11_image_io.so"};
  const Result<const ImageIoApi*> module = LoadImageIoModule(candidates);
  ASSERT_FALSE(module.ok());
  EXPECT_EQ(module.error().code, DiagnosticCode::kImageIoModule);
  const std::string error = module.message();
  EXPECT_THAT(error, HasSubstr("OpenImageIO"));
  EXPECT_THAT(error, HasSubstr("missing"));
  EXPECT_THAT(error, HasSubstr("/nonexistent/a/libvs11_image_io.so, /nonexistent/b/libvs11_image_io.so"));
}

TEST(ImageIoModule, SharedObjectWithoutTheEntryPointIsRefusedByName) {
  // Any shared object that is not the module: the C library's math library is everywhere.
  const fs::path foreign = "/lib/x86_64-linux-gnu/libm.so.6";
  if (!fs::exists(foreign)) GTEST_SKIP() << foreign << " is not here";
  const std::string error = LoadImageIoModule({"/nonexistent/libvs11_image_io.so", foreign}).message();
  EXPECT_THAT(error, HasSubstr(foreign.string()));
  EXPECT_THAT(error, HasSubstr(kImageIoEntryPoint));
}

TEST(ImageIoModule, LooksBesideTheProgramThenInItsLibFolderFirst) {
  const std::vector<fs::path> candidates = ImageIoModuleCandidates();
  ASSERT_GE(candidates.size(), 2u);
  const fs::path program_folder = fs::read_symlink("/proc/self/exe").parent_path();
  EXPECT_EQ(candidates[0], program_folder / kImageIoModuleFileName);
  EXPECT_EQ(candidates[1].filename(), kImageIoModuleFileName);
  EXPECT_EQ(candidates[1].parent_path().filename(), "vs11");
}

TEST(ImageIoModule, TheBuiltModuleLoadsAndIsLoadedOnce) {
  const Result<const ImageIoApi*> first = ImageIo();
  ASSERT_TRUE(first) << first.message();
  EXPECT_NE((*first)->read, nullptr);
  EXPECT_EQ(ImageIo().value(), *first);
}

}  // namespace
}  // namespace vs11::irradiance
