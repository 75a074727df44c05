// CoupledProblem's adaptive particle region (coupled_problem.h, adaptive_region.h): its set-up
// and a growth event.
//
// A growth event, between steps (right after a record step n, state x^{n+1}, v^{n+1/2}):
//  1. the energy before: both sides' strain, load potential and kinetic energy with the
//     half-step velocities (blending weights included);
//  2. what the particles that join take from the continuum, at their reference centres X:
//     u(X), v(X), and the rotation and spin 1/2 curl u, 1/2 curl v (central differences over
//     1e-3 r inside the cell); their position X + u(X), velocity v(X), orientation the rotation
//     (a quaternion of the rotation vector), angular velocity the spin. Their bonds are formed in
//     the reference configuration, so that they carry the continuum's strain at once;
//  3. both sides are rebuilt on the larger region (the continuum on the grid refined where the
//     fine zone widened, less the cells that turned particle-only; the band along the new
//     region's faces; the constraint matrix and the common step anew); the particles and bonds
//     that were there take their state (positions, velocities, orientations, damage, strengths,
//     broken or not), the continuum its displacements and velocities (the earlier Q1 field,
//     exactly: the new grid's lines hold the earlier's), the particle solver the time and the
//     crack log;
//  4. the tie's gap at the new interface; the energy after, as in 1.
// Energy bookkeeping: the models' works (damping, loads, supports, fracture, the tie's work on
// the continuum) up to the record before the event are carried and added to the new models'
// own; the initial energy stays the run's. The balance error then holds the events' jumps (and
// one step's work between the record and the event, of order 1 / steps of the work): it is not
// corrected for them.
#include "coupling/coupled_problem.h"

#include "dem/measurements/particle_stress.h"
#include "dem/packing/packings.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

namespace dembridge::coupling
{
using namespace dealii;

namespace
{
using Key = std::array<std::int64_t, 3>;

Key node_key(const Point<3>& x, double q)
{
  return Key{{std::llround(x[0] / q), std::llround(x[1] / q), std::llround(x[2] / q)}};
}

/// An earlier continuum's Q1 field from its nodal values, on its box grid's @p lines: at a point
/// of a new node, the trilinear interpolation over the earlier cell that holds it (along an axis
/// where the point lies on an earlier line, that line alone). The new grid's lines hold the
/// earlier's, so that this is the earlier field itself, and a node that was there keeps its value.
class NodalField : public Function<3>
{
public:
  NodalField(const std::map<Key, Vec3>& values, const GridLines& lines, double q)
      : Function<3>(3), values_(values), lines_(lines), q_(q)
  {
  }
  double value(const Point<3>& x, const unsigned int c) const override
  {
    // per axis the earlier lines around x and their weights
    std::array<std::array<double, 2>, 3> at{}, weight{};
    std::array<int, 3> n{};
    for (int d = 0; d < 3; ++d)
    {
      const auto& l = lines_[d];
      auto above = std::lower_bound(l.begin(), l.end(), x[d] - q_);
      if (above == l.end())
        throw std::logic_error("adaptive region: a new node lies outside the earlier grid");
      if (std::abs(*above - x[d]) <= q_ || above == l.begin())
      {
        at[d] = {{*above, 0.0}}, weight[d] = {{1.0, 0.0}}, n[d] = 1;
        continue;
      }
      const double a = *std::prev(above), b = *above, t = (x[d] - a) / (b - a);
      at[d] = {{a, b}}, weight[d] = {{1 - t, t}}, n[d] = 2;
    }
    double sum = 0;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          const auto it = values_.find(node_key(Point<3>(at[0][i], at[1][j], at[2][k]), q_));
          if (it == values_.end())
            throw std::logic_error("adaptive region: a new node lies in no cell of the earlier "
                                   "continuum");
          sum += weight[0][i] * weight[1][j] * weight[2][k] * it->second[c];
        }
    return sum;
  }

private:
  const std::map<Key, Vec3>& values_;
  const GridLines& lines_;
  double q_;
};

/// u and v at every node of @p fe (one process), keyed by position.
void nodal_values(const fem::ExplicitDynamics& fe, double q, std::map<Key, Vec3>& u,
                  std::map<Key, Vec3>& v)
{
  const auto& dofs = fe.get_dof_handler();
  for (const auto& cell : dofs.active_cell_iterators())
    for (const unsigned int k : cell->vertex_indices())
    {
      const Key key = node_key(cell->vertex(k), q);
      if (u.count(key))
        continue;
      Vec3 uk, vk;
      for (unsigned int c = 0; c < 3; ++c)
      {
        const auto i = cell->vertex_dof_index(k, c);
        uk[c] = fe.displacement()(i);
        vk[c] = fe.velocity()(i);
      }
      u[key] = uk;
      v[key] = vk;
    }
}

/// Rotation 1/2 curl f from the gradient g(i, j) = d f_i / d x_j.
Vec3 half_curl(const Eigen::Matrix3d& g)
{
  return 0.5 * Vec3(g(2, 1) - g(1, 2), g(0, 2) - g(2, 0), g(1, 0) - g(0, 1));
}
} // namespace

void CoupledProblem::prepare_adaptive_region()
{
  auto& g = settings_.geometry;
  const auto& a = settings_.adaptive;
  if (Utilities::MPI::n_mpi_processes(comm_) > 1)
    throw std::runtime_error("Coupling/Adaptive region/enabled: an adaptive region runs on one "
                             "MPI process (this run has " +
                             std::to_string(Utilities::MPI::n_mpi_processes(comm_)) + ")");
  if (g.region)
    throw std::runtime_error("Coupling/particle region file: an adaptive region starts from the "
                             "particle box (Particles/origin, box size), not a volume");
  using Kind = dem::ParticleSource::Kind;
  auto& src = dem_case_.particles;
  if (!(src.kind == Kind::cubic || src.kind == Kind::hcp || src.kind == Kind::fcc))
    throw std::runtime_error("Particles/source: an adaptive region grows a lattice (cubic, hcp "
                             "or fcc) by whole periods; a random packing is not available yet");
  if (dem_case_.contacts.enabled() || !dem_case_.walls.empty())
    throw std::runtime_error("Contacts/model: contacts and walls are not available with an "
                             "adaptive region yet (their state is not handed over at a growth)");
  const auto& damage = dem_case_.damage;
  if (damage.law.mode == dem::FailureMode::none)
    throw std::runtime_error("Coupling/Adaptive region/enabled: the particle model has no bond "
                             "strengths to grow against (Damage/failure = none)");
  if (damage.scatter != dem::StrengthScatter::none && !damage.scatter_by_position)
    throw std::runtime_error("Damage/scatter key: an adaptive region needs scatter key = position "
                             "(a bond keeps its strength whatever the region, as in full DEM)");
  const Vec3 lo = a.envelope_given ? a.envelope_lo : g.domain_lo;
  const Vec3 hi = a.envelope_given ? a.envelope_hi : g.domain_hi;
  const GridLines lines =
      AdaptiveRegion::envelope_grid(g, lo, hi, settings_.element_size, settings_.band_element_size,
                                    settings_.far_element_size, settings_.element_growth);
  // the packing over the envelope, once (every rank: the region's cells are every rank's)
  dem::ParticleSource whole = src;
  whole.origin = lo;
  whole.box_size = hi - lo;
  whole.keep = nullptr;
  dem::ParticleStore packing;
  dem::generate_particles(whole, packing, dem_case_.run.threads);
  PackingStrength strength;
  strength.law = damage.law;
  strength.tensile_strength = damage.tensile_strength;
  strength.shear_strength =
      damage.law.shear == dem::ShearCriterion::constant ? damage.shear_strength : damage.cohesion;
  adaptive_ = std::make_unique<AdaptiveRegion>(a, lines, g, strength, packing.reference_position,
                                               2 * src.radius);
  adaptive_->start_from_box(g.particle_lo, g.particle_hi, "Particles/origin");
  adaptive_->widen_fine_zone();
  src.origin = lo;
  src.box_size = hi - lo;
  apply_region();
}

void CoupledProblem::apply_region()
{
  settings_.geometry.region = adaptive_->volume();
  fine_planes_.lines = adaptive_->fe_lines();
  const AdaptiveRegion* a = adaptive_.get();
  dem_case_.particles.keep = [a](const Vec3& x) { return a->in_region(x); };
}

double CoupledProblem::stored_energy_now(double* strain)
{
  double dem[2] = {0, 0}; // strain, kinetic
  if (root_)
  {
    const auto& p = model_.particles;
    dem[0] = dem::particle_stresses(p, model_.bonds).strain_energy;
    for (std::size_t i = 0; i < p.size(); ++i)
      dem[1] += 0.5 * p.mass[i] * p.velocity[i].squaredNorm() +
                0.5 * p.inertia[i] * p.angular_velocity[i].squaredNorm();
  }
  MPI_Bcast(dem, 2, MPI_DOUBLE, 0, comm_);
  const auto fe = fe_->energies_now();
  if (strain)
    *strain = dem[0] + fe.strain;
  return dem[0] + dem[1] + fe.strain + fe.load_potential + fe.kinetic;
}

double CoupledProblem::fracture_energy() const
{
  const dem::ExplicitSolver* s = particle_solver(); // the report solver on the ranks
  return carried_.dem_other + (s ? s->energy().fracture : 0.0);
}

std::optional<GrowthEvent> CoupledProblem::grow_region_if_due()
{
  if (!adaptive_)
    return std::nullopt;
  // the band's bonds at or above the band threshold mark their cells too: the particle model's
  // own failure index where damage nears the band
  std::vector<Vec3> loaded_bonds;
  if (root_)
  {
    const auto& b = model_.bonds;
    const auto& X = model_.particles.reference_position;
    for (std::size_t n = 0; n < band_kappa_.size(); ++n)
      if (band_kappa_[n] >= adaptive_->settings().band_threshold)
      {
        const std::size_t k = blending_.band_bonds[n];
        loaded_bonds.push_back(0.5 * (X[b.a[k]] + X[b.b[k]]));
      }
  }
  adaptive_->measure(*fe_, loaded_bonds);
  const auto proposal = adaptive_->propose();
  using Kind = AdaptiveRegion::Proposal::Kind;
  const double threshold = adaptive_->settings().threshold;
  if (proposal.kind == Kind::whole_body)
  {
    std::ostringstream m;
    m << "Coupling/Adaptive region/threshold: at t = " << time_
      << " s the continuum's utilisation passes " << threshold
      << " in every cell (a uniform stress): the particle region would have to grow through the "
         "whole body; run it as full DEM (Mode = dem) or raise the threshold";
    throw std::runtime_error(m.str());
  }
  if (proposal.kind == Kind::capped)
  {
    if (!growth_cap_.reached)
    {
      growth_cap_ = {true, time_, proposal.particles};
      if (root_)
      {
        std::printf("coupling: the particle region stops growing at t = %.4g s: it would hold "
                    "%zu particles, above Coupling/Adaptive region/maximum particles (%zu)\n",
                    time_, proposal.particles, adaptive_->settings().maximum_particles);
        std::fflush(stdout);
      }
    }
    return std::nullopt;
  }
  if (proposal.kind != Kind::grow)
    return std::nullopt;

  auto event = grow_region(proposal.cells);
  event.marked_cells = proposal.marked;
  event.marked_by_bonds = proposal.marked_by_bonds;
  event.max_utilisation = adaptive_->max_utilisation();
  growth_events_.back() = event;
  if (root_)
  {
    std::printf("coupling: the particle region grew at t = %.5g s: %zu cells marked (%zu by "
                "band bonds; largest utilisation %.3f), +%zu cells (%zu), +%zu particles (%zu), "
                "+%zu bonds; energy jump %.3e J (%.2e of the strain energy); time step %.4g s; "
                "%.2f s\n",
                event.time, event.marked_cells, event.marked_by_bonds, event.max_utilisation,
                event.cells_added, event.region_cells, event.particles_added, event.n_particles,
                event.bonds_added, event.energy_jump(), event.energy_jump_ratio(), event.time_step,
                event.wall_seconds);
    std::fflush(stdout);
  }
  return event;
}

// What a growth hands from the earlier models to the new ones (grow_region's steps).
struct CoupledProblem::GrowthHandover
{
  std::vector<char> old_cells;                         ///< the region before the growth
  std::map<std::int32_t, std::array<Vec3, 4>> joining; ///< packing index: u, v, rotation, spin
  double key_quantum = 0;                              ///< node positions' rounding, m
  std::map<Key, Vec3> node_u, node_v;                  ///< the earlier continuum's nodes
  GridLines old_lines;                                 ///< its grid's lines
  dem::Model old;                                      ///< the earlier particle model
  std::vector<std::int32_t> old_packing;               ///< its particles' packing indices
  std::vector<dem::CrackEvent> cracks;                 ///< its solver's crack log
  std::vector<double> old_tensile, old_shear;          ///< its bonds' own strengths, Pa
  std::unique_ptr<Handshake> old_handshake;            ///< outlives old_fe (its weights)
  std::unique_ptr<fem::ExplicitDynamics> old_fe;
  std::vector<std::int32_t> id_of_old; ///< old particle -> new id
  std::vector<long> new_bond;          ///< old bond -> new bond
};

GrowthEvent CoupledProblem::grow_region(const std::vector<char>& cells)
{
  if (!adaptive_)
    throw std::logic_error("CoupledProblem::grow_region: no adaptive region");
  const auto start = std::chrono::steady_clock::now();
  GrowthEvent event;
  event.time = time_;
  event.step = steps_;
  event.energy_before = stored_energy_now(&event.strain_energy);
  const std::size_t particles_before = n_particles_;
  const std::size_t bonds_before = root_ ? model_.bonds.size() : 0;
  const std::size_t cells_before = adaptive_->n_region_cells();

  GrowthHandover h;
  h.old_cells = add_region_cells(cells);
  sample_continuum_at_joining(h);
  hand_over_earlier_models(h);
  build(
      [&]
      {
        adopt_particle_state(h);
        adopt_bond_state(h);
        renumber_crack_log(h);
        check_loaded_groups_kept(h.old);
      });
  continue_continuum(h);
  set_tie_gap(); // 4. at the new interface
  if (root_)
    solver_->continue_run(time_, std::move(h.cracks));

  event.energy_after = stored_energy_now(nullptr);
  event.region_cells = adaptive_->n_region_cells();
  event.cells_added = event.region_cells - cells_before;
  event.n_particles = n_particles_;
  event.particles_added = n_particles_ - particles_before;
  event.n_bonds = root_ ? model_.bonds.size() : 0;
  event.bonds_added = event.n_bonds - bonds_before;
  event.time_step = dt_;
  event.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  growth_events_.push_back(event);
  return event;
}

// The region becomes its cells and @p cells (no switching back); returns the cells it had.
std::vector<char> CoupledProblem::add_region_cells(const std::vector<char>& cells)
{
  const std::vector<char> old_cells = adaptive_->cells();
  std::vector<char> grown = cells;
  for (std::size_t c = 0; c < grown.size() && c < old_cells.size(); ++c)
    grown[c] = grown[c] || old_cells[c];
  adaptive_->set_cells(grown);
  adaptive_->widen_fine_zone();
  return old_cells;
}

// 2. the continuum at the centres that join: u, v and their rotations 1/2 curl (central
// differences over 1e-3 r; one process: rank 0 holds the points).
void CoupledProblem::sample_continuum_at_joining(GrowthHandover& h)
{
  std::vector<Vec3> fresh;
  for (const Vec3& X : adaptive_->packing())
    if (adaptive_->in_region(X) && !adaptive_->in_cells(h.old_cells, X))
      fresh.push_back(X);
  const double delta = 1e-3 * dem_case_.particles.radius;
  std::vector<Vec3> points;
  for (const Vec3& X : fresh)
  {
    points.push_back(X);
    for (int d = 0; d < 3; ++d)
      for (const double s : {-1.0, 1.0})
        points.push_back(X + s * delta * Vec3::Unit(d));
  }
  PointTransfer at;
  at.reinit(*fe_, points, "Coupling/Adaptive region");
  std::vector<double> slots, u, v;
  at.gather(fe_->displacement(), slots);
  at.interpolate(slots, u);
  at.gather(fe_->velocity(), slots);
  at.interpolate(slots, v);
  auto value = [](const std::vector<double>& f, std::size_t p)
  { return Vec3(f[3 * p], f[3 * p + 1], f[3 * p + 2]); };
  for (std::size_t n = 0; n < fresh.size(); ++n)
  {
    const std::size_t p0 = 7 * n;
    Eigen::Matrix3d gu, gv;
    for (int d = 0; d < 3; ++d)
    {
      gu.col(d) = (value(u, p0 + 2 + 2 * d) - value(u, p0 + 1 + 2 * d)) / (2 * delta);
      gv.col(d) = (value(v, p0 + 2 + 2 * d) - value(v, p0 + 1 + 2 * d)) / (2 * delta);
    }
    h.joining[adaptive_->packing_index(fresh[n])] = {
        {value(u, p0), value(v, p0), half_curl(gu), half_curl(gv)}};
  }
}

// 1./3. the earlier models' state kept by packing index (nodes by position), their works
// carried; the region's new volume applied for the build.
void CoupledProblem::hand_over_earlier_models(GrowthHandover& h)
{
  h.key_quantum = 1e-6 * 2 * dem_case_.particles.radius;
  nodal_values(*fe_, h.key_quantum, h.node_u, h.node_v);
  h.old_lines = fine_planes_.lines;
  h.old = std::move(model_);
  h.old_packing = packing_of_;
  if (root_)
  {
    const auto& e = solver_->energy();
    carried_.dem_damping += e.damping;
    carried_.dem_external += e.external;
    carried_.dem_other += e.fracture + e.friction + e.contact_damping;
    h.cracks = solver_->cracks();
    auto& b = h.old.bonds;
    h.old_tensile = b.tensile_strength;
    h.old_shear = b.shear_strength;
    for (std::size_t n = 0; n < blending_.band_bonds.size() && n < band_tensile_.size(); ++n)
    {
      h.old_tensile[blending_.band_bonds[n]] = band_tensile_[n];
      h.old_shear[blending_.band_bonds[n]] = band_shear_[n];
    }
  }
  {
    const auto& f = fe_->energies();
    carried_.fe_damping += f.damping;
    carried_.fe_boundary_work += f.boundary_work;
    carried_.multiplier_work_fe += f.outside_work;
  }
  solver_.reset(); // it held the old model's stores
  h.old_fe = std::move(fe_);
  h.old_handshake = std::move(handshake_);
  apply_region();
}

// The particles that were there keep their state; those that join take the continuum's.
void CoupledProblem::adopt_particle_state(GrowthHandover& h)
{
  auto& p = model_.particles;
  const auto& op = h.old.particles;
  std::vector<int> old_of(adaptive_->packing().size(), -1); // packing -> old particle
  for (std::size_t i = 0; i < op.size(); ++i)
    old_of[std::size_t(h.old_packing[i])] = int(i);
  h.id_of_old.assign(op.size(), -1);
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const int o = old_of[std::size_t(packing_of_[i])];
    if (o >= 0)
    {
      h.id_of_old[std::size_t(o)] = p.id[i];
      p.position[i] = op.position[o];
      p.velocity[i] = op.velocity[o];
      p.angular_velocity[i] = op.angular_velocity[o];
      p.orientation[i] = op.orientation[o];
      continue;
    }
    const auto& t = h.joining.at(packing_of_[i]);
    p.position[i] = p.reference_position[i] + t[0];
    p.velocity[i] = t[1];
    const double angle = t[2].norm();
    p.orientation[i] =
        angle > 0 ? dem::Quat(Eigen::AngleAxisd(angle, t[2] / angle)) : dem::Quat::Identity();
    p.angular_velocity[i] = t[3];
  }
}

// The bonds that were there (found by their particles' packing indices) keep their state,
// damage and strengths; the coordination numbers anew.
void CoupledProblem::adopt_bond_state(GrowthHandover& h)
{
  auto& p = model_.particles;
  auto& b = model_.bonds;
  std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> by_pair;
  const auto& ob = h.old.bonds;
  for (std::size_t k = 0; k < ob.size(); ++k)
  {
    const auto a = h.old_packing[ob.a[k]], c = h.old_packing[ob.b[k]];
    by_pair[{std::min(a, c), std::max(a, c)}] = k;
  }
  h.new_bond.assign(ob.size(), -1);
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    const auto a = packing_of_[b.a[k]], c = packing_of_[b.b[k]];
    const auto it = by_pair.find({std::min(a, c), std::max(a, c)});
    if (it == by_pair.end())
      continue;
    const std::size_t o = it->second;
    h.new_bond[o] = long(k);
    b.state[k] = ob.state[o];
    if (b.has_failure())
    {
      b.tensile_strength[k] = h.old_tensile[o];
      b.shear_strength[k] = h.old_shear[o];
      b.damage[k] = ob.damage[o];
      b.kappa_max[k] = ob.kappa_max[o];
      b.kappa_ultimate[k] = ob.kappa_ultimate[o];
      b.dissipated[k] = ob.dissipated[o];
      b.failure_mode[k] = ob.failure_mode[o];
    }
  }
  std::fill(p.coordination.begin(), p.coordination.end(), 0);
  for (std::size_t k = 0; k < b.size(); ++k)
    if (dem::is_bonded(b.state[k]))
      ++p.coordination[b.a[k]], ++p.coordination[b.b[k]];
}

// The crack log in the new numbering (ids are the particles' user ids: ParticleStore::id).
void CoupledProblem::renumber_crack_log(GrowthHandover& h)
{
  const auto& op = h.old.particles;
  std::vector<int> old_index_of_id(op.size(), -1);
  for (std::size_t i = 0; i < op.size(); ++i)
    old_index_of_id[std::size_t(op.id[i])] = int(i);
  for (auto& c : h.cracks)
  {
    if (h.new_bond[c.bond] < 0)
      throw std::logic_error("adaptive region: a broken bond is missing after the growth");
    c.bond = std::size_t(h.new_bond[c.bond]);
    c.a = h.id_of_old[std::size_t(old_index_of_id[std::size_t(c.a)])];
    c.b = h.id_of_old[std::size_t(old_index_of_id[std::size_t(c.b)])];
  }
}

// A load or support must act on the same particles as before.
void CoupledProblem::check_loaded_groups_kept(const dem::Model& old) const
{
  for (std::size_t gi = 0; gi < model_.groups.size(); ++gi)
  {
    bool acted = false;
    for (const auto& c : model_.constraints)
      acted = acted || c.group == int(gi);
    for (const auto& l : model_.loads)
      acted = acted || l.group == int(gi);
    if (acted && model_.groups[gi].members.size() != old.groups[gi].members.size())
      throw std::runtime_error(
          "Group " + model_.groups[gi].name + ": it holds a load or support and would gain " +
          std::to_string(model_.groups[gi].members.size() - old.groups[gi].members.size()) +
          " particles as the adaptive region grows; select it inside the particle box");
  }
}

// 3. the new continuum takes the earlier one's displacements and velocities (its grid holds the
// earlier's lines: a node that was there keeps its values, a new one takes the earlier field's
// trilinear interpolation, which is that field) and its run's state.
void CoupledProblem::continue_continuum(GrowthHandover& h)
{
  const NodalField U(h.node_u, h.old_lines, h.key_quantum), V(h.node_v, h.old_lines, h.key_quantum);
  fe_->set_initial_state(U, V);
  fe_->continue_from(*h.old_fe, V);
  h.old_fe.reset();
  h.old_handshake.reset();
}
} // namespace dembridge::coupling
