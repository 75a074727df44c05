#pragma once
// Runs an FE case (Mode = fem, and the FE models of `verify` and `compare`): fem::run_case
// measures, this run decides what goes into the output folder and when:
//   BASE_NNNN.R.vtu, BASE_NNNN.pvtu, BASE.pvd (FEM/Output/vtu, base name): the fields of a
//                   static run once solved; of a dynamics run at step 0, every FEM/Output/every
//                   steps and after the last step
//   history.csv     a dynamics run's probes and energies, one row per step (fem_history.h)
//   timing.log      deal.II's timer table
// and returns the summary's figures (SI units). Checkpoints of a dynamics run
// (fem_checkpoints.h) resume it with its history and snapshots as they were at the checkpoint.
#include "fem/fem_case.h"
#include <filesystem>
#include <mpi.h>
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// Runs @p p on the ranks of @p comm, writing its files into @p output_dir (which exists);
/// @p checkpoints as fem::run_case. Collective.
nlohmann::json run_fem_case(const fem::Parameters& p, const std::filesystem::path& output_dir,
                            MPI_Comm comm, const fem::DynamicsCheckpoints* checkpoints = nullptr);
} // namespace dembridge::app
