#pragma once
// dembridge verify: the rows of the side-by-side report, read from the DEM and the FE summaries
// of the same specimen test (coupling/specimen_fe_model.h). Internal to app/verify.cc.
#include "app/studies/verify_report.h"
#include "coupling/specimen_fe_model.h"
#include <nlohmann/json.hpp>
#include <optional>

namespace dembridge::app::verify_detail
{
/// The DEM's Young's modulus (thesis eq. 64). Under force control the DEM summary's
/// youngs_modulus reads the loaded end's net force (zero in equilibrium), so there E comes from
/// the fixed end's reaction: E = -R_fixed / A * L0 / (u_loaded - u_fixed), as in the FE summary.
std::optional<double> dem_youngs_modulus(const coupling::SpecimenTest& t,
                                         const nlohmann::json& dem);

/// Every compared quantity of the test, and the normal stress along the test axis per slab (FE
/// integrals over the DEM slab volumes).
Report compare_results(const coupling::SpecimenTest& t, const nlohmann::json& dem,
                       const nlohmann::json& fe, const coupling::SpecimenLayers& layers);
} // namespace dembridge::app::verify_detail
