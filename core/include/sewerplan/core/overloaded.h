// SPDX-License-Identifier: MIT
// Overloaded: a set of lambdas as one visitor for std::visit over a variant (plans, jobs, events).
//
//   std::visit(Overloaded{[](const DriveForward& j) { ... }, [](const auto&) { ... }}, job);
//
// Thread safety: A compile-time helper: nothing shared.
#pragma once

namespace sewerplan {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace sewerplan
