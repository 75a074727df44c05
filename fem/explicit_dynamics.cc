// dembridge::fem — explicit elastodynamics (lumped mass, central differences).
#include "explicit_dynamics.h"
#include "dem/core/byte_archive.h"
#include "fem/local_array.h"

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace dembridge::fem
{
using namespace dealii;

ExplicitDynamics::ExplicitDynamics(const Parameters& parameters, MPI_Comm comm)
    : ElasticProblem(parameters, comm)
{
}

void ExplicitDynamics::set_weights(PointFunction stiffness_weight_function,
                                   PointFunction mass_weight_function)
{
  stiffness_weight = std::move(stiffness_weight_function);
  mass_weight = std::move(mass_weight_function);
}

void ExplicitDynamics::setup()
{
  if (grid_builder)
  {
    TimerOutput::Scope t(computing_timer, "make grid");
    names = grid_builder(triangulation);
    geometric_tolerance = 1e-6 * GridTools::minimal_cell_diameter(triangulation);
  }
  else
    make_grid();
  setup_system();
  cell_operator.reinit(locally_owned_dofs, locally_relevant_dofs, fe.n_dofs_per_cell(),
                       mpi_communicator);
  cell_matrix_sink = [this](const auto& dofs, const auto& m) { cell_operator.add_cell(dofs, m); };
  assemble_system(/*condense=*/false);
  cell_matrix_sink = nullptr;
  for (auto* v : {&mass, &mass_unweighted, &inverse_mass, &row_sums, &u_owned, &velocity_half,
                  &velocity_trial, &internal_force, &applied_force, &step_force, &outside_force})
    v->reinit(locally_owned_dofs, mpi_communicator);
  for (const auto& line : constraints.get_lines())
    has_hanging_nodes = has_hanging_nodes || !line.entries.empty();
  has_hanging_nodes = Utilities::MPI::logical_or(has_hanging_nodes, mpi_communicator);
  assemble_lumped_mass();
  compute_stable_time_step();
  apply_initial_displacement();
}

// M_ii = sum_q w_M(x_q) rho phi_i(x_q)^2 w_q with Gauss-Lobatto points at the nodes of FE_Q
// (exact diagonal for degree 1 and 2, whose nodes are the Gauss-Lobatto points).
void ExplicitDynamics::assemble_lumped_mass()
{
  TimerOutput::Scope t(computing_timer, "assemble mass");
  const QGaussLobatto<3> quadrature(fe.degree + 1);
  FEValues<3> fe_values(mapping, fe, quadrature,
                        update_values | update_quadrature_points | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  Vector<double> cell_mass(n), cell_mass_unweighted(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      cell_mass = 0;
      cell_mass_unweighted = 0;
      // The weight is read a hair inside the cell: Gauss-Lobatto points lie on the cell's faces,
      // where a weight that jumps across a face (the band's edges) must come from this side.
      const Point<3> centre = cell->center();
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        const Point<3>& x = fe_values.quadrature_point(q);
        const double w = mass_weight ? mass_weight(x + 1e-6 * (centre - x)) : 1.0;
        for (unsigned int i = 0; i < n; ++i)
        {
          const double m = prm.density * fe_values.shape_value(i, q) * fe_values.shape_value(i, q) *
                           fe_values.JxW(q);
          cell_mass(i) += w * m;
          cell_mass_unweighted(i) += m;
        }
      }
      cell->get_dof_indices(dofs);
      cell_operator.add_cell_mass(cell_mass);
      mass.add(dofs, cell_mass);
      mass_unweighted.add(dofs, cell_mass_unweighted);
    }
  mass.compress(VectorOperation::add);
  mass_unweighted.compress(VectorOperation::add);
  // Fixed DoFs (and hanging nodes, which follow their masters) do not answer forces.
  for (const auto i : locally_owned_dofs)
  {
    if (!(mass(i) > 0))
      throw std::runtime_error("FEM/Material/density: non-positive lumped mass");
    inverse_mass(i) = constraints.is_constrained(i) ? 0.0 : 1.0 / mass(i);
  }
  inverse_mass.compress(VectorOperation::insert);
}

// Gershgorin: every eigenvalue of M^-1 K lies below max_i sum_j |K_ij| / M_ii; rows of fixed
// or driven DoFs do not move and are left out. The element bound is taken where it is smaller.
void ExplicitDynamics::compute_stable_time_step()
{
  for (const auto row : locally_owned_dofs)
  {
    double sum = 0;
    if (inverse_mass(row) > 0)
      for (auto entry = system_matrix.begin(row); entry != system_matrix.end(row); ++entry)
        sum += std::abs(entry->value());
    row_sums(row) = sum;
  }
  row_sums.compress(VectorOperation::insert);
  const double omega2 = frequency_bound();
  critical_time_step = omega2 > 0 ? 2.0 / std::sqrt(omega2) : 0.0;
}

double ExplicitDynamics::frequency_bound(const LA::MPI::Vector* added_mass) const
{
  double gershgorin = 0;
  for (const auto i : locally_owned_dofs)
    if (inverse_mass(i) > 0)
      gershgorin =
          std::max(gershgorin, row_sums(i) / (mass(i) + (added_mass ? (*added_mass)(i) : 0.0)));
  gershgorin = Utilities::MPI::max(gershgorin, mpi_communicator);
  if (!cell_operator.active())
    return gershgorin;
  const IndexSet ghosts = [&]
  {
    IndexSet g = locally_relevant_dofs;
    g.subtract_set(locally_owned_dofs);
    return g;
  }();
  LA::MPI::Vector scale(locally_owned_dofs, ghosts, mpi_communicator),
      moves(locally_owned_dofs, ghosts, mpi_communicator);
  for (const auto i : locally_owned_dofs)
  {
    scale(i) = added_mass ? (mass(i) + (*added_mass)(i)) / mass(i) : 1.0;
    moves(i) = inverse_mass(i) > 0 ? 1.0 : 0.0;
  }
  scale.compress(VectorOperation::insert);
  moves.compress(VectorOperation::insert);
  scale.update_ghost_values();
  moves.update_ghost_values();
  return std::min(gershgorin, cell_operator.frequency_bound(scale, moves));
}

void ExplicitDynamics::apply_initial_displacement()
{
  FunctionParser<3> initial(3);
  try
  {
    initial.initialize("x,y,z", prm.initial_displacement, {{"pi", numbers::PI}});
  }
  catch (const std::exception&)
  {
    throw std::runtime_error("FEM/Dynamics/initial displacement: cannot parse '" +
                             prm.initial_displacement + "'");
  }
  set_initial_state(initial, Functions::ZeroFunction<3>(3));
}

void ExplicitDynamics::set_initial_state(const Function<3>& u0, const Function<3>& v0)
{
  VectorTools::interpolate(mapping, dof_handler, u0, u_owned);
  constraints.distribute(u_owned);
  solution = u_owned;
  VectorTools::interpolate(mapping, dof_handler, v0, velocity_half);
  for (const auto i : locally_owned_dofs)
    if (!(inverse_mass(i) > 0))
      velocity_half(i) = 0;
  velocity_half.compress(VectorOperation::insert);
  current_time = 0;
  step_number = 0;
  energy = Energies();
}

void ExplicitDynamics::continue_from(const ExplicitDynamics& earlier, const Function<3>& velocity)
{
  current_time = earlier.current_time;
  step_number = earlier.step_number;
  pvtu_records = earlier.pvtu_records;
  if (driven.empty())
    return;
  LA::MPI::Vector v(locally_owned_dofs, mpi_communicator);
  VectorTools::interpolate(mapping, dof_handler, velocity, v);
  {
    LocalArray from(v), to(velocity_half);
    for (const auto& d : driven)
      to[d.local] = from[d.local];
  }
}

ExplicitDynamics::EnergiesNow ExplicitDynamics::energies_now() const
{
  LA::MPI::Vector Ku(locally_owned_dofs, mpi_communicator);
  system_matrix.vmult(Ku, u_owned);
  const std::size_t n = locally_owned_dofs.n_elements();
  LocalArray v(velocity_half), m(mass);
  double kinetic = 0;
  for (std::size_t i = 0; i < n; ++i)
    kinetic += 0.5 * m[i] * v[i] * v[i];
  EnergiesNow e;
  e.strain = 0.5 * (u_owned * Ku);
  e.load_potential = -(external_force * u_owned);
  e.kinetic = Utilities::MPI::sum(kinetic, mpi_communicator);
  return e;
}

void ExplicitDynamics::prescribe_boundary_displacement(const types::boundary_id id,
                                                       const ComponentSet& mask,
                                                       const Function<3>& g,
                                                       std::function<double(double)> ramp)
{
  const std::vector<bool> components(mask.begin(), mask.end());
  const IndexSet on_boundary =
      DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(components), {id});
  const unsigned int r = drive_ramps.size();
  drive_ramps.push_back(std::move(ramp));
  const auto first = locally_owned_dofs.nth_index_in_set(0);
  const auto& unit_points = fe.get_unit_support_points();
  std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
  std::set<types::global_dof_index> done;
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell->get_dof_indices(cell_dofs);
      for (unsigned int k = 0; k < cell_dofs.size(); ++k)
      {
        const auto i = cell_dofs[k];
        if (!on_boundary.is_element(i) || !locally_owned_dofs.is_element(i) ||
            constraints.is_constrained(i) || !done.insert(i).second)
          continue;
        const Point<3> x = mapping.transform_unit_to_real_cell(cell, unit_points[k]);
        driven.push_back({static_cast<unsigned int>(i - first),
                          g.value(x, fe.system_to_component_index(k).first), r});
        inverse_mass(i) = 0;
      }
    }
  inverse_mass.compress(VectorOperation::insert);
  compute_stable_time_step();
}

// ------------------------------------------------------------------------------------------
// Phase 1: f^n = f_ext + f_applied - K u_n - c M v_{n-1/2}; trial velocity.
void ExplicitDynamics::predict(const double dt)
{
  if (cell_operator.active())
    cell_operator.vmult(internal_force, solution); // u_n with its ghosts (see update())
  else
    system_matrix.vmult(internal_force, u_owned);
  const std::size_t n = locally_owned_dofs.n_elements();
  LocalArray f(step_force), Ku(internal_force), fe_(external_force), fa(applied_force), m(mass),
      minv(inverse_mass), v(velocity_half), vt(velocity_trial), fo(outside_force);
  const bool first_half = step_number == 0 && half_step_start;
  for (std::size_t i = 0; i < n; ++i)
  {
    f[i] = fe_[i] + fa[i] - Ku[i] - mass_damping * m[i] * v[i];
    if (first_half) // v_{-1/2} = v_0 - dt/2 a_0: the first step lands on v_0 + dt/2 a_0
      v[i] -= 0.5 * dt * minv[i] * f[i];
    vt[i] = v[i] + dt * minv[i] * f[i];
    fo[i] = 0;
  }
  outside_force_applied = false;
}

// Phase 2: forces from outside (the coupling's multipliers).
void ExplicitDynamics::apply_force(const LA::MPI::Vector& force, const double dt)
{
  const std::size_t n = locally_owned_dofs.n_elements();
  LocalArray f(force), minv(inverse_mass), vt(velocity_trial), fo(outside_force);
  for (std::size_t i = 0; i < n; ++i)
  {
    vt[i] += dt * minv[i] * f[i];
    fo[i] += f[i];
  }
  outside_force_applied = true;
}

// Phase 3: v_{n+1/2}, u_{n+1}; the works summed every step, the energies of step n on record.
void ExplicitDynamics::update(const double dt, const bool record)
{
  const std::size_t n = locally_owned_dofs.n_elements();
  {
    LocalArray f(step_force), Ku(internal_force), fe_(external_force), fa(applied_force), m(mass),
        v(velocity_half), vt(velocity_trial), fo(outside_force), u(u_owned);
    // Works are summed as f^n . (v_{n-1/2} + v_{n+1/2}) / 2 dt; the shadow energy H_n has only
    // received f^n . v_{n+1/2} dt / 2 less of it (H_{n+1} - H_n = (f^n + f^{n+1}) / 2 .
    // v_{n+1/2} dt), so each work is reported without that half-step lead. Each rank sums its
    // own share; the shares are added over the ranks on record steps only.
    double lead_boundary = 0;
    for (const auto& d : driven) // u_{n+1} = ramp(t_{n+1}) g: the reaction is what that takes
    {
      const double vd = (drive_ramps[d.ramp](current_time + dt) * d.target - u[d.local]) / dt;
      const double reaction = m[d.local] * (vd - v[d.local]) / dt - f[d.local] - fo[d.local];
      boundary_work_summed += reaction * 0.5 * (v[d.local] + vd) * dt;
      lead_boundary += reaction * 0.5 * vd * dt;
      vt[d.local] = vd;
    }
    if (!record)
    {
      double damping = 0, outside = 0;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double v0 = v[i], v1 = vt[i], mean = 0.5 * (v0 + v1);
        damping += m[i] * v0 * mean;
        outside += (fa[i] + fo[i]) * mean;
        v[i] = v1;
        u[i] += dt * v1;
      }
      damping_summed += mass_damping * damping * dt;
      outside_work_summed += outside * dt;
    }
    else
    {
      double sums[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (std::size_t i = 0; i < n; ++i)
      {
        const double v0 = v[i], v1 = vt[i], mean = 0.5 * (v0 + v1);
        sums[0] += 0.5 * m[i] * v0 * v1;
        sums[1] += 0.5 * m[i] * mean * mean;
        sums[2] += 0.5 * u[i] * Ku[i];
        sums[3] -= fe_[i] * u[i];
        sums[4] += mass_damping * m[i] * v0 * mean * dt;
        sums[5] += (fa[i] + fo[i]) * mean * dt;
        sums[6] += mass_damping * m[i] * v0 * v1 * 0.5 * dt; // leads (see above)
        sums[7] += (fa[i] + fo[i]) * v1 * 0.5 * dt;
        v[i] = v1;
        u[i] += dt * v1;
      }
      damping_summed += sums[4];
      outside_work_summed += sums[5];
      sums[4] = damping_summed;
      sums[5] = outside_work_summed;
      sums[8] = boundary_work_summed;
      sums[9] = lead_boundary;
      Utilities::MPI::sum(ArrayView<const double>(sums, 10), mpi_communicator,
                          ArrayView<double>(sums, 10));
      energy.kinetic_shadow = sums[0];
      energy.kinetic = sums[1];
      energy.strain = sums[2];
      energy.load_potential = sums[3];
      energy.damping = sums[4] - sums[6];
      energy.outside_work = sums[5] - sums[7];
      energy.boundary_work = sums[8] - sums[9];
    }
  }
  if (has_hanging_nodes)
    constraints.distribute(u_owned);
  solution = u_owned;
  current_time += dt;
  ++step_number;
}

void broadcast_state(MPI_Comm comm, const std::function<void(dem::StateArchive&)>& visit)
{
  std::string bytes;
  if (Utilities::MPI::this_mpi_process(comm) == 0)
  {
    dem::ByteArchive packed;
    visit(packed);
    bytes = packed.bytes();
  }
  if (Utilities::MPI::n_mpi_processes(comm) == 1)
    return;
  bytes = Utilities::MPI::broadcast(comm, bytes, 0);
  if (Utilities::MPI::this_mpi_process(comm) != 0)
  {
    dem::ByteArchive unpacked(std::move(bytes));
    visit(unpacked);
  }
}

void ExplicitDynamics::owned_ranges(std::vector<int>& counts, std::vector<int>& offsets) const
{
  const unsigned int ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
  // MPI counts are int
  if (dof_handler.n_dofs() > types::global_dof_index(std::numeric_limits<int>::max()))
    throw std::runtime_error("checkpoints: more than 2^31 FE DoFs");
  const unsigned long long mine[2] = {
      locally_owned_dofs.n_elements() > 0 ? locally_owned_dofs.nth_index_in_set(0) : 0,
      locally_owned_dofs.n_elements()};
  std::vector<unsigned long long> all(2 * ranks);
  MPI_Allgather(mine, 2, MPI_UNSIGNED_LONG_LONG, all.data(), 2, MPI_UNSIGNED_LONG_LONG,
                mpi_communicator);
  counts.assign(ranks, 0);
  offsets.assign(ranks, 0);
  unsigned long long next = 0;
  for (unsigned int r = 0; r < ranks; ++r)
  {
    counts[r] = int(all[2 * r + 1]);
    offsets[r] = int(next);
    if (counts[r] > 0 && all[2 * r] != next)
      throw std::logic_error("checkpoints: the FE DoFs are not owned in rank order");
    next += all[2 * r + 1];
  }
}

// Checkpoint state (docs/checkpoint.md, /fe/). Between steps a step reads u_n (u_owned, and
// `solution`, its ghosted copy), v_{n-1/2}, the applied forces, the time (driven boundaries are
// ramps of it), the step count (the half-step start) and the works summed so far; the trial
// velocity, step, internal and outside forces are overwritten by predict() before they are read.
// The energies are those of the last record (read by the caller between records).
void ExplicitDynamics::gather_state()
{
  std::vector<int> counts, offsets;
  owned_ranges(counts, offsets);
  const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
  const unsigned int ranks = counts.size();
  for (auto [vector, out] :
       {std::pair{&u_owned, &gathered.u}, std::pair{&velocity_half, &gathered.v},
        std::pair{&applied_force, &gathered.applied}})
  {
    LocalArray local(*vector);
    out->assign(rank == 0 ? dof_handler.n_dofs() : 0, 0.0);
    MPI_Gatherv(local.data(), counts[rank], MPI_DOUBLE, out->data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, mpi_communicator);
  }
  const double works[3] = {boundary_work_summed, damping_summed, outside_work_summed};
  std::vector<double> all(rank == 0 ? 3 * ranks : 0);
  MPI_Gather(works, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, 0, mpi_communicator);
  for (auto* w : {&gathered.boundary_work, &gathered.damping, &gathered.outside_work})
    w->clear();
  for (std::size_t r = 0; r < all.size() / 3; ++r)
  {
    gathered.boundary_work.push_back(all[3 * r]);
    gathered.damping.push_back(all[3 * r + 1]);
    gathered.outside_work.push_back(all[3 * r + 2]);
  }
}

void ExplicitDynamics::visit_state(dem::StateArchive& a)
{
  dem::StateGroup group(a, "fe");
  const std::size_t ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
  for (auto [name, values] :
       {std::pair{"displacement", &gathered.u}, std::pair{"velocity", &gathered.v},
        std::pair{"applied_force", &gathered.applied}})
  {
    if (a.loading())
      values->assign(dof_handler.n_dofs(), 0.0);
    a.io_sized(name, *values);
  }
  // why: each rank sums its own share; another partition adds other numbers in another order
  for (auto [name, values] : {std::pair{"boundary_work_summed", &gathered.boundary_work},
                              std::pair{"damping_summed", &gathered.damping},
                              std::pair{"outside_work_summed", &gathered.outside_work}})
  {
    a.io(name, *values);
    if (a.loading() && values->size() != ranks)
      throw dem::InputError(a.where() + name + ": the checkpoint was written on " +
                            std::to_string(values->size()) + " MPI rank(s), this run has " +
                            std::to_string(ranks) + " (resume it on as many)");
  }
  visit_scalars(a);
  if (!a.loading())
    gathered = Gathered(); // written: free rank 0's copies
}

void ExplicitDynamics::scatter_state()
{
  std::vector<int> counts, offsets;
  owned_ranges(counts, offsets);
  const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
  const unsigned int ranks = counts.size();
  for (auto [vector, in] :
       {std::pair{&u_owned, &gathered.u}, std::pair{&velocity_half, &gathered.v},
        std::pair{&applied_force, &gathered.applied}})
  {
    LocalArray local(*vector);
    MPI_Scatterv(in->data(), counts.data(), offsets.data(), MPI_DOUBLE, local.data(), counts[rank],
                 MPI_DOUBLE, 0, mpi_communicator);
  }
  solution = u_owned;
  std::vector<double> all;
  if (rank == 0)
    for (unsigned int r = 0; r < ranks; ++r)
      all.insert(all.end(),
                 {gathered.boundary_work[r], gathered.damping[r], gathered.outside_work[r]});
  double works[3];
  MPI_Scatter(all.data(), 3, MPI_DOUBLE, works, 3, MPI_DOUBLE, 0, mpi_communicator);
  boundary_work_summed = works[0];
  damping_summed = works[1];
  outside_work_summed = works[2];
  gathered = Gathered();
  broadcast_state(mpi_communicator, [this](dem::StateArchive& a) { visit_scalars(a); });
}

void ExplicitDynamics::visit_scalars(dem::StateArchive& a)
{
  a.io("time", current_time);
  long steps = step_number;
  a.io("steps", steps);
  step_number = static_cast<unsigned int>(steps);
  {
    dem::StateGroup energies(a, "energy");
    a.io("kinetic_shadow", energy.kinetic_shadow);
    a.io("kinetic", energy.kinetic);
    a.io("strain", energy.strain);
    a.io("load_potential", energy.load_potential);
    a.io("damping", energy.damping);
    a.io("outside_work", energy.outside_work);
    a.io("boundary_work", energy.boundary_work);
  }
  // the .pvd's records so far (each output rewrites the .pvd with all of them)
  std::vector<double> times;
  std::string names;
  for (const auto& [t, f] : pvtu_records)
    times.push_back(t), names += f + "\n";
  a.io("pvtu_times", times);
  a.io("pvtu_files", names);
  if (!a.loading())
    return;
  pvtu_records.clear();
  std::size_t at = 0;
  for (const double t : times)
  {
    const std::size_t end = names.find('\n', at);
    if (end == std::string::npos)
      throw dem::InputError(a.where() + "pvtu_files: fewer names than times");
    pvtu_records.emplace_back(t, names.substr(at, end - at));
    at = end + 1;
  }
}

void ExplicitDynamics::step(const double dt)
{
  predict(dt);
  update(dt);
}

std::string ExplicitDynamics::output(const std::filesystem::path& output_dir,
                                     const unsigned int cycle, const double time)
{
  output_results(output_dir, cycle, time);
  return pvtu_records.back().second;
}
} // namespace dembridge::fem
