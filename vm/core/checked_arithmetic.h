// Sums and products of numbers a user gave (a --stride, an --element offset, a .npy shape, a vertex
// count) that become sizes or addresses: each returns the exact result in T, or nullopt where it
// does not fit, instead of wrapping around to a small number that passes every later check.
#pragma once

#include <optional>

namespace vs11 {

// a + b in T, or nullopt when the exact sum is outside T's range (negative, for an unsigned T).
template <class T, class A, class B>
constexpr std::optional<T> CheckedAdd(A a, B b) {
  T sum{};
  if (__builtin_add_overflow(a, b, &sum)) return std::nullopt;
  return sum;
}

// a * b in T, or nullopt when the exact product is outside T's range.
template <class T, class A, class B>
constexpr std::optional<T> CheckedMul(A a, B b) {
  T product{};
  if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
  return product;
}

// offset + count * size in T (the end of `count` items of `size` bytes at `offset`), or nullopt.
template <class T, class A, class B, class C>
constexpr std::optional<T> CheckedEnd(A offset, B count, C size) {
  const std::optional<T> bytes = CheckedMul<T>(count, size);
  return bytes ? CheckedAdd<T>(offset, *bytes) : std::nullopt;
}

}  // namespace vs11
