#include "app/input/verification_parameters.h"

namespace dembridge::app
{
void declare_verification_parameters(dealii::ParameterHandler& prm)
{
  namespace P = dealii::Patterns;
  prm.enter_subsection("Verification");
  prm.declare_entry("test", "auto", P::Selection("auto|uniaxial|bending"),
                    "Which DEM test `dembridge verify` models: uniaxial (Measurements/modulus "
                    "groups), bending (Measurements/flexural groups), auto: the one the case "
                    "measures.");
  prm.declare_entry("degree", "2", P::Integer(1, 2), "FE degree of the verification model.");
  prm.declare_entry("cell size", "0", P::Double(0),
                    "FE cell size (m) of the verification model; 0: the mean particle diameter.");
  prm.declare_entry("stress layers", "10", P::Integer(1, 1000),
                    "Slabs for the layer-averaged stress when the case sets no Measurements/"
                    "stress layers.");
  prm.declare_entry("stress layer axis", "z", P::Selection("x|y|z"),
                    "Normal of those slabs (through the depth: z).");
  prm.leave_subsection();
}
} // namespace dembridge::app
