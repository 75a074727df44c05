#pragma once
// A coupled case file (Mode = coupled) as a coupling::CoupledCase (coupling/coupled_case.h): the
// DEM sections (the particle region), the FEM sections (the continuum) and the Coupling section
// (coupling/coupling_parameters.h).
#include "coupling/coupled_case.h"
#include "coupling/coupled_run.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
/// Throws dem::InputError or std::runtime_error naming Section/key and the reason.
coupling::CoupledCase parse_coupled_case(dealii::ParameterHandler& prm);

/// The run's stop and record settings (Simulation, Output and Coupling/rest tolerance).
coupling::CoupledRunSettings parse_coupled_run_settings(dealii::ParameterHandler& prm,
                                                        const coupling::CoupledCase& c);
} // namespace dembridge::app
