#pragma once
// The support reaction and Young's modulus of a continuum, one measurement for every mode that
// has a continuum (Mode = fem, the coupled run's continuum): FEM/Measurements/reaction boundary
// along the reaction direction e, and with a loaded boundary the thesis' eq. (64),
//   E = (F / A) (L0 / dL),  F = -R . e,  L0 = |(c_loaded - c_reaction) . e|,
//   dL = (u_loaded - u_reaction) . e,
// with A the reaction boundary's area, c the boundaries' centroids and u their mean
// displacements (the reaction opposes the elongation).
#include "fem/elastic_problem.h"
#include "fem/parameters.h"
#include <optional>

namespace dembridge::fem
{
struct ReactionMeasurement
{
  dealii::Tensor<1, 3> reaction;    ///< N, the support's force on the body
  double reaction_along = 0;        ///< N, reaction . e
  bool has_loaded_boundary = false; ///< the fields below are set
  double area = 0;                  ///< m^2, of the reaction boundary
  double gauge_length = 0;          ///< m, L0
  double elongation = 0;            ///< m, dL
  double youngs_modulus = 0;        ///< Pa; infinite or NaN when dL = 0 (callers say so)
};

/// None without FEM/Measurements/reaction boundary; throws std::runtime_error naming the key
/// for a boundary the mesh does not have (collective).
std::optional<ReactionMeasurement> measure_reaction(const ElasticProblem& problem,
                                                    const Parameters& p);
} // namespace dembridge::fem
