#pragma once
// Internal to the HTTP transport plugin: cpp-httplib's task queue with a fixed number of threads
// and a bound on the connections waiting for one. httplib accepts a connection, then enqueues it;
// when `max_waiting` connections wait already, enqueue() blocks the accepting thread, so that
// further connections wait in the kernel's listen backlog instead of holding descriptors and
// memory in the process (a flood of connections must not starve the robot server of descriptors).
#include <httplib.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace binpick::web::detail {

class BoundedTaskQueue : public httplib::TaskQueue {
 public:
  // `stopping` set: enqueue() no longer blocks (the server is shutting down).
  BoundedTaskQueue(std::size_t threads, std::size_t max_waiting, std::shared_ptr<const std::atomic<bool>> stopping);
  ~BoundedTaskQueue() override;
  void enqueue(std::function<void()> job) override;
  void shutdown() override;  // runs the jobs queued, then joins the threads

 private:
  void work();
  std::size_t max_waiting_;
  std::shared_ptr<const std::atomic<bool>> stopping_;
  std::mutex mutex_;
  std::condition_variable job_ready_, room_;
  std::deque<std::function<void()>> jobs_;
  bool shut_down_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace binpick::web::detail
