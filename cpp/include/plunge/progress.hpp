// Progress and cancellation of a long plan: a callback told how far planning
// got, able to stop it; and a flag any worker thread checks cheaply.
#pragma once
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "plunge/error.hpp"

namespace plunge {

// Thrown where a cancelled plan stops. Not a plunge::Error: the input is not
// at fault, and a stage that catches Error to mean "no floor here" lets it
// pass. Python sees plunge.Cancelled ("planning cancelled"), not a ValueError.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("planning cancelled") {}
};

class Progress {
 public:
  // fraction in [0, 1] and what is being done; return false to cancel.
  using Callback = std::function<bool(double fraction, const std::string& stage)>;

  Progress() = default;
  // The callback runs only on the thread that made this object (the caller's:
  // Python and FreeCAD need that), at most every `interval`.
  explicit Progress(Callback callback, std::chrono::milliseconds interval = std::chrono::milliseconds(100));

  // A stage from `fraction` on: always reported to the callback.
  void stage(double fraction, const std::string& name) const;
  // From inside a long loop, on any thread: throws Cancelled once cancelled;
  // on the caller's thread also reports (the stage's fraction, or `fraction`)
  // when the interval has passed.
  void tick(double fraction = -1.0) const;
  // Cancels from any thread (the callback returning false or throwing does too).
  void cancel() const { state_->cancelled = true; }
  bool cancelled() const { return state_->cancelled; }
  // The same callback and flag, with fractions [0, 1] mapped into [lo, hi] of this one.
  Progress sub(double lo, double hi) const;
  // The result of work running on another thread, reporting (and able to
  // cancel) while it runs: the caller's thread would otherwise wait silent.
  // On a cancel the other thread's own ticks stop it; the future's owner
  // waits for it as usual.
  template <class T>
  T await(std::future<T>& work) const {
    while (work.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) tick();
    return work.get();
  }

 private:
  struct State {
    Callback callback;
    std::chrono::milliseconds interval{100};
    std::thread::id owner;
    std::atomic<bool> cancelled{false};
    std::chrono::steady_clock::time_point last;
    double fraction = 0.0;
    std::string stage;
  };
  void report(double fraction, bool force) const;

  std::shared_ptr<State> state_ = std::make_shared<State>();
  double lo_ = 0.0, hi_ = 1.0;
};

}  // namespace plunge
