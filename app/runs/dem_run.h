#pragma once
// Runs a DEM case (Mode = dem): builds the model, integrates it, writes history.csv and the
// ParaView series into the output folder, and returns the summary.
#include "app/checkpoint/checkpoint.h"
#include <deal.II/base/parameter_handler.h>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// @p checkpoint: where checkpoints go and whether to resume from one (explicit runs; the
/// intervals are read from the case's Output section).
nlohmann::json run_dem_case(dealii::ParameterHandler& prm, const std::filesystem::path& output_dir,
                            CheckpointSettings checkpoint = {});
} // namespace dembridge::app
