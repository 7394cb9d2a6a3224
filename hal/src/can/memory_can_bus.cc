// SPDX-License-Identifier: MIT
#include <chrono>

#include "sewerplan/hal/can/can_bus.h"

#include "can_text.h"

namespace sewerplan::hal {

struct MemoryCanBus::Shared {
  std::mutex mutex;
  std::condition_variable arrived;
  std::deque<Item> queues[2];  // queues[i]: waiting for side i
  bool bus_off = false;
};

MemoryCanBus::MemoryCanBus(std::shared_ptr<Shared> shared, int side, std::string name)
    : shared_(std::move(shared)), side_(side), name_(std::move(name)) {}

std::pair<std::unique_ptr<MemoryCanBus>, std::unique_ptr<MemoryCanBus>> make_memory_can_pair() {
  auto shared = std::make_shared<MemoryCanBus::Shared>();
  return {std::unique_ptr<MemoryCanBus>(new MemoryCanBus(shared, 0, "memory:a")),   // NOLINT
          std::unique_ptr<MemoryCanBus>(new MemoryCanBus(shared, 1, "memory:b"))};  // NOLINT
}

Result<void> MemoryCanBus::send(const CanFrame& frame) {
  const std::lock_guard lock(shared_->mutex);
  if (shared_->bus_off) return Error{ErrorCode::kBusError, name_ + ": bus-off"};
  shared_->queues[1 - side_].emplace_back(frame);
  shared_->arrived.notify_all();
  return {};
}

Result<std::optional<CanFrame>> MemoryCanBus::receive(double timeout_s) {
  std::unique_lock lock(shared_->mutex);
  auto& queue = shared_->queues[side_];
  shared_->arrived.wait_for(lock, std::chrono::duration<double>(timeout_s),
                            [&] { return !queue.empty(); });
  if (queue.empty()) return std::optional<CanFrame>();
  Item item = std::move(queue.front());
  queue.pop_front();
  if (auto* error = std::get_if<Error>(&item)) return *error;
  return std::optional<CanFrame>(std::get<CanFrame>(item));
}

Result<void> MemoryCanBus::recover() {
  const std::lock_guard lock(shared_->mutex);
  shared_->bus_off = false;
  return {};
}

void MemoryCanBus::write_garbage(std::string_view bytes) {
  const std::lock_guard lock(shared_->mutex);
  shared_->queues[1 - side_].emplace_back(
      Error{ErrorCode::kParse, name_ + ": garbage on the bus: '" + printable(bytes) + "'"});
  shared_->arrived.notify_all();
}

void MemoryCanBus::enter_bus_off() {
  const std::lock_guard lock(shared_->mutex);
  shared_->bus_off = true;
}

}  // namespace sewerplan::hal
