// Charts drawn by Debian's gnuplot (package gnuplot-nox, installed by .ci/setup), run as a child
// process: the tool computes the numbers, gnuplot does the drawing.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vm/core/result.h"

namespace vs11::irradiance {

struct GnuplotChart {
  // Whitespace-separated columns, '#' comments, blank lines between data blocks (gnuplot's
  // `index`). Written to a temporary file that the script reads as the string variable `datafile`.
  std::string data;
  // gnuplot commands after the terminal and output are set, e.g.
  //   set logscale x; plot datafile index 0 using 1:2 with linespoints title 'sky'
  std::string script;
  int width = 900;  // pixels (SVG: its size in user units)
  int height = 600;
};

// Renders the chart once per output; the terminal is chosen by the extension (.svg or .png, the
// latter with cairo). Each image is written to a temporary beside it and renamed into place when
// gnuplot succeeded, so a failure leaves none of them. An error (kGnuplot: gnuplot missing, or its
// own error message; kCannotWriteFile) says what went wrong.
Status RenderGnuplotChart(const GnuplotChart& chart, const std::vector<std::filesystem::path>& outputs);

// `text` quoted as a gnuplot single-quoted string (for titles and labels).
std::string GnuplotQuote(const std::string& text);
// The same, with the characters gnuplot's enhanced text mode reads as markup (_ ^ @ & ~ { } \)
// escaped, so that the text prints as written: 'probulator\_grace', not "probulator" with a
// subscript "g". For titles made of user input, such as file names.
std::string GnuplotLiteral(const std::string& text);

}  // namespace vs11::irradiance
