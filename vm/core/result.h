// The one way a library call that can fail reports it: a Result<T> holds either the value or the
// Diagnostic that says why there is none (its code, its message, and the file:line:column where
// there is one); Status is the Result of a call that returns nothing else. A pass that finds many
// problems in source text collects them in Diagnostics instead (diagnostic.h) and returns those.
//
//   Result<Mesh> DecodeMesh(...);            // return mesh;  or  return Failure(code, "why");
//   if (Result<Mesh> mesh = DecodeMesh(bytes); !mesh) Report(mesh.error().message);
//
// Reading the value of a failed Result (or the error of a successful one) is a programmer error: it
// prints the diagnostic and aborts, also in release builds, rather than reading garbage. message()
// is empty on success.
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "vm/core/diagnostic.h"

namespace vs11 {

// The Diagnostic of a failed call, an error: `return Failure(DiagnosticCode::kX, "why");`.
Diagnostic Failure(DiagnosticCode code, std::string message, SourceLoc loc = {});

namespace result_detail {
[[noreturn]] void ValueOfFailedResult(const Diagnostic& error);
[[noreturn]] void ErrorOfSuccessfulResult();
}  // namespace result_detail

template <class T>
class [[nodiscard]] Result {
  static_assert(!std::is_same_v<std::remove_cv_t<T>, Diagnostic>, "a Result carries a value or a Diagnostic");

 public:
  // Anything T is made from (a derived unique_ptr for a unique_ptr to its base, a braced list).
  template <class U = T>
    requires(std::is_constructible_v<T, U &&> && !std::is_same_v<std::remove_cvref_t<U>, Result> &&
             !std::is_same_v<std::remove_cvref_t<U>, Diagnostic>)
  Result(U&& value) : state_(std::in_place_index<0>, std::forward<U>(value)) {}  // NOLINT: implicit
  Result(Diagnostic error) : state_(std::in_place_index<1>, std::move(error)) {}  // NOLINT: implicit

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & {
    CheckOk();
    return std::get<0>(state_);
  }
  const T& value() const& {
    CheckOk();
    return std::get<0>(state_);
  }
  T&& value() && {
    CheckOk();
    return std::get<0>(std::move(state_));
  }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Diagnostic& error() const {
    if (ok()) result_detail::ErrorOfSuccessfulResult();
    return std::get<1>(state_);
  }
  // The error's message; empty on success (for messages and test output).
  std::string message() const { return ok() ? std::string() : error().message; }

 private:
  void CheckOk() const {
    if (!ok()) result_detail::ValueOfFailedResult(std::get<1>(state_));
  }
  std::variant<T, Diagnostic> state_;
};

// The result of a call that returns nothing but whether it worked.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Diagnostic error) : error_(std::move(error)) {}  // NOLINT: implicit

  bool ok() const { return !error_.has_value(); }
  explicit operator bool() const { return ok(); }
  const Diagnostic& error() const {
    if (ok()) result_detail::ErrorOfSuccessfulResult();
    return *error_;
  }
  std::string message() const { return ok() ? std::string() : error().message; }

 private:
  std::optional<Diagnostic> error_;
};

using Status = Result<void>;

}  // namespace vs11
