#include "vm/mesh/smooth_normals.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vs11::mesh {
namespace {

bool IsFinite(const Vec3f& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// A position as a sort key in which +0 and -0 are one value (adding +0 turns -0 into +0).
Vec3f PositionKey(const Vec3f& p) { return {p[0] + 0.0f, p[1] + 0.0f, p[2] + 0.0f}; }

Vec3d TwiceAreaNormal(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  Vec3d u{}, v{};
  for (int k = 0; k < 3; ++k) {
    u[k] = static_cast<double>(b[k]) - a[k];
    v[k] = static_cast<double>(c[k]) - a[k];
  }
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

Vec3d Normalised(const Vec3d& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 0.0) || !std::isfinite(length)) return {};
  return {v[0] / length, v[1] / length, v[2] / length};
}

}  // namespace

bool IsUsableNormal(const Vec3f& n) { return IsFinite(n) && (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f); }

std::vector<Vec3d> AreaWeightedNormals(std::span<const Vec3f> positions, std::span<const std::uint32_t> triangles) {
  std::vector<Vec3d> sums(positions.size(), Vec3d{});
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const Vec3f& a = positions[triangles[t]];
    const Vec3f& b = positions[triangles[t + 1]];
    const Vec3f& c = positions[triangles[t + 2]];
    if (!IsFinite(a) || !IsFinite(b) || !IsFinite(c)) continue;
    const Vec3d face = TwiceAreaNormal(a, b, c);
    for (std::size_t corner = t; corner < t + 3; ++corner) {
      for (int k = 0; k < 3; ++k) sums[triangles[corner]][k] += face[k];
    }
  }
  // Vertices at one position, found by sorting (finite positions only: NaN has no order), share the
  // sum of all their triangles.
  std::vector<std::uint32_t> order;
  order.reserve(positions.size());
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (IsFinite(positions[v])) order.push_back(v);
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Vec3f key_a = PositionKey(positions[a]), key_b = PositionKey(positions[b]);
    return key_a != key_b ? key_a < key_b : a < b;
  });
  std::vector<Vec3d> normals(positions.size(), Vec3d{});
  for (std::size_t first = 0, end = 0; first < order.size(); first = end) {
    const Vec3f key = PositionKey(positions[order[first]]);
    Vec3d sum{};
    for (end = first; end < order.size() && PositionKey(positions[order[end]]) == key; ++end) {
      for (int k = 0; k < 3; ++k) sum[k] += sums[order[end]][k];
    }
    const Vec3d normal = Normalised(sum);
    for (std::size_t i = first; i < end; ++i) normals[order[i]] = normal;
  }
  return normals;
}

}  // namespace vs11::mesh
