// dembridge::fem — the entry point the app calls for "set Mode = fem".
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include "parameters.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace dembridge::fem
{
/// Declare every FEM parameter subsection (FEM, FEM/Mesh, FEM/Material, ...), each entry with a
/// default, a bounded pattern and a documentation string.
void declare_parameters(dealii::ParameterHandler& prm);

/// Run the case described by @p prm (already parsed): static elasticity or explicit dynamics.
/// Writes ParaView files (.vtu/.pvtu/.pvd) and history.csv (dynamics) into @p output_dir and
/// returns the summary (SI units, snake_case keys). Throws std::runtime_error with a one-line
/// message naming the parameter ("Section/Key") or file on bad input.
nlohmann::json run_case(const dealii::ParameterHandler& prm,
                        const std::filesystem::path& output_dir, MPI_Comm comm);
/// The same for parameters built in code (coupling/full_models.h).
nlohmann::json run_case(const Parameters& p, const std::filesystem::path& output_dir, MPI_Comm comm);
} // namespace dembridge::fem
