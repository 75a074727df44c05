#pragma once
// Progress lines from long phases that have no observer of their own (random packing, static
// solves): the library reports, the application decides where the lines go (the CLI prints
// them; tests and library users hear nothing unless they install a sink). Rate-limited by the
// caller (ProgressClock), so a report costs one clock read. StepRate: the rate and time left of
// a time-stepping run, which may have been resumed from a checkpoint.
#include <algorithm>
#include <chrono>
#include <functional>
#include <string>

namespace dembridge::dem
{
/// Where progress lines go; empty: nowhere (the default).
inline std::function<void(const std::string&)>& progress_sink()
{
  static std::function<void(const std::string&)> sink;
  return sink;
}

inline void report_progress(const std::string& line)
{
  if (progress_sink())
    progress_sink()(line);
}

/// due() is true once every `seconds` of wall time (first after `seconds`).
class ProgressClock
{
public:
  explicit ProgressClock(double seconds = 2.0)
      : start_(std::chrono::steady_clock::now()), last_(start_), seconds_(seconds)
  {
  }
  bool due()
  {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < seconds_)
      return false;
    last_ = now;
    return true;
  }
  double elapsed() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

private:
  std::chrono::steady_clock::time_point start_, last_;
  double seconds_;
};

/// Steps per second and the seconds left of a run, counted from the step it started at and the
/// wall time since: a run resumed from a checkpoint at step k counts its own steps after k, not
/// the k its checkpoint holds, which it never made (its rate and ETA would be too high and too
/// short).
class StepRate
{
public:
  using clock = std::chrono::steady_clock;
  StepRate(long first_step, clock::time_point start) : first_(first_step), start_(start) {}

  /// The steps made since the start (@p step is the run's step count now).
  long steps_made(long step) const { return std::max(0L, step - first_); }
  /// Steps per second at @p step, @p now; 0 before a step or a tick of the clock.
  double per_second(long step, clock::time_point now) const
  {
    const double wall = std::chrono::duration<double>(now - start_).count();
    return wall > 0 ? double(steps_made(step)) / wall : 0.0;
  }
  /// Seconds until step @p planned at the rate so far; 0 while the rate is unknown.
  double seconds_left(long step, long planned, clock::time_point now) const
  {
    const double rate = per_second(step, now);
    return rate > 0 ? double(std::max(0L, planned - step)) / rate : 0.0;
  }

private:
  long first_;
  clock::time_point start_;
};
} // namespace dembridge::dem
