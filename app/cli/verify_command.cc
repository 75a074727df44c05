#include "app/cli/verify_command.h"

namespace dembridge::app
{
CLI::App* add_verify_command(CLI::App& app, VerifyOptions& verify)
{
  auto* verify_cmd = app.add_subcommand(
      "verify", "Run a DEM specimen case and the FE model of the same specimen; compare them");
  verify_cmd->add_option("case", verify.case_file, "DEM case file (uniaxial or bending test)")
      ->required();
  verify_cmd->add_option("--set", verify.overrides, "Override a parameter: \"Section/Key=value\"");
  verify_cmd->add_option("--output-dir", verify.output_dir,
                         "Output folder (default output/verify_CASE)");
  auto* from = verify_cmd->add_option("--material-from", verify.material_from,
                                      "summary.json of a uniaxial DEM test (E, mean nu) or "
                                      "an elasticity.json (its stiffness tensor)");
  auto* e_opt = verify_cmd->add_option("--youngs-modulus", verify.youngs_modulus, "E (Pa)");
  auto* nu_opt = verify_cmd->add_option("--poisson-ratio", verify.poisson_ratio, "nu");
  verify_cmd->add_option("--shear-modulus", verify.shear_modulus,
                         "G (Pa): cubic FE material along the axes, C44 = G (default isotropic)");
  e_opt->needs(nu_opt)->excludes(from);
  nu_opt->needs(e_opt);
  verify_cmd->add_option("--dem-run", verify.dem_run,
                         "Folder of a finished DEM run of this case (its summary.json is used)");
  verify_cmd->add_flag("!--no-plot", verify.plot, "Do not write comparison.png");
  verify_cmd
      ->add_flag("--measured-tensor", verify.measured_tensor,
                 "FE material: the stiffness tensor measured on the case's own packing")
      ->excludes(from)
      ->excludes(e_opt);
  return verify_cmd;
}
} // namespace dembridge::app
