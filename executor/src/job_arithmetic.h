// SPDX-License-Identifier: MIT
// Job arithmetic: the rest of a drive, the same drive longer, a drive the other way, a push.
//
// Private to executor. Staged recovery (staged_recovery.h) builds its manoeuvres from the job
// that failed: it resumes the rest after a reboot, backs up and drives the distance again, backs
// off from a danger, pushes over the rest. These are the pure functions behind that.
#pragma once

#include <optional>
#include <string>

#include "sewerplan/core/job.h"
#include "sewerplan/hal/obstacle_clearing.h"

namespace sewerplan::executor::detail {

// Where a blocked drive's failure is placed: this far ahead of where the robot stopped, so that
// the plan made next has the robot before it, not on it.
inline constexpr double kBlockageAhead_m = 0.001;

// The rest of a drive after `done_m`, or nothing for a job that is not a drive.
std::optional<Job> rest_of(const Job& job, double done_m);
// The same drive the other way (forward for backward); any other job unchanged.
Job reversed(const Job& job);

// The distance a drive, push or scan has to go; 0 for any other job.
double distance_left_m(const Job& job);

// The same drive, `extra_m` longer (after backing up that far).
Job lengthened(const Job& job, double extra_m);

// A drive of `distance_m` the other way, at the job's speed.
Job back_off(const Job& job, double distance_m);

// A push over the rest of a drive, the same way (forward with the front head, backward with the
// rear one); none for a job that is not a drive.
std::optional<Job> push_for(const Job& job);

// How a drive meets what stops it: front first (forward) or rear first (backward); front for a job
// that is not a drive.
hal::Approach approach_of(const Job& job);

// Whether `job` is a drive that ends at a manhole's mouth (DriveForward/DriveBackward::to_manhole):
// reported done, the robot is at that manhole (core/job.h).
bool ends_at_manhole(const Job& job);

// The job as the event log writes it.
std::string job_text(const Job& job);

}  // namespace sewerplan::executor::detail
