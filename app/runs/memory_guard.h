#pragma once
// The memory guard of `dembridge run`: before anything is built, the case's particles, bonds
// (dem/model/size_estimate.h) and FE mesh (cells and DoFs: fem/mesh_estimate.h for FEM/Mesh,
// coupling/mesh_estimate.h for a coupled run's continuum) and the memory they take are estimated,
// and a case that does not fit in the machine's available memory is refused with the figures.
// A large mesh that fits is announced before it is built (building it takes a while).
#include <deal.II/base/parameter_handler.h>
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// Estimates the case, throws (dem::InputError or std::runtime_error) naming the key that sets its
/// size when it does not fit; returns {particles, bonds, fe_cells, fe_dofs, bytes,
/// available_bytes} (the parts the mode has) for summary.json.
nlohmann::json check_memory(dealii::ParameterHandler& prm);

/// The largest resident memory this process has had so far (getrusage), bytes.
double peak_memory_bytes();
} // namespace dembridge::app
