#pragma once
// Runs a coupled case (Mode = coupled): builds the coupled problem from the case file
// (coupled_parameters.h, coupling/coupled_case.h), runs it (coupling/coupled_run.h) and writes
// into the output folder, on one time base:
//   history.csv     energies of both sides, multiplier work, balance error, tie gap, the
//                   particle groups' mean displacements, the FE probes' displacements
//   particles_*.vtu, bonds_*.vtu, fem_*.pvtu, and coupled.pvd, which opens all three together
//                   in ParaView (one dataset per part and time)
// and returns the summary (SI units). With Output/checkpoint interval it writes checkpoints of
// the complete coupled state, and resumes from one (checkpoint.h, docs/checkpoint.md).
#include "app/checkpoint/checkpoint.h"
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <mpi.h>
#include <nlohmann/json.hpp>

namespace dembridge::app
{
nlohmann::json run_coupled_case(dealii::ParameterHandler& prm,
                                const std::filesystem::path& output_dir, MPI_Comm comm,
                                CheckpointSettings checkpoint = {});
}
