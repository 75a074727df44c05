// S_v and the interface-compliance estimate for `dembridge elasticity` (see column_estimate.h).
#include "app/studies/column_estimate.h"
#include "app/studies/column_tessellation.h"
#include "app/studies/interface_compliance.h"
#include "dem/model/model.h"
#include <cstdio>

namespace dembridge::app
{
nlohmann::json column_estimate_json(const dem::CaseConfig& config,
                                    const dem::MeasuredElasticity& measured,
                                    const dem::ElasticityMeasurementSettings& settings,
                                    bool estimate)
{
  const auto& grains = config.microstructure.grains;
  const ColumnTessellation t = column_tessellation(grains, measured.core_lo, measured.core_hi);
  nlohmann::json j = {{"boundary_area_per_volume", t.boundary_area_per_volume}, {"cells", t.cells}};
  if (!estimate)
    return j;
  if (config.microstructure.weak_planes)
    throw dem::InputError("--interface-estimate: the case has weak planes; the estimate is for "
                          "grain boundaries alone");
  dem::CaseConfig intact = config;
  intact.microstructure = {};
  const dem::Vec3 E0 =
      dem::measured_stiffness_tensor(dem::build_model(intact), settings).properties.youngs_modulus;
  const int u = (grains.axis + 1) % 3, v = (grains.axis + 2) % 3;
  const double E = 0.5 * (E0[u] + E0[v]);
  const dem::BondClassConfig boundary = config.microstructure.grain_boundary.value_or(
      dem::BondClassConfig::of_specimen(config.bonds.material, config.damage));
  const PlaneComplianceMean B = mean_plane_compliance(config, grains.axis, boundary, 4);
  const dem::Vec3& Em = measured.properties.youngs_modulus;
  const double across = 0.5 * (Em[u] + Em[v]);
  const double Ex = interface_compliance_youngs_modulus(E, t.boundary_area_per_volume,
                                                        B.mean.normal, B.mean.shear);
  j["normal_compliance"] = B.mean.normal;
  j["shear_compliance"] = B.mean.shear;
  j["youngs_modulus_without_grains"] = E;
  j["youngs_modulus_across"] = across;
  j["youngs_modulus_estimate"] = Ex;
  j["measured_over_estimate"] = across / Ex;
  return j;
}

void print_column_estimate(const nlohmann::json& c)
{
  std::printf("%-22s %14.6g\n", "columns: S_v (1/m)", c["boundary_area_per_volume"].get<double>());
  if (!c.contains("youngs_modulus_estimate"))
    return;
  std::printf("%-22s %14.6g\n", "  B_N (m/Pa)", c["normal_compliance"].get<double>());
  std::printf("%-22s %14.6g\n", "  B_T (m/Pa)", c["shear_compliance"].get<double>());
  std::printf("%-22s %14.6g\n", "  E no grains (GPa)",
              c["youngs_modulus_without_grains"].get<double>() / 1e9);
  std::printf("%-22s %14.6g\n", "  E across (GPa)", c["youngs_modulus_across"].get<double>() / 1e9);
  std::printf("%-22s %14.6g\n", "  estimate (GPa)",
              c["youngs_modulus_estimate"].get<double>() / 1e9);
}
} // namespace dembridge::app
