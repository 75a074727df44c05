#pragma once
// The options of `dembridge verify` (app/studies/verify.h runs it).
#include "app/studies/verify.h"
#include <CLI/CLI.hpp>

namespace dembridge::app
{
/// Declares the subcommand and its options on @p app.
CLI::App* add_verify_command(CLI::App& app, VerifyOptions& options);
} // namespace dembridge::app
