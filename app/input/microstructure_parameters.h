#pragma once
// The `Microstructure` section of a DEM case file (columnar grains and weak planes,
// dem/microstructure/) and the `Bond class grain_boundary` / `Bond class weak_plane` sections
// (each class's Bonds and Damage values; a key left empty takes the Bonds or Damage value),
// declared with defaults and documentation and read into dem::MicrostructureConfig.
#include "dem/model/case_config.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
void declare_microstructure_parameters(dealii::ParameterHandler& prm);

/// Reads the sections; the classes' empty keys take @p material's and @p damage's values.
/// Throws dem::InputError naming Section/key.
dem::MicrostructureConfig parse_microstructure_parameters(dealii::ParameterHandler& prm,
                                                          const dem::BondMaterial& material,
                                                          const dem::DamageConfig& damage);
} // namespace dembridge::app
