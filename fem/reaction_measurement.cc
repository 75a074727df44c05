#include "fem/reaction_measurement.h"
#include "fem/mesh.h"
#include <cmath>

namespace dembridge::fem
{
std::optional<ReactionMeasurement> measure_reaction(const ElasticProblem& problem,
                                                    const Parameters& p)
{
  if (p.reaction_boundary.empty())
    return std::nullopt;
  ReactionMeasurement m;
  const auto id = find_boundary(problem.boundary_names(), p.reaction_boundary,
                                "FEM/Measurements/reaction boundary");
  m.reaction = problem.reaction(id);
  m.reaction_along = m.reaction * p.reaction_direction;
  if (p.loaded_boundary.empty())
    return m;
  const auto loaded = find_boundary(problem.boundary_names(), p.loaded_boundary,
                                    "FEM/Measurements/loaded boundary");
  const auto fixed_means = problem.boundary_means(id);
  const auto loaded_means = problem.boundary_means(loaded);
  const dealii::Tensor<1, 3> e = p.reaction_direction;
  m.has_loaded_boundary = true;
  m.area = fixed_means.area;
  m.gauge_length = std::abs((loaded_means.centroid - fixed_means.centroid) * e);
  m.elongation = (loaded_means.mean_displacement - fixed_means.mean_displacement) * e;
  m.youngs_modulus = -(m.reaction * e) / m.area * m.gauge_length / m.elongation;
  return m;
}
} // namespace dembridge::fem
