// Exceptions out of OpenMP parallel loops. An exception that leaves a parallel region calls
// std::terminate (SIGABRT, no message); each iteration runs through `run`, which keeps the
// exception of the lowest iteration (the one a serial loop would have met first, whatever the
// thread count) and lets the others finish; `rethrow` throws it after the region.
#pragma once

#include <climits>
#include <exception>
#include <mutex>

namespace qf {

class ParallelErrors {
 public:
  // Calls f(); an exception it throws is kept (the lowest `iteration`'s wins), not propagated.
  template <class F>
  void run(long long iteration, F&& f) noexcept {
    try {
      f();
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_ || iteration < first_) error_ = std::current_exception(), first_ = iteration;
    }
  }
  // After the region: throws the kept exception, if any.
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr error_;
  long long first_ = LLONG_MAX;
};

}  // namespace qf
