// SPDX-License-Identifier: MIT
// The Python module's shared pieces: the handles Python holds, and how errors become exceptions.
//
// Python objects must not outlive what the C++ values refer to: a Mission refers to its map by
// IDs, a plan to its mission, the Replanner to its map by reference. So Python holds handles that
// own (through shared_ptr) the map and mission they need: a MissionHandle keeps its map alive, a
// PlanHandle its mission. Library errors (Result) become `sewerplan.Error` exceptions with the
// error's code ("no-plan", "parse", ...), its message and the readers' diagnostics, each naming
// its file and line or JSON path (raise_error). Three translation units (module.cc: maps,
// profiles, missions; planning.cc: plan, check, Replanner; simulation.cc: simulate, campaign)
// keep the compile time of pybind11's templates down.
#pragma once
#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

#include <pybind11/pybind11.h>

namespace sewerplan::python {

namespace py = pybind11;

struct MissionHandle {
  std::shared_ptr<const SewerMap> map;
  Mission mission;
};

struct PlanHandle {
  std::shared_ptr<const MissionHandle> mission;
  domain::Plan plan;
  domain::MissionProgress start;  // where the plan begins
  std::uint8_t start_heading_end = 1;
};

// A cancel flag for plan() and the Replanner, settable from any Python thread. plan() marks it
// entered once it runs without the GIL, so that a test can show another thread runs meanwhile.
class CancelToken {
 public:
  void cancel() { flag_.store(true); }
  bool cancelled() const { return flag_.load(); }
  const std::atomic<bool>& flag() const { return flag_; }
  void mark_entered();
  // Blocks (without the GIL) until a call using this token runs without the GIL.
  void wait_entered();

 private:
  std::atomic<bool> flag_{false};
  std::mutex mutex_;
  std::condition_variable entered_cv_;
  bool entered_ = false;
};

// Raises sewerplan.Error with `error`'s code and message and the diagnostics' list. Call with
// the GIL held.
[[noreturn]] void raise_error(const Error& error, const Diagnostics* diagnostics = nullptr);

template <class T>
T value_or_raise(Result<T> result, const Diagnostics* diagnostics = nullptr) {
  if (!result.has_value()) raise_error(result.error(), diagnostics);
  return std::move(*result);
}

// A value class's __repr__, "<PlanOutcome cost_s=585.377 optimal=True algorithm='astar'>": the
// type and the fields that tell one value from another; reals with 6 significant digits, strings
// quoted as Python quotes them, None for a missing value.
class Repr {
 public:
  explicit Repr(std::string_view type) { out_ << '<' << type; }
  // A bare word after the type: "<Manhole M1 ...>".
  Repr& word(std::string_view text) {
    out_ << ' ' << text;
    return *this;
  }
  template <class T>
  Repr& field(std::string_view name, const T& value) {
    out_ << ' ' << name << '=';
    put(value);
    return *this;
  }
  std::string str() const { return out_.str() + '>'; }

 private:
  void put(const std::string& s) { out_ << std::string(py::repr(py::str(s))); }
  void put(const char* s) { put(std::string(s)); }
  void put(bool b) { out_ << (b ? "True" : "False"); }
  void put(double d) { out_ << d; }
  template <class T>
  void put(const std::optional<T>& v) {
    if (v) {
      put(*v);
    } else {
      out_ << "None";
    }
  }
  template <class T>
  requires std::is_integral_v<T>
  void put(T v) { out_ << v; }
  std::ostringstream out_;
};

// Name lookups for arguments given by name; an unknown name raises sewerplan.Error
// (invalid-argument) naming it.
ManholeId manhole_named(const SewerMap& map, const std::string& name);
PipeId pipe_named(const SewerMap& map, const std::string& name);

void bind_maps(py::module_& m);
void bind_planning(py::module_& m);
void bind_simulation(py::module_& m);

}  // namespace sewerplan::python
