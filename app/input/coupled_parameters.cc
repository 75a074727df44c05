#include "app/input/coupled_parameters.h"
#include "app/input/dem_parameters.h"
#include "coupling/coupling_parameters.h"
#include "fem/parameters.h"

namespace dembridge::app
{
using dealii::ParameterHandler;

coupling::CoupledCase parse_coupled_case(ParameterHandler& prm)
{
  coupling::CoupledCase c;
  c.particles = parse_dem_case(prm);
  if (c.particles.run.static_solver)
    throw dem::InputError("Simulation/solver: a coupled run is explicit (solver = explicit)");
  c.continuum = fem::parse_parameters(prm);
  c.continuum.problem = fem::ProblemKind::explicit_dynamics;
  coupling::parse_coupling_section(prm, c);
  return c;
}

coupling::CoupledRunSettings parse_coupled_run_settings(ParameterHandler& prm,
                                                        const coupling::CoupledCase& c)
{
  coupling::CoupledRunSettings r;
  const OutputSettings out = parse_output_settings(prm);
  r.end_time = c.particles.run.end_time;
  r.max_steps = c.particles.run.max_steps;
  r.record_interval = out.history_interval;
  r.snapshot_interval = out.snapshot_interval;
  r.rest_tolerance = prm.get_double({"Coupling"}, "rest tolerance");
  r.rest_after = coupling::last_ramp_end(c);
  r.pulse_side = coupling::pulse_side(c);
  return r;
}
} // namespace dembridge::app
