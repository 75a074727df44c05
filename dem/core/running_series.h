#pragma once
// A per-step series summarised as it grows, so that a run of any length keeps a few numbers
// instead of the series (the FE dynamics energies, fem/fem_case.cc): the first value, the range
// and the least-squares line against the step index k = 0, 1, ..., n - 1,
//   slope = sum (k - mean_k)(v_k - mean_v) / sum (k - mean_k)^2,
// with the means and co-moments updated one value at a time (Welford, Technometrics 4(3) 419,
// 1962; the co-moment form of Pebay, Sandia report SAND2008-6212), which keeps the sums of
// small deviations from the running means instead of large sums that would cancel. The values
// enter as v_k - v_0 (exact while v_k lies within a factor 2 of v_0), so an energy that stays
// near H_0 is fitted to the precision of its changes, not of H_0.
#include "dem/core/state_archive.h"
#include <algorithm>
#include <cmath>
#include <string>

namespace dembridge::dem
{
struct RunningSeries
{
  long count = 0;
  double first = 0, lowest = 0, highest = 0;
  double mean_index = 0, mean_change = 0; ///< means of k and of v_k - v_0
  double co_moment = 0;                   ///< sum (k - mean_k)(v_k - mean_v)
  double index_moment = 0;                ///< sum (k - mean_k)^2

  void add(double v)
  {
    const double k = double(count);
    ++count;
    if (count == 1)
      first = lowest = highest = v;
    lowest = std::min(lowest, v);
    highest = std::max(highest, v);
    const double change = v - first;
    const double dk = k - mean_index;
    mean_index += dk / double(count);
    mean_change += (change - mean_change) / double(count);
    co_moment += dk * (change - mean_change);
    index_moment += dk * (k - mean_index);
  }

  /// (largest - smallest) / |first|.
  double relative_range() const { return (highest - lowest) / std::abs(first); }

  /// The fitted line's change over the series: slope times the number of values (0 for fewer
  /// than two).
  double fitted_change() const
  {
    return index_moment > 0 ? co_moment / index_moment * double(count) : 0.0;
  }

  /// Reads or writes the summary as `<name>_count`, `<name>_first`, ... (a checkpoint).
  void visit(StateArchive& a, const std::string& name)
  {
    a.io(name + "_count", count);
    a.io(name + "_first", first);
    a.io(name + "_lowest", lowest);
    a.io(name + "_highest", highest);
    a.io(name + "_mean_index", mean_index);
    a.io(name + "_mean_change", mean_change);
    a.io(name + "_co_moment", co_moment);
    a.io(name + "_index_moment", index_moment);
  }
};
} // namespace dembridge::dem
