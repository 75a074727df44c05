#pragma once
// The DEM case file: every subsection a DEM run reads, declared with defaults, bounded patterns
// and documentation (deal.II ParameterHandler), and its translation into dem::CaseConfig.
// Groups and loads are named lists: `Groups/names = left, tip` declares the subsections
// `Group left` and `Group tip`; likewise `Loads/names` and `Load NAME` (group_load_parameters.h).
#include "dem/model/case_config.h"
#include <deal.II/base/parameter_handler.h>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Declares the fixed DEM subsections (Particles, Bonds, Damping, Simulation, Groups, Loads,
/// Measurements, Output).
void declare_dem_parameters(dealii::ParameterHandler& prm);

/// Reads the parsed file into a CaseConfig; throws dem::InputError (Section/key: reason).
dem::CaseConfig parse_dem_case(dealii::ParameterHandler& prm);

/// Output settings (not part of the physics).
struct OutputSettings
{
  long history_interval = 100;
  long snapshot_interval = 0;
  bool write_vtu = true;
  double checkpoint_interval = 0;      ///< s of simulated time (checkpoint.h)
  double checkpoint_wall_interval = 0; ///< s of wall time
  int load_steps = 1;                  ///< static solver (Simulation/load steps)
};
OutputSettings parse_output_settings(dealii::ParameterHandler& prm);

/// Splits a comma-separated list of names, trimming blanks.
std::vector<std::string> split_names(const std::string& text);
} // namespace dembridge::app
