#pragma once
// Progress lines from long phases that have no observer of their own (random packing, static
// solves): the library reports, the application decides where the lines go (the CLI prints
// them; tests and library users hear nothing unless they install a sink). Rate-limited by the
// caller (ProgressClock), so a report costs one clock read.
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
} // namespace dembridge::dem
