#pragma once
// The FE model of a DEM specimen test, for `dembridge verify` (docs/fem.md, "FEM vs DEM"): the
// specimen's extent as one continuum with the same supports and load, and the measurements the
// comparison reads. specimen_test reads the DEM case before anything runs; specimen_fe_parameters
// builds the FE problem once the DEM results are known.
//
//  * uniaxial test (Measurements/modulus groups = fixed, loaded; axis a): the FE body spans the
//    specimen's extent across a and, along a, the distance between the two end groups' centroids
//    (where the DEM holds and moves its end particles; their outer halves move rigidly with the
//    grips). The fixed end face holds the translations its group holds; the loaded end face gets
//    the DEM's load: a prescribed displacement (the DEM's measured end displacement; for the
//    static solver exactly the prescribed value) or the total force. Lateral rigid-body motion
//    that neither end removes is removed on the lateral min faces (symmetry planes, exact for a
//    homogeneous state).
//  * three-point bending (Measurements/flexural groups = pin, roller, loaded, bottom; span x,
//    load z as in the DEM measurement): the FE body is the specimen's extent; the supports are
//    bottom-face strips under the pin and roller particles (their x extent, radii included) held
//    in the translations the groups hold; the load is the DEM force, spread over the top-face
//    strip above the loaded particles; the deflections are FE displacements at the centres of the
//    loaded and bottom particles, as the DEM measures them.
#include "dem/measurements/elasticity_tensor.h"
#include "dem/model/case_config.h"
#include "dem/model/model.h"
#include "fem/parameters.h"
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace dembridge::coupling
{
/// Everything the FE model needs from the DEM case, found before anything runs.
struct SpecimenTest
{
  std::string test; ///< uniaxial | bending
  int axis = 0;     ///< uniaxial: loading axis; bending: span axis
  dem::Vec3 lo, hi; ///< specimen extent (radii included)
  dem::Vec3 body_lo, body_hi;
  double mean_diameter = 0;
  std::size_t n_particles = 0;
  // uniaxial
  std::string fixed_group, loaded_group, fixed_face, loaded_face;
  std::uint8_t fixed_components = 0, loaded_held_components = 0; ///< held at zero (bits x, y, z)
  bool displacement_control = false;
  std::uint8_t load_components = 0; ///< prescribed (displacement control)
  dem::Vec3 load_force = dem::Vec3::Zero();
  // bending
  std::string pin, roller, loaded, bottom;
  std::uint8_t pin_components = 0, roller_components = 0;
  std::vector<fem::BoundaryPatch> patches; ///< the pin, roller and loaded strips
  std::vector<dem::Vec3> top_points, bottom_points;
  std::vector<std::string> mapped_groups, ignored_groups;
};

/// Layer edges: the DEM's (summary stress_layers.edges) when present, else equal slabs of the
/// extent as the DEM would cut them.
struct SpecimenLayers
{
  int axis = 2;
  std::vector<double> edges;
};

/// The FE material: isotropic (E, nu), cubic along the axes (E, nu and C44 = G > 0), or a full
/// 6x6 stiffness tensor (Pa, Voigt order xx, yy, zz, yz, xz, xy).
struct SpecimenMaterial
{
  double youngs_modulus = 0, poisson_ratio = 0, shear_modulus = 0;
  std::optional<dem::Matrix6> stiffness_tensor;
};

/// The test the case describes; throws std::runtime_error ("Section/Key: reason") when it is not
/// one the FE model can reproduce. @p test: auto | uniaxial | bending.
SpecimenTest specimen_test(const dem::CaseConfig& c, const dem::Model& model,
                           const std::string& test);

/// The slabs: those of the DEM summary (stress_layers.edges) if present, else @p n equal slabs of
/// the specimen extent normal to @p axis, as the DEM cuts them.
SpecimenLayers specimen_layers(const nlohmann::json& dem_summary, const SpecimenTest& t, int n,
                               int axis);

/// The static FE problem: a box mesh of cells about @p cell_size, the supports and load of the
/// test (a prescribed end displacement is the DEM's measured one, from @p dem_summary's groups),
/// the measurements the comparison reads (reactions, point groups, the stress slabs).
fem::Parameters specimen_fe_parameters(const SpecimenTest& t, const SpecimenMaterial& material,
                                       const nlohmann::json& dem_summary, unsigned int degree,
                                       double cell_size, const SpecimenLayers& layers);
} // namespace dembridge::coupling
