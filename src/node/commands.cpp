#include "commands.hpp"

namespace mpm_sdem::node {

Reply CommandQueue::call(Command command) {
  std::future<Reply> reply;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return {false, reason_};
    items_.push_back({std::move(command), {}});
    reply = items_.back().reply.get_future();
  }
  // No time-out: the loop either runs the command or refuses it in close().
  return reply.get();
}

void CommandQueue::post(Command command) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!closed_) items_.push_back({std::move(command), {}});
}

void CommandQueue::runPending(SimLoop& sim) {
  std::deque<Item> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    batch.swap(items_);
  }
  for (Item& item : batch) {
    try {
      item.reply.set_value(item.command(sim));
    } catch (const std::exception& e) {
      // A request the checks let through but the core refused: the world is unchanged.
      item.reply.set_value({false, e.what()});
    }
  }
}

void CommandQueue::close(const std::string& reason) {
  std::deque<Item> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    reason_ = reason;
    batch.swap(items_);
  }
  for (Item& item : batch) item.reply.set_value({false, reason});
}

}  // namespace mpm_sdem::node
