#include "memory_guard.h"
#include "dem/model/size_estimate.h"
#include "dem_parameters.h"
#include <sys/resource.h>

namespace dembridge::app
{
nlohmann::json check_memory(dealii::ParameterHandler& prm)
{
  if (prm.get("Mode") == "fem")
    return nullptr;
  const dem::SizeEstimate estimate = dem::estimate_size(parse_dem_case(prm));
  const double available = available_memory_bytes();
  dem::check_fits_in_memory(estimate, available);
  return {{"particles", estimate.particles},
          {"bonds", estimate.bonds},
          {"bytes", estimate.bytes},
          {"available_bytes", available}};
}

double peak_memory_bytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0; // Linux: kilobytes
}
} // namespace dembridge::app
