// The text irrmap prints of a finished job: the level table and the stage timings (irrmap_job.h).
#include <string>

#include <fmt/format.h>

#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh_order.h"

namespace vs11::irradiance {

std::string FormatLevelTable(const IrrmapReport& report) {
  std::string out = fmt::format("  {:>5}  {:>11}  {:>11}  {:>11}  {:>12}  {:>10}  {:>10}  {:>12}", "level", "size",
                                "update ms", "max rel err", "mean rel err", "peak err", "rms err", "est vs lvl 0");
  for (ShOrder order : kAllShOrders) {
    if (order != ShOrder::kOrder2) out += fmt::format("  {:>12}", fmt::format("est {}", ShOrderName(order)));
  }
  out += "\n";
  for (const LevelReport& level : report.levels) {
    auto percent = [&](double fraction, int width) {
      return report.errors_measured ? fmt::format("{:>{}.3f} %", 100.0 * fraction, width - 2)
                                    : fmt::format("{:>{}}", "-", width);
    };
    out += fmt::format("{} {:>5}  {:>11}  {:>11.4f}  {}  {}  {}  {}  {:>10.3f} %", level.chosen ? '*' : ' ',
                       level.level, fmt::format("{0}x{0}", level.size), level.update_ms,
                       percent(level.error.max_relative, 11), percent(level.error.mean_relative, 12),
                       percent(level.error.max_peak, 10), percent(level.error.max_rms, 10),
                       100.0 * level.estimated_error);
    for (const ProgramLevelEstimate& pair : report.program_estimates) {
      if (pair.level == level.level && pair.order != ShOrder::kOrder2) {
        out += fmt::format("  {:>10.3f} %", 100.0 * pair.estimated);
      }
    }
    out += "\n";
  }
  if (report.errors_measured) {
    out += fmt::format("  errors of the nine terms against the exact irradiance at {} normals, the worst of r, g, b: "
                       "relative per normal (floor 1 % of the peak), peak = max |E - E*| / max E*, rms = RMS of "
                       "E - E* / mean E*\n",
                       report.error_normals);
  }
  const ShOrderInfo& order = Info(report.order);
  out += fmt::format("  estimates (est) and --max-error: the {} metric\n", ErrorMetricName(report.error_metric));
  out += fmt::format("  program: {} ({}, {} slots per vertex) from level {}, estimated {:.3f} % against the nine "
                     "terms at level 0 (measured {:.3f} %)\n",
                     ShOrderName(order.order), order.program_file, order.slots, report.level, 100.0 * report.order_estimated_error,
                     100.0 * report.program_vs_full_order2);
  return out;
}

std::string FormatTimings(const IrrmapReport& report) {
  std::string out;
  for (const Timing& timing : report.timings) out += fmt::format("  {:<15} {:>10.3f} ms\n", timing.name, timing.ms);
  return out;
}

}  // namespace vs11::irradiance
