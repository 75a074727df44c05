#pragma once
// `dembridge elasticity` on a columnar case: the columns' boundary area per volume S_v over the
// measured core (column_tessellation.h) and, on request, the interface-compliance estimate of
// the Young's modulus across the columns, 1 / E_x = 1 / E + S_v (3 B_N + B_T) / 8, with E the
// case's packing without grains (its tensor measured the same way) and B_N, B_T of a plane of
// its grain-boundary bonds through the same packing (interface_compliance.h;
// docs/columnar_ice.md).
#include "dem/measurements/elasticity_tensor.h"
#include "dem/model/case_config.h"
#include <nlohmann/json.hpp>

namespace dembridge::app
{
/// The "columns" object of elasticity.json: boundary_area_per_volume (1/m) and cells (reaching
/// the core); with @p estimate also normal_compliance, shear_compliance (m/Pa, the mean over
/// the planes' directions), youngs_modulus_without_grains, youngs_modulus_across (the means over
/// the two axes across the columns of the tensors without and with grains, Pa),
/// youngs_modulus_estimate (Pa) and measured_over_estimate. Throws InputError if the case has
/// weak planes (the estimate is for grain boundaries alone).
nlohmann::json column_estimate_json(const dem::CaseConfig& config,
                                    const dem::MeasuredElasticity& measured,
                                    const dem::ElasticityMeasurementSettings& settings,
                                    bool estimate);

/// Its lines of the printed table.
void print_column_estimate(const nlohmann::json& columns);
} // namespace dembridge::app
