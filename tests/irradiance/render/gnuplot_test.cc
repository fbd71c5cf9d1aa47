#include "irradiance/render/gnuplot.h"

#include <fstream>
#include <iterator>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

class Gnuplot : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("vs11_gnuplot_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::size_t FileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()));
  }

  fs::path folder_;
};

std::string ReadText(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

GnuplotChart LineChart() {
  GnuplotChart chart;
  chart.data = "# x y\n1 10\n2 20\n4 40\n\n\n1 5\n2 6\n";
  chart.script = "set logscale x\nset title " + GnuplotQuote("it's a test") +
                 "\nplot datafile index 0 using 1:2 with linespoints title 'a', "
                 "datafile index 1 using 1:2 with lines title 'b'";
  return chart;
}

TEST_F(Gnuplot, DrawsSvgAndPngAndLeavesNothingElse) {
  const fs::path svg = folder_ / "chart.svg";
  const fs::path png = folder_ / "chart.png";
  ASSERT_EQ(RenderGnuplotChart(LineChart(), {svg, png}).message(), "");
  EXPECT_THAT(ReadText(svg), HasSubstr("<svg"));
  EXPECT_THAT(ReadText(svg), HasSubstr("it's a test"));
  EXPECT_THAT(ReadText(png), StartsWith("\x89PNG"));
  EXPECT_EQ(FileCount(), 2u);
}

TEST_F(Gnuplot, AScriptErrorIsReportedAndNoImageIsLeft) {
  GnuplotChart chart = LineChart();
  chart.script = "plot datafile using 1:2 with nonsense_style";
  const Status error = RenderGnuplotChart(chart, {folder_ / "chart.svg"});
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("gnuplot failed"));
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(Gnuplot, AnUnknownExtensionIsRefused) {
  const Status error = RenderGnuplotChart(LineChart(), {folder_ / "chart.gif"});
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr(".svg or .png"));
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(Gnuplot, LogAxisTickLabelsReadLikeNumbers) {
  GnuplotChart chart;
  // As the stability sweep draws it: gnuplot's own labels for this were 0.000010 ... 10000.000000.
  chart.data = "100 0.00001\n0.25 5000\n";
  chart.script = "set logscale x\nset xrange [*:*] reverse\nset logscale y\n"
                 "plot datafile using 1:2 with lines notitle\n";
  ASSERT_EQ(RenderGnuplotChart(chart, {folder_ / "log.svg"}).message(), "");
  const std::string svg = ReadText(folder_ / "log.svg");
  EXPECT_THAT(svg, ::testing::ContainsRegex(">10000<"));
  EXPECT_THAT(svg, ::testing::ContainsRegex(">1e-05<"));
  EXPECT_THAT(svg, ::testing::Not(HasSubstr(".000000")));
}

TEST(GnuplotQuoteTest, DoublesSingleQuotes) { EXPECT_EQ(GnuplotQuote("a'b"), "'a''b'"); }

}  // namespace
}  // namespace vs11::irradiance
