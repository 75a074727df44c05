#pragma once
// The `Coupling` section of a case file (Mode = coupled) and its translation, with the DEM
// sections (the particle region) and the FEM sections (the continuum), into a
// coupling::CoupledCase (coupling/coupled_case.h).
#include "coupling/coupled_case.h"
#include "coupling/coupled_run.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
void declare_coupling_parameters(dealii::ParameterHandler& prm);

/// Throws dem::InputError or std::runtime_error naming Section/key and the reason.
coupling::CoupledCase parse_coupled_case(dealii::ParameterHandler& prm);

/// The run's stop and record settings (Simulation, Output and Coupling/rest tolerance).
coupling::CoupledRunSettings parse_coupled_run_settings(dealii::ParameterHandler& prm,
                                                        const coupling::CoupledCase& c);
} // namespace dembridge::app
