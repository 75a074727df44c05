#pragma once
// Specimen measurements from particle displacements and support reactions (thesis section 4.3):
//  - axial stress  sigma = F / A, with F the reaction of the loaded end group along the axis and
//    A the specimen cross-section (extent of the particles, radii included, across the axis, or
//    the given section area of a specimen that is not a box, e.g. a cylindrical core);
//  - axial strain  eps = (mean u of the loaded end - mean u of the fixed end) / distance of the
//    two end groups' reference centroids (the gauge length between the end particles);
//  - Young's modulus E = sigma / eps (thesis eq. 64 for a single load level);
//  - Poisson's ratios from the bounding particles (thesis eq. 65, Fig. 26): for each lateral axis
//    d, the lateral strain is the change of the distance between the particles within 1.5 r of
//    the two faces normal to d divided by that distance, and nu_ad = -eps_d / eps_axial.
// Signs: tension positive.
#include "dem/bonds/bond_store.h"
#include "dem/core/particle_store.h"
#include "dem/model/groups.h"

namespace dembridge::dem
{
struct AxialResponse
{
  int axis = 0;
  double force = 0;        ///< N, reaction on the loaded end along the axis
  double area = 0;         ///< m^2
  double gauge_length = 0; ///< m
  double stress = 0;       ///< Pa
  double strain = 0;       ///< -
  double youngs_modulus = 0;
  double poisson_ratio[3] = {0, 0, 0}; ///< nu_{axis,d}; 0 on the axis itself
  bool force_controlled = false;       ///< the load was read from the fixed end's reaction
};

/// @p section_area: the cross-section A in m^2 where it is not the particles' extent; 0: the
/// extent.
AxialResponse axial_response(const ParticleStore& p, const Group& fixed_end,
                             const Group& loaded_end, int axis, double section_area = 0);

/// Thesis eq. 64 with F/dL from the force-displacement curve: the least-squares slope (with
/// intercept, so a constant offset does not bias it) of the loaded end's axial force over the
/// end groups' relative axial displacement, scaled by the gauge length and area of `geometry`.
/// The early transient is skipped: only points with |dL| >= 1/4 of the largest are fitted.
struct ModulusFit
{
  double youngs_modulus = 0;
  long points = 0;
};
ModulusFit fit_youngs_modulus(const std::vector<double>& relative_displacement,
                              const std::vector<double>& force, const AxialResponse& geometry);
} // namespace dembridge::dem

namespace dembridge::dem
{
/// Three-point bending (thesis section 4.4, Fig. 28): the load F is the total support reaction
/// normal to the beam, the deflection delta the mean of the loaded (top) and the bottom midspan
/// groups' displacements along the load, L_e the support distance, b the length over which the
/// load is spread (extent of the loaded centres along the span), I = w h^3 / 12 and A = w h
/// from the specimen's extent. Flexural moduli:
///   eq. 67 (point load)        E_f = F/(2 delta) [L_e^3/(24 I) + L_e f_s (1 + nu)/A]
///   eq. 69 (distributed load)  E_f = F/(2 delta) [(8 L_e^3 - 4 b^2 L_e + b^3)/(192 I)
///                                                 + f_s (L_e - b)(1 + nu)/A]
/// and eq. 69 with the bottom deflection alone. nu is the mean of nu_xy, nu_xz from the uniaxial
/// tests; f_s the Timoshenko form factor (6/5 for a rectangle).
struct FlexuralResponse
{
  double load = 0, deflection = 0, bottom_deflection = 0, span = 0, load_length = 0;
  double flexural_modulus_point = 0;  ///< eq. 67
  double flexural_modulus = 0;        ///< eq. 69
  double flexural_modulus_bottom = 0; ///< eq. 69, bottom deflection
  /// E_f 2 delta / F of eq. 67 and eq. 69: the bracketed compliance factors (1/m^2), from the
  /// geometry alone (0 without a span)
  double compliance_factor_point = 0, compliance_factor = 0;
};

FlexuralResponse flexural_response(const ParticleStore& p, const Group& pin, const Group& roller,
                                   const Group& loaded, const Group& bottom, int span_axis,
                                   int load_axis, double poisson_ratio, double form_factor);

/// Eq. 69 with F/delta from the load-deflection curve: the least-squares slope through the origin
/// (the beam starts unloaded at rest) of |load| over |deflection| (delta as flexural_response's:
/// the mean of the loaded and bottom groups' deflections), times compliance_factor / 2 of
/// @p geometry. Every record counts: the slope through the origin weighs the early transient by
/// its small deflection, and averages the ringing of an explicit run.
ModulusFit fit_flexural_modulus(const std::vector<double>& deflection,
                                const std::vector<double>& load, const FlexuralResponse& geometry);

/// The largest rotation from the reference configuration (rad): of any particle (the angle of
/// its orientation) and of any bond's axis (the angle between x_b - x_a and X_b - X_a). A
/// solution linearised in the rotations (the static solver) is accurate while this is small.
double largest_rotation(const ParticleStore& p, const BondStore& b);
} // namespace dembridge::dem
