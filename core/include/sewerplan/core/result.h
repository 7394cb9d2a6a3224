// SPDX-License-Identifier: MIT
// Result<T>: a value or an Error, for failures that are expected (bad input, no plan, timeout).
//
// Modelled on std::expected (not available to clang 14 with libstdc++ 12, which the fuzz builds
// use). An Error carries a code from one closed enum and a message for people; the message of a
// load error lists every problem found, one "where: error: what" line each.
//
//   Result<SewerMap> map = read_map("ais.json", diagnostics);
//   if (!map.has_value()) {
//     std::cerr << map.error().message << '\n';
//     return 1;
//   }
//   use(*map);
//
// There is no implicit conversion to bool: ask has_value().
//
// Thread safety: Result and Error are plain values: const access from several threads is safe.
#pragma once

#include <ostream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "sewerplan/core/check.h"

namespace sewerplan {

// Why an operation failed. Each library adds its codes here so that an Error can cross layers
// unchanged; prefer the most specific code.
enum class ErrorCode {
  kIo,                 // a file could not be read or written
  kParse,              // the file is not well-formed in its format
  kInvalidMap,         // the map is well-formed but inconsistent (dangling reference, ...)
  kInvalidMission,     // the mission names unknown objects or is inconsistent
  kInvalidProfile,     // the robot profile is missing or has impossible values
  kInvalidArgument,    // a caller passed a value outside the documented range
  kUnsupportedFormat,  // the file format is not one sewerplan reads or writes
  kNoPlan,             // no plan exists: a task, an exit or the battery is out of reach
  kSearchLimit,        // the search stopped at its time or expansion limit without a plan
  kCancelled,          // the search was cancelled from another thread
  kCanTimeout,         // a CAN peer did not answer within its deadline (hal/can/)
  kBusError,           // a CAN bus or adapter failed: bus-off, no CAN support, a broken link
};

std::string_view to_string(ErrorCode code);

struct Error {
  ErrorCode code;
  std::string message;
  friend bool operator==(const Error&, const Error&) = default;
};

std::ostream& operator<<(std::ostream& os, const Error& error);

template <class T>
class [[nodiscard]] Result {
 public:
  using value_type = T;
  Result(T value) : data_(std::in_place_index<0>, std::move(value)) {}      // NOLINT: implicit
  Result(Error error) : data_(std::in_place_index<1>, std::move(error)) {}  // NOLINT: implicit

  bool has_value() const { return data_.index() == 0; }

  T& value() & {
    SEWER_CHECK(has_value(), "Result::value() called on an error");
    return std::get<0>(data_);
  }
  const T& value() const& {
    SEWER_CHECK(has_value(), "Result::value() called on an error");
    return std::get<0>(data_);
  }
  T&& value() && {
    SEWER_CHECK(has_value(), "Result::value() called on an error");
    return std::get<0>(std::move(data_));
  }
  const Error& error() const {
    SEWER_CHECK(!has_value(), "Result::error() called on a value");
    return std::get<1>(data_);
  }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  std::variant<T, Error> data_;
};

// Result<void>: success or an Error.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit
  bool has_value() const { return ok_; }
  const Error& error() const {
    SEWER_CHECK(!ok_, "Result::error() called on a success");
    return error_;
  }

 private:
  Error error_{ErrorCode::kInvalidArgument, {}};
  bool ok_ = true;
};

}  // namespace sewerplan
