#include "plunge/progress.hpp"

#include <algorithm>

namespace plunge {

Progress::Progress(Callback callback, std::chrono::milliseconds interval) {
  state_->callback = std::move(callback);
  state_->interval = interval;
  state_->owner = std::this_thread::get_id();
  state_->last = std::chrono::steady_clock::now();
}

Progress Progress::sub(double lo, double hi) const {
  Progress p = *this;
  p.lo_ = lo_ + (hi_ - lo_) * std::clamp(lo, 0.0, 1.0);
  p.hi_ = lo_ + (hi_ - lo_) * std::clamp(hi, 0.0, 1.0);
  return p;
}

void Progress::stage(double fraction, const std::string& name) const {
  if (std::this_thread::get_id() == state_->owner) state_->stage = name;
  report(fraction, true);
}

void Progress::tick(double fraction) const {
  if (state_->cancelled) throw Cancelled();
  if (state_->callback && std::this_thread::get_id() == state_->owner &&
      std::chrono::steady_clock::now() - state_->last >= state_->interval)
    report(fraction < 0.0 ? -1.0 : fraction, false);
}

void Progress::report(double fraction, bool force) const {
  State& s = *state_;
  if (s.cancelled) throw Cancelled();
  if (!s.callback || std::this_thread::get_id() != s.owner) return;
  // Never back: a stage run again (the plunges posted a second time for the
  // tool that reaches) keeps the bar where it was.
  if (fraction >= 0.0) s.fraction = std::max(s.fraction, lo_ + (hi_ - lo_) * std::clamp(fraction, 0.0, 1.0));
  if (!force && std::chrono::steady_clock::now() - s.last < s.interval) return;
  s.last = std::chrono::steady_clock::now();
  bool go = false;
  try {
    go = s.callback(s.fraction, s.stage);
  } catch (...) {
    s.cancelled = true;  // stops the other threads too; the caller's exception goes on
    throw;
  }
  if (!go) {
    s.cancelled = true;
    throw Cancelled();
  }
}

}  // namespace plunge
