// The reduced SH orders and their packings. See sh_orders.h.
#include "vm/reference/sh_orders.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <numbers>

#include <fmt/format.h>

namespace vs11 {
namespace {

constexpr std::array<ShOrderInfo, 4> kInfos = {{
    {ShOrder::kOrder0, "sh_order0.vsh", 1, 1, 0.0},
    {ShOrder::kOrder1, "sh_order1.vsh", 3, 3, 1.0},
    {ShOrder::kZh3, "sh_zh3.vsh", 6, 5, 1.5},
    {ShOrder::kOrder2, "sh9_irradiance.vsh", 11, 7, 2.0},
}};
// Rec. 709 luminance weights, as ZH3's shared axis uses.
constexpr glm::dvec3 kLuminance{0.2126, 0.7152, 0.0722};
constexpr std::array<char, 3> kChannels = {'R', 'G', 'B'};
// sqrt(4 pi / 5): the zonal coefficient along a is sqrt(4 pi / 5) sum_m L2m y2m(a) (addition
// theorem: sum_m y2m(a) y2m(n) = 5 / (4 pi) P2(a.n)).
const double kZonalScale = std::sqrt(4.0 * std::numbers::pi / 5.0);

glm::vec4 ToFloat(double x, double y, double z, double w) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), static_cast<float>(w)};
}

// Per channel, the ZH3 zonal coefficient z of band 2 around `axis`.
glm::dvec3 ZonalCoefficient(const Sh9Rgb& sh, glm::dvec3 axis) {
  const std::array<double, kSh9Coefficients> basis = ShBasis(axis);
  glm::dvec3 z(0.0);
  for (int m = -2; m <= 2; ++m) z += sh.at(2, m) * basis[ShIndex(2, m)];
  return kZonalScale * z;
}

// The linear registers (c1 L11, c1 L1-1, c1 L10, constant) of each channel.
void AddLinearRegisters(const Sh9Rgb& sh, const glm::dvec3& constant, std::string_view constant_text,
                        std::vector<NamedRegister>& out) {
  for (int c = 0; c < 3; ++c) {
    out.push_back({fmt::format("cA{}", static_cast<char>(std::tolower(kChannels[c]))),
                   fmt::format("(c1 {0}11, c1 {0}1-1, c1 {0}10, {1})", kChannels[c],
                               fmt::format(fmt::runtime(constant_text), kChannels[c])),
                   ToFloat(kShC1 * sh.at(1, 1)[c], kShC1 * sh.at(1, -1)[c], kShC1 * sh.at(1, 0)[c], constant[c])});
  }
}

}  // namespace

const ShOrderInfo& Info(ShOrder order) {
  for (const ShOrderInfo& info : kInfos) {
    if (info.order == order) return info;
  }
  assert(false);
  return kInfos.back();
}

glm::dvec3 Zh3Axis(const Sh9Rgb& sh) {
  const glm::dvec3 linear(glm::dot(kLuminance, sh.at(1, 1)), glm::dot(kLuminance, sh.at(1, -1)),
                          glm::dot(kLuminance, sh.at(1, 0)));
  const double length = glm::length(linear);
  if (!(length > 0.0) || !std::isfinite(length)) return {0.0, 0.0, 1.0};
  return linear / length;
}

Sh9Rgb ReduceToOrder(const Sh9Rgb& sh, ShOrder order) {
  Sh9Rgb reduced = sh;
  if (order == ShOrder::kOrder2) return reduced;
  for (int m = -2; m <= 2; ++m) reduced.at(2, m) = glm::dvec3(0.0);
  if (order == ShOrder::kOrder0) {
    for (int m = -1; m <= 1; ++m) reduced.at(1, m) = glm::dvec3(0.0);
  }
  if (order == ShOrder::kZh3) {
    const glm::dvec3 axis = Zh3Axis(sh);
    const glm::dvec3 z = ZonalCoefficient(sh, axis);
    const std::array<double, kSh9Coefficients> basis = ShBasis(axis);
    for (int m = -2; m <= 2; ++m) reduced.at(2, m) = kZonalScale * basis[ShIndex(2, m)] * z;
  }
  return reduced;
}

std::vector<NamedRegister> PackShOrder(const Sh9Rgb& sh, ShOrder order) {
  std::vector<NamedRegister> out;
  switch (order) {
    case ShOrder::kOrder0: {
      const glm::dvec3 e = kShC0 * sh.at(0, 0);
      out.push_back({"cE", "(c0 R00, c0 G00, c0 B00, unused)", ToFloat(e.r, e.g, e.b, 0.0)});
      break;
    }
    case ShOrder::kOrder1:
      AddLinearRegisters(sh, kShC0 * sh.at(0, 0), "c0 {0}00", out);
      break;
    case ShOrder::kZh3: {
      const glm::dvec3 axis = Zh3Axis(sh);
      const glm::dvec3 z = ZonalCoefficient(sh, axis);
      AddLinearRegisters(sh, kShC0 * sh.at(0, 0) - kShC3 * z, "c0 {0}00 - c3 z{0}", out);
      out.push_back({"cAxis", "(a, unused): the luminance direction of the linear band",
                     ToFloat(axis.x, axis.y, axis.z, 0.0)});
      const glm::dvec3 quadratic = 3.0 * kShC3 * z;
      out.push_back({"cZ", "(3 c3 zR, 3 c3 zG, 3 c3 zB, unused): z = band 2's zonal coefficient around a",
                     ToFloat(quadratic.r, quadratic.g, quadratic.b, 0.0)});
      break;
    }
    case ShOrder::kOrder2: {
      const SevenConstants k = PackTable1(sh);
      for (std::size_t i = 0; i < k.registers.size(); ++i) {
        out.push_back({SevenConstants::kNames[i], Table1Contents(static_cast<int>(i)), k.registers[i]});
      }
      break;
    }
  }
  assert(static_cast<int>(out.size()) == Info(order).constant_registers);
  return out;
}

glm::dvec3 EvaluateShOrder(std::span<const NamedRegister> registers, ShOrder order, glm::dvec3 n) {
  assert(static_cast<int>(registers.size()) == Info(order).constant_registers);
  auto reg = [&](int i) { return glm::dvec4(registers[static_cast<std::size_t>(i)].value); };
  if (order == ShOrder::kOrder0) return glm::dvec3(reg(0));
  if (order == ShOrder::kOrder2) {
    SevenConstants k;
    for (std::size_t i = 0; i < k.registers.size(); ++i) k.registers[i] = registers[i].value;
    return EvaluateTable1(k, n);
  }
  const glm::dvec4 v(n, 1.0);
  glm::dvec3 e(glm::dot(v, reg(0)), glm::dot(v, reg(1)), glm::dot(v, reg(2)));
  if (order == ShOrder::kZh3) {
    const double t = glm::dot(n, glm::dvec3(reg(3)));
    e += glm::dvec3(reg(4)) * (t * t);
  }
  return e;
}

}  // namespace vs11
