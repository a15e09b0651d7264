// Requests from ROS callbacks, applied by the simulation loop between steps (the
// diff_drive_controller pattern). A callback validates what it can alone, then queues a command
// and waits for its reply; the loop runs each command between two steps, or refuses it when the
// node is shutting down. The simulation never sees a request half-applied.
#pragma once

#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <string>

namespace mpm_sdem::node {

class SimLoop;

struct Reply {
  bool success = false;
  std::string message;
};

class CommandQueue {
 public:
  using Command = std::function<Reply(SimLoop&)>;

  // From a callback thread: queues the command and blocks until the loop has run or refused it.
  Reply call(Command command);
  // From a callback thread: queues without waiting (streamed commands); the reply is dropped.
  void post(Command command);
  // Loop thread, between steps: runs every queued command in arrival order.
  void runPending(SimLoop& sim);
  // Loop thread, on exit: refuses what is queued and everything queued later.
  void close(const std::string& reason);

 private:
  struct Item {
    Command command;
    std::promise<Reply> reply;
  };
  std::mutex mutex_;
  std::deque<Item> items_;
  bool closed_ = false;
  std::string reason_;
};

}  // namespace mpm_sdem::node
