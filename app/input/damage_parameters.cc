#include "app/input/damage_parameters.h"

namespace dembridge::app
{
using dealii::ParameterHandler;
using dealii::Patterns::Double;
using dealii::Patterns::Integer;
using dealii::Patterns::Selection;

void declare_damage_parameters(ParameterHandler& prm)
{
  prm.enter_subsection("Damage");
  prm.declare_entry("failure", "none", Selection("none|brittle|softening"),
                    "Bond failure: none; brittle (a bond breaks in the step its stress reaches "
                    "its strength, its strain energy booked as fracture); softening (linear "
                    "softening after the peak to the fracture energy G_f per bond area).");
  prm.declare_entry("tensile strength", "0", Double(),
                    "Tensile strength sigma_t of the bonds (Pa, mean); the tensile stress is "
                    "F_n/A + beta |M_b| R/I (Potyondy & Cundall 2004).");
  prm.declare_entry("shear criterion", "constant", Selection("constant|mohr_coulomb"),
                    "Shear strength: constant ('shear strength') or Mohr-Coulomb, c + sigma_c "
                    "tan(phi) with sigma_c the bond's compressive normal stress.");
  prm.declare_entry("shear strength", "0", Double(),
                    "Shear strength tau_c (Pa, mean), shear criterion = constant; the shear "
                    "stress is |F_s|/A + beta |M_t| R/J.");
  prm.declare_entry("cohesion", "0", Double(), "Cohesion c (Pa, mean), Mohr-Coulomb.");
  prm.declare_entry("friction angle", "0", Double(),
                    "Friction angle phi (degrees, in [0, 90)), Mohr-Coulomb.");
  prm.declare_entry("moment factor", "1", Double(),
                    "beta in [0, 1]: the share of the bending and twisting moments in the bond "
                    "stresses (PFC's moment-contribution factor).");
  prm.declare_entry("strength scatter", "none", Selection("none|normal|weibull"),
                    "Scatter of the strengths between bonds (seeded): normal (relative std dev "
                    "'scatter', truncated to positive values) or Weibull ('weibull modulus', "
                    "mean = the given strength).");
  prm.declare_entry("scatter", "0", Double(),
                    "Relative standard deviation of a normal strength scatter.");
  prm.declare_entry("weibull modulus", "0", Double(), "Weibull modulus m of the strengths.");
  prm.declare_entry("seed", "1", Integer(0), "Seed of the strength scatter.");
  prm.declare_entry("scatter key", "bond order", Selection("bond order|position"),
                    "bond order: one stream drawn in the order the bonds are formed; position: "
                    "each bond's own stream, seeded by its reference midpoint, so that the same "
                    "bond gets the same strengths in a renumbered or larger specimen (a coupled "
                    "run's particle region and its full DEM, dembridge compare).");
  prm.declare_entry("fracture energy mode I", "0", Double(),
                    "Softening: energy dissipated per bond area when tension governs (J/m^2); "
                    "at least sigma_t^2 A / (2 k_n) (no snap-back).");
  prm.declare_entry("fracture energy mode II", "0", Double(),
                    "Softening: energy dissipated per bond area when shear governs (J/m^2); at "
                    "least tau^2 A / (2 k_s) (no snap-back).");
  prm.leave_subsection();
}

dem::DamageConfig parse_damage_parameters(ParameterHandler& prm)
{
  dem::DamageConfig d;
  prm.enter_subsection("Damage");
  const std::string failure = prm.get("failure");
  d.law.mode = failure == "none"      ? dem::FailureMode::none
               : failure == "brittle" ? dem::FailureMode::brittle
                                      : dem::FailureMode::softening;
  d.law.shear = prm.get("shear criterion") == "constant" ? dem::ShearCriterion::constant
                                                         : dem::ShearCriterion::mohr_coulomb;
  d.law.moment_factor = prm.get_double("moment factor");
  d.law.fracture_energy_I = prm.get_double("fracture energy mode I");
  d.law.fracture_energy_II = prm.get_double("fracture energy mode II");
  d.tensile_strength = prm.get_double("tensile strength");
  d.shear_strength = prm.get_double("shear strength");
  d.cohesion = prm.get_double("cohesion");
  d.friction_angle = prm.get_double("friction angle");
  const std::string scatter = prm.get("strength scatter");
  d.scatter = scatter == "none"     ? dem::StrengthScatter::none
              : scatter == "normal" ? dem::StrengthScatter::normal
                                    : dem::StrengthScatter::weibull;
  d.scatter_deviation = prm.get_double("scatter");
  d.scatter_by_position = prm.get("scatter key") == "position";
  d.weibull_modulus = prm.get_double("weibull modulus");
  d.seed = static_cast<unsigned long>(prm.get_integer("seed"));
  prm.leave_subsection();
  d.validate();
  return d;
}
} // namespace dembridge::app
