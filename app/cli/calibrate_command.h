#pragma once
// The options of `dembridge calibrate` (app/studies/calibrate.h runs it).
#include "app/studies/calibrate.h"
#include <CLI/CLI.hpp>

namespace dembridge::app
{
/// Declares the subcommand and its options on @p app.
CLI::App* add_calibrate_command(CLI::App& app, CalibrateOptions& options);
} // namespace dembridge::app
