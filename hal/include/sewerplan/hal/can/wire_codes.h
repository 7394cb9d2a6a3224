// SPDX-License-Identifier: MIT
// The codes on the CAN bus for the job kinds (a JOB's header byte 0) and for the errors (a
// RESULT's outcome byte), written out once, beside the kind they stand for, and checked at compile
// time: every kind has exactly one code, no two share one, and decoding gives back what was
// encoded. The wire is these tables, not the order of a C++ type: reordering the Job variant or
// the RobotErrorCause enum changes nothing on the bus. docs/can-protocol.md lists them; the golden
// frames (tests/hal/can_golden_test.cc) hold them to it.
//
//   std::uint8_t code = job_code(job);                        // DriveForward: 1
//   std::optional<Job> blank = blank_job(code);               // DriveForward{}, or empty
//   std::uint8_t outcome = error_code(RobotErrorCause::kLink);  // 0x35
//   std::optional<RobotErrorCause> cause = error_cause(0x03);   // kOtherMalfunction
//
// Thread safety: constants and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <variant>

#include "sewerplan/core/job.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::hal {

// --- Job kinds
// ------------------------------------------------------------------------------------

// The code of each job kind; a kind of Job without one here does not compile (below).
template <class J>
inline constexpr std::uint8_t kJobCode = 0;
template <>
inline constexpr std::uint8_t kJobCode<DriveForward> = 1;
template <>
inline constexpr std::uint8_t kJobCode<DriveBackward> = 2;
template <>
inline constexpr std::uint8_t kJobCode<Push> = 3;
template <>
inline constexpr std::uint8_t kJobCode<TurnInManhole> = 4;
template <>
inline constexpr std::uint8_t kJobCode<EnterPipeFromManhole> = 5;
template <>
inline constexpr std::uint8_t kJobCode<LiftHead> = 6;
template <>
inline constexpr std::uint8_t kJobCode<LowerHead> = 7;
template <>
inline constexpr std::uint8_t kJobCode<TakeSample> = 8;
template <>
inline constexpr std::uint8_t kJobCode<Scan> = 9;
template <>
inline constexpr std::uint8_t kJobCode<Stop> = 10;

namespace wire_detail {

inline constexpr std::size_t kJobKinds = std::variant_size_v<Job>;

template <std::size_t... I>
constexpr std::array<std::uint8_t, kJobKinds> job_codes(std::index_sequence<I...> /*kinds*/) {
  return {kJobCode<std::variant_alternative_t<I, Job>>...};
}

// By the Job variant's index: a lookup, the values are the table's.
inline constexpr std::array<std::uint8_t, kJobKinds> kJobCodes =
    job_codes(std::make_index_sequence<kJobKinds>{});

// The Job variant's index of the kind with `code`; empty for a code no kind has.
constexpr std::optional<std::size_t> job_index(std::uint8_t code) {
  for (std::size_t i = 0; i < kJobKinds; ++i) {
    if (kJobCodes[i] == code) return i;
  }
  return std::nullopt;
}

constexpr bool every_job_kind_has_one_code() {
  for (std::size_t i = 0; i < kJobKinds; ++i) {
    if (kJobCodes[i] == 0) return false;  // 0 is no kind
    for (std::size_t j = i + 1; j < kJobKinds; ++j) {
      if (kJobCodes[i] == kJobCodes[j]) return false;
    }
  }
  return true;
}

constexpr bool job_decoding_inverts_encoding() {
  for (std::size_t i = 0; i < kJobKinds; ++i) {
    if (job_index(kJobCodes[i]) != i) return false;
  }
  for (unsigned code = 0; code < 256; ++code) {
    const std::optional<std::size_t> i = job_index(static_cast<std::uint8_t>(code));
    if (i && kJobCodes[*i] != code) return false;
  }
  return true;
}

static_assert(every_job_kind_has_one_code(),
              "every kind of Job needs a code of its own on the CAN bus (kJobCode)");
static_assert(job_decoding_inverts_encoding());

template <std::size_t... I>
constexpr std::array<Job (*)(), kJobKinds> job_makers(std::index_sequence<I...> /*kinds*/) {
  return {+[]() -> Job { return std::variant_alternative_t<I, Job>{}; }...};
}

}  // namespace wire_detail

// The code of `job`'s kind on the bus.
inline std::uint8_t job_code(const Job& job) { return wire_detail::kJobCodes[job.index()]; }

// A job of the kind with `code`, every field at its default (the decoder fills it in); empty for
// a code no kind has.
inline std::optional<Job> blank_job(std::uint8_t code) {
  static constexpr auto kMakers =
      wire_detail::job_makers(std::make_index_sequence<wire_detail::kJobKinds>{});
  const std::optional<std::size_t> i = wire_detail::job_index(code);
  if (!i) return std::nullopt;
  return kMakers[*i]();
}

// --- Errors -------------------------------------------------------------------------------------

// A RESULT's outcome byte: 0 for a job that was done, else the error's code. Codes 1 to 3 are the
// kinds alone (the codes of earlier versions, which a node of an earlier version still sends);
// the typed causes have the kind in the high nibble (0x1_ BLOCKAGE, 0x2_ DANGER, 0x3_
// MALFUNCTION), so that a candump log reads.
inline constexpr std::uint8_t kDoneCode = 0;

struct ErrorCodeRow {
  RobotErrorCause cause;
  std::uint8_t code;
};

inline constexpr std::array<ErrorCodeRow, kRobotErrorCauses> kErrorCodes{{
    {RobotErrorCause::kOtherBlockage, 0x01},
    {RobotErrorCause::kOtherDanger, 0x02},
    {RobotErrorCause::kOtherMalfunction, 0x03},
    {RobotErrorCause::kObstacle, 0x11},
    {RobotErrorCause::kBlindEnd, 0x12},
    {RobotErrorCause::kNoManholeSeen, 0x13},
    {RobotErrorCause::kNoMouth, 0x14},
    {RobotErrorCause::kDangerSpot, 0x21},
    {RobotErrorCause::kDangerousPassage, 0x22},
    {RobotErrorCause::kFault, 0x31},
    {RobotErrorCause::kBatteryEmpty, 0x32},
    {RobotErrorCause::kInvalidJob, 0x33},
    {RobotErrorCause::kEmergencyStop, 0x34},
    {RobotErrorCause::kLink, 0x35},
    {RobotErrorCause::kNotAtStart, 0x36},
}};

// The cause with `code`; empty for kDoneCode and for a code no cause has.
constexpr std::optional<RobotErrorCause> error_cause(std::uint8_t code) {
  for (const ErrorCodeRow& row : kErrorCodes) {
    if (row.code == code) return row.cause;
  }
  return std::nullopt;
}

// The code of `cause`.
constexpr std::uint8_t error_code(RobotErrorCause cause) {
  for (const ErrorCodeRow& row : kErrorCodes) {
    if (row.cause == cause) return row.code;
  }
  return kDoneCode;  // unreachable: every cause has a row (below)
}

namespace wire_detail {

constexpr bool every_cause_has_one_code() {
  for (std::size_t c = 0; c < kRobotErrorCauses; ++c) {
    std::size_t rows = 0;
    for (const ErrorCodeRow& row : kErrorCodes) {
      if (static_cast<std::size_t>(row.cause) == c) ++rows;
    }
    if (rows != 1) return false;
  }
  for (std::size_t i = 0; i < kErrorCodes.size(); ++i) {
    if (static_cast<std::size_t>(kErrorCodes[i].cause) >= kRobotErrorCauses) return false;
    if (kErrorCodes[i].code == kDoneCode) return false;
    for (std::size_t j = i + 1; j < kErrorCodes.size(); ++j) {
      if (kErrorCodes[i].code == kErrorCodes[j].code) return false;
    }
  }
  return true;
}

// Codes 1-3 are the kinds of earlier versions; a typed cause's high nibble is its kind's code.
constexpr bool codes_follow_the_kinds() {
  for (const ErrorCodeRow& row : kErrorCodes) {
    const auto kind_code = static_cast<std::uint8_t>(1 + static_cast<int>(kind_of(row.cause)));
    const bool other = row.cause == other_cause(kind_of(row.cause));
    if (other ? row.code != kind_code : (row.code >> 4U) != kind_code) return false;
  }
  return true;
}

constexpr bool error_decoding_inverts_encoding() {
  for (const ErrorCodeRow& row : kErrorCodes) {
    if (error_cause(error_code(row.cause)) != row.cause) return false;
  }
  for (unsigned code = 0; code < 256; ++code) {
    const std::optional<RobotErrorCause> c = error_cause(static_cast<std::uint8_t>(code));
    if (c && error_code(*c) != code) return false;
  }
  return true;
}

static_assert(every_cause_has_one_code(),
              "every RobotErrorCause needs exactly one code of its own on the CAN bus, not 0");
static_assert(codes_follow_the_kinds());
static_assert(error_decoding_inverts_encoding());

}  // namespace wire_detail

}  // namespace sewerplan::hal
