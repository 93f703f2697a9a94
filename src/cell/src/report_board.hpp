#pragma once
// Internal: where CellService publishes its CellReport. Writers (the service's threads) build the
// next report aside and swap it in; readers copy a pointer. The read lock is held only for that
// swap or copy, so a reader never delays the cycle, whatever it does with its copy.
#include <memory>
#include <mutex>
#include <utility>

#include "binpick/cell/cell_report.hpp"

namespace binpick::cell {

class ReportBoard {
 public:
  std::shared_ptr<const CellReport> read() const {
    const std::lock_guard<std::mutex> lock(read_mutex_);
    return current_;
  }
  // `change(CellReport&)` edits a copy of the current report, which then replaces it.
  template <typename Change>
  void update(const Change& change) {
    const std::lock_guard<std::mutex> writing(write_mutex_);
    auto next = std::make_shared<CellReport>(*current_);
    change(*next);
    std::shared_ptr<const CellReport> previous;  // destroyed after the read lock is released
    {
      const std::lock_guard<std::mutex> lock(read_mutex_);
      previous = std::exchange(current_, std::move(next));
    }
  }

 private:
  std::mutex write_mutex_;  // one writer at a time: no change is lost
  mutable std::mutex read_mutex_;
  std::shared_ptr<const CellReport> current_ = std::make_shared<const CellReport>();
};

}  // namespace binpick::cell
