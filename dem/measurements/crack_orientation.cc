#include "dem/measurements/crack_orientation.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace dembridge::dem
{
CrackOrientation crack_orientation(const std::vector<CrackEvent>& cracks, int axis, int bins)
{
  if (axis < 0 || axis > 2 || bins < 1)
    throw std::invalid_argument("crack_orientation: axis 0..2 and at least one bin");
  constexpr double degree = std::numbers::pi / 180;
  CrackOrientation h;
  h.axis = axis;
  const double width = 90.0 / bins;
  for (int k = 0; k <= bins; ++k)
    h.edges.push_back(k * width);
  h.counts.assign(std::size_t(bins), 0);
  for (int k = 0; k < bins; ++k)
    h.isotropic_fraction.push_back(std::cos(h.edges[k] * degree) -
                                   std::cos(h.edges[k + 1] * degree));
  long along = 0;
  double sum = 0;
  for (const auto& c : cracks)
  {
    const double cosine = std::min(1.0, std::abs(c.axis[axis]) / c.axis.norm());
    const double theta = std::acos(cosine) / degree;
    sum += theta;
    along += theta >= 60.0;
    ++h.counts[std::size_t(std::min(bins - 1, int(theta / width)))];
  }
  const double n = double(cracks.size());
  for (long count : h.counts)
    h.fraction.push_back(n > 0 ? double(count) / n : 0.0);
  h.mean_angle = n > 0 ? sum / n : 0.0;
  h.along_load_fraction = n > 0 ? double(along) / n : 0.0;
  return h;
}
} // namespace dembridge::dem
