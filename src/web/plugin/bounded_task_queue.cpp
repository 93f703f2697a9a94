#include "bounded_task_queue.hpp"

#include <chrono>

namespace binpick::web::detail {

BoundedTaskQueue::BoundedTaskQueue(std::size_t threads, std::size_t max_waiting,
                                   std::shared_ptr<const std::atomic<bool>> stopping)
    : max_waiting_(max_waiting), stopping_(std::move(stopping)) {
  for (std::size_t i = 0; i < threads; ++i) threads_.emplace_back([this] { work(); });
}

BoundedTaskQueue::~BoundedTaskQueue() { shutdown(); }

void BoundedTaskQueue::enqueue(std::function<void()> job) {
  std::unique_lock<std::mutex> lock(mutex_);
  // Checked every 100 ms: stop() sets the flag from another thread without this queue's lock.
  while (jobs_.size() >= max_waiting_ && !stopping_->load()) room_.wait_for(lock, std::chrono::milliseconds(100));
  jobs_.push_back(std::move(job));  // even when stopping: the job closes its connection
  job_ready_.notify_one();
}

void BoundedTaskQueue::shutdown() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (shut_down_) return;
    shut_down_ = true;
  }
  job_ready_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void BoundedTaskQueue::work() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      job_ready_.wait(lock, [&] { return !jobs_.empty() || shut_down_; });
      if (jobs_.empty()) return;  // shut down with nothing left
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    room_.notify_one();
    job();
  }
}

}  // namespace binpick::web::detail
