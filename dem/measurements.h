#pragma once
// Specimen measurements from particle displacements and support reactions (thesis section 4.3):
//  - axial stress  sigma = F / A, with F the reaction of the loaded end group along the axis and
//    A the specimen cross-section (extent of the particles, radii included, across the axis);
//  - axial strain  eps = (mean u of the loaded end - mean u of the fixed end) / distance of the
//    two end groups' reference centroids (the gauge length between the end particles);
//  - Young's modulus E = sigma / eps (thesis eq. 64 for a single load level);
//  - Poisson's ratios from the bounding particles (thesis eq. 65, Fig. 26): for each lateral axis
//    d, the lateral strain is the change of the distance between the particles within 1.5 r of
//    the two faces normal to d divided by that distance, and nu_ad = -eps_d / eps_axial.
// Signs: tension positive.
#include "groups.h"
#include "particle_store.h"

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
};

AxialResponse axial_response(const ParticleStore& p, const Group& fixed_end,
                             const Group& loaded_end, int axis);
} // namespace dembridge::dem
