#pragma once
// The memory guard of `dembridge run`: before anything is built, the case's particles, bonds
// and memory are estimated (dem/model/size_estimate.h) and a case that does not fit in the
// machine's available memory is refused with the figures. FE meshes are checked where their
// coarse mesh is known, before refinement (fem/mesh.cc).
#include <deal.II/base/parameter_handler.h>
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// DEM (and the DEM part of other modes): estimates the case, throws dem::InputError naming the
/// key that sets its size when it does not fit; returns {particles, bonds, bytes, available_bytes}
/// for summary.json (null for FE cases).
nlohmann::json check_memory(dealii::ParameterHandler& prm);

/// The largest resident memory this process has had so far (getrusage), bytes.
double peak_memory_bytes();
} // namespace dembridge::app
