#pragma once
// The `Verification` section of a DEM case: how `dembridge verify` builds the FE model of the
// specimen (app/studies/verify.h).
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
/// Declares `subsection Verification` (FE degree and cell size, the test, the stress slabs).
void declare_verification_parameters(dealii::ParameterHandler& prm);
} // namespace dembridge::app
