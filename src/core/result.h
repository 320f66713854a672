// Error values for anything that comes from the outside world (files, contexts,
// shaders): docs/design.md §6. Internal invariants use LODLINE_ASSERT instead.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace lodline {

/// What went wrong, in one line a user can act on ("mesh.off: line 12: vertex index 40 out
/// of range (20 vertices)"). `kind` selects the process exit code in the apps.
struct Error {
  enum class Kind {
    kUsage,    ///< bad command line or option value: exit code 2
    kRuntime,  ///< bad file, failed context, failed write: exit code 1
  };
  Kind kind = Kind::kRuntime;
  std::string message;

  static Error usage(std::string msg) { return {Kind::kUsage, std::move(msg)}; }
  static Error runtime(std::string msg) { return {Kind::kRuntime, std::move(msg)}; }
  int exitCode() const { return kind == Kind::kUsage ? 2 : 1; }
};

/// A value or an Error. Small stand-in for C++23 std::expected.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Error error) : v_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & { assert(ok()); return std::get<0>(v_); }
  const T& value() const& { assert(ok()); return std::get<0>(v_); }
  T&& value() && { assert(ok()); return std::get<0>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const Error& error() const { assert(!ok()); return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

/// Result of an operation that returns nothing on success.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT
  static Status success() { return {}; }
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { assert(!ok_); return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

}  // namespace lodline

/// Debug-only check of an internal invariant (compiled out in release builds).
#define LODLINE_ASSERT(cond) assert(cond)
