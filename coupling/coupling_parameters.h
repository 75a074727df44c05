#pragma once
// The `Coupling` section of a case file (Mode = coupled): the handshake band, the FE mesh around
// the particle region, the continuum's tensor, the tie and its solve, damping, ramps, the
// adaptive region and the test pulse. Declared here, beside the code that checks the rules they
// feed (coupling/handshake.h, coupling/coupled_mesh.h, coupling/adaptive_region.h).
#include "coupling/coupled_case.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::coupling
{
/// Declares `subsection Coupling` with its subsections `Adaptive region` and `Pulse`.
void declare_coupling_parameters(dealii::ParameterHandler& prm);

/// Reads the Coupling section into @p c, whose particles (the DEM sections) are read already:
/// the band width's default and the common time step come from them. Throws dem::InputError
/// naming Section/key and the reason.
void parse_coupling_section(dealii::ParameterHandler& prm, CoupledCase& c);
} // namespace dembridge::coupling
