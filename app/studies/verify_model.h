#pragma once
// dembridge verify: the FE model of a DEM specimen test. make_plan reads the DEM case (its
// measurement groups, supports and loads) before anything runs; fe_case writes the FE case file
// once the DEM results are known. Internal to app/verify.cc.
#include "app/studies/verify.h"
#include "dem/model/case_config.h"
#include "dem/model/model.h"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dembridge::app::verify_detail
{
/// Everything the FE case needs from the DEM case, found before anything runs.
struct Plan
{
  std::string test; ///< uniaxial | bending
  int axis = 0;     ///< uniaxial: loading axis; bending: span axis
  dem::Vec3 lo, hi; ///< specimen extent (radii included)
  dem::Vec3 body_lo, body_hi;
  double mean_diameter = 0;
  std::size_t n_particles = 0;
  // uniaxial
  std::string fixed_group, loaded_group, fixed_face, loaded_face;
  std::string fixed_components, loaded_held_components; // held at zero
  bool displacement_control = false;
  std::string load_components; // prescribed (displacement control)
  dem::Vec3 load_force = dem::Vec3::Zero();
  // bending
  std::string pin, roller, loaded, bottom, pin_components, roller_components;
  std::string patches, top_points, bottom_points;
  std::vector<std::string> mapped_groups, ignored_groups;
};

/// Layer edges: the DEM's (summary stress_layers.edges) when present, else equal slabs of the
/// extent as the DEM would cut them.
struct Layers
{
  int axis = 2;
  std::vector<double> edges;
};

/// The plan of the FE model; throws std::runtime_error ("Section/Key: reason") when the case
/// does not describe a test verify can model. @p test: auto | uniaxial | bending.
Plan make_plan(const dem::CaseConfig& c, const dem::Model& model, const std::string& test);

/// The slabs: those of the DEM summary (stress_layers.edges) if present, else n equal slabs of
/// the specimen extent normal to @p axis, as the DEM cuts them.
Layers layers_from(const nlohmann::json& dem, const Plan& p, int n, int axis);

/// The FE case file text (Mode = fem): box mesh of cell size about @p cell_size, the supports
/// and load of the plan (a prescribed end displacement is the DEM's measured one), measurements
/// for the comparison (reactions, point groups, the stress slabs).
std::string fe_case(const Plan& p, const ElasticConstants& mat, const nlohmann::json& dem,
                    int degree, double cell_size, const Layers& layers);

/// Shortest round-trip text of a double.
std::string num(double v);
} // namespace dembridge::app::verify_detail
