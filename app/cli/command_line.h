#pragma once
// What every subcommand's command line shares: the one-line usage error and the refusal of
// empty folder paths; and `dembridge print-parameters`.
#include "app/job/mpi_job.h"
#include <CLI/CLI.hpp>
#include <string>

namespace dembridge::app
{
/// One line for a command-line error; an unknown subcommand is named with the known ones.
std::string usage_error(CLI::App& app, int argc, char** argv, const std::string& what);

/// A folder option given an empty path would silently fall back to the default folder: throws
/// std::runtime_error naming the option.
void refuse_empty_paths(const CLI::App& app);

/// Declares `print-parameters` on @p app.
CLI::App* add_print_parameters_command(CLI::App& app);

/// Prints every parameter with its default and documentation (rank 0); returns the exit code.
int print_parameters(const MpiJob& job);
} // namespace dembridge::app
