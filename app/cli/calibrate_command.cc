#include "app/cli/calibrate_command.h"

namespace dembridge::app
{
CLI::App* add_calibrate_command(CLI::App& app, CalibrateOptions& o)
{
  auto* cmd = app.add_subcommand(
      "calibrate", "Find the bond parameters that give a packing the target E, nu (and tensile "
                   "strength) of its Calibration section");
  cmd->add_option("targets", o.targets_file,
                  "DEM case (.prm) with a static uniaxial test and a Calibration section")
      ->required();
  cmd->add_option("--set", o.overrides, "Override a parameter: \"Section/Key=value\"");
  cmd->add_option("--output-dir", o.output_dir, "Output folder (default output/calibrate_CASE)");
  cmd->add_flag("!--no-plot", o.plot, "Do not write calibration.png");
  return cmd;
}
} // namespace dembridge::app
