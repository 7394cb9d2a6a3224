// SPDX-License-Identifier: MIT
#include "sewerplan/executor/background_replan.h"

#include <chrono>
#include <stop_token>

namespace sewerplan::executor {

BackgroundReplan::BackgroundReplan(Replanner& replanner, std::optional<Failure> failure,
                                   std::string reason) {
  std::promise<Result<PlanResponse>> promise;
  answer_ = promise.get_future();
  thread_ =
      std::jthread([this, &replanner, failure = std::move(failure), reason = std::move(reason),
                    promise = std::move(promise)](std::stop_token stop) mutable {
        const std::stop_callback on_stop(stop, [this] { cancel_.store(true); });
        promise.set_value(replanner.plan_cancellable(failure, reason, cancel_));
      });
}

BackgroundReplan::~BackgroundReplan() { cancel(); }  // the jthread joins

void BackgroundReplan::cancel() { thread_.request_stop(); }

bool BackgroundReplan::ready() const {
  // After get() the future is empty: the answer was there.
  return !answer_.valid() || answer_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

Result<PlanResponse> BackgroundReplan::get() { return answer_.get(); }

}  // namespace sewerplan::executor
