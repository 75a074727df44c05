// The explicit solver's bond loop (explicit_solver.h): the unified law on SIMD blocks of bonds
// (bonds/bond_block.h), the failure laws on the trial forces (bond_damage.h), the scatter of the
// particle resultants and the dashpot resultants, the crack log, and the bond-force evaluation
// for tests and tools. The rest of the step (loads, integration, supports) is explicit_solver.cc.
#include "dem/bonds/bond_block.h"
#include "dem/bonds/bond_stress.h"
#include "dem/solvers/explicit_solver.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace dembridge::dem
{
template <bool record, bool dashpots, FailureMode failure, bool smooth>
void ExplicitSolver::bond_range(std::size_t begin, std::size_t end, double& strain,
                                double& fracture, double& intact_force, long& intact,
                                std::vector<CrackEvent>& events)
{
  [[maybe_unused]] const bool records = b_.records_forces();
  [[maybe_unused]] const Vec3* v = p_.velocity.data();
  [[maybe_unused]] const Vec3* w = p_.angular_velocity.data();
  constexpr int S = particle_record_size<dashpots>;
  double* sums = particle_sums_.data(); // per particle, the records' layout (bond_block.h)
  [[maybe_unused]] const FailureLaw& law = b_.failure;
  // per bond, its class's constants (a table of four indexed by the class byte), or the law's
  [[maybe_unused]] const FailureConstants* class_law =
      law.by_class && !b_.bond_class.empty() ? law.classes.data() : nullptr;
  [[maybe_unused]] const BondClass* bond_class = b_.bond_class.data();
  [[maybe_unused]] const double dt = settings_.time_step;
  [[maybe_unused]] const int owned = int(owned_);
  const BondLawArrays arrays(p_, b_);
  BondBlock block;
  BondForces f;
  // why: consecutive bonds share their lower particle (renumbering.h sorts them so); its sums
  // stay in registers while they do, and only the other end is added in memory. A particle's
  // contributions still arrive in bond order, so the sums are bitwise those of adding each bond
  // in memory, for any bond order (a run ends when the lower particle changes).
  int run = -1; // the lower particle of the current run, -1: none
  ParticleRecord<S> run_sum;
  auto end_run = [&]
  {
    if (run >= 0)
      run_sum.store(sums + std::size_t(S) * std::size_t(run));
  };
  auto start_run = [&](int lower)
  {
    end_run();
    run = lower;
    run_sum.load(sums + std::size_t(S) * std::size_t(run));
  };
  for (std::size_t k0 = begin; k0 < end; k0 += BondBlock::W)
  {
    const int m = int(std::min<std::size_t>(BondBlock::W, end - k0));
    // the law in SIMD lanes; the contact-force rows only where they are read below
    bond_law_block<dashpots, record || failure != FailureMode::none, smooth>(arrays, k0, m, block);
    for (int j = 0; j < m; ++j) // scatter, failure, records: bond by bond
    {
      const std::size_t k = k0 + std::size_t(j);
      if constexpr (failure == FailureMode::none)
      {
        if (b_.state[k] != BondState::intact)
          continue;
      }
      else if (b_.state[k] == BondState::broken)
        continue;
      const int ia = b_.a[k], ib = b_.b[k];
      if constexpr (record || failure != FailureMode::none)
        block.lane(j, f);
      [[maybe_unused]] double carried = 1.0; // 1 - D
      if constexpr (failure != FailureMode::none)
      {
        // Failure index on the trial elastic forces (bond_stress.h; bond_damage.h eq. 1-2), its
        // two ratios compared as sigma A R against sigma_t A R and tau A R against tau_max A R:
        // no division on the way, the common case of a bond below its strength
        const double Fe[3] = {f.Fc[0] - f.Fd[0], f.Fc[1] - f.Fd[1], f.Fc[2] - f.Fd[2]};
        const double Me[3] = {f.Mc[0] - f.Md[0], f.Mc[1] - f.Md[1], f.Mc[2] - f.Md[2]};
        const double R = b_.radius[k], area = std::numbers::pi * R * R;
        // a smooth joint's stresses against its plane (smooth_joint.h eq. 6), others' axis
        const double* axis = f.e;
        if constexpr (smooth)
          block.lane_axis(j, f), axis = f.n;
        const FailureConstants& constants = class_law ? class_law[std::size_t(bond_class[k])] : law;
        const SectionLoads loads = section_loads(Fe, Me, axis, R, constants.moment_factor);
        const double tension_cap = b_.tensile_strength[k] * area * R;
        const double shear_cap =
            shear_strength(law.shear, constants, b_.shear_strength[k], loads.normal_force, area) *
            area * R;
        // kappa_s > kappa_t (rare: read on failure only)
        auto shear_governs = [&] { return loads.shear * tension_cap > loads.tension * shear_cap; };
        // Power of the trial elastic forces on the particles at v^{n-1/2}, w^{n-1/2} (eq. 5).
        auto elastic_power = [&]
        {
          const double cx = f.e[1] * Fe[2] - f.e[2] * Fe[1], cy = f.e[2] * Fe[0] - f.e[0] * Fe[2],
                       cz = f.e[0] * Fe[1] - f.e[1] * Fe[0];
          double P = 0;
          for (int d = 0; d < 3; ++d)
          {
            const double c = d == 0 ? cx : d == 1 ? cy : cz;
            P += Fe[d] * (v[ib][d] - v[ia][d]) - (Me[d] + f.ra * c) * w[ia][d] +
                 (Me[d] + f.rb * c) * w[ib][d];
          }
          return P;
        };
        auto fail = [&](double energy, CrackMode mode)
        {
          b_.state[k] = BondState::broken;
          b_.damage[k] = 1.0;
          events.push_back({time_, k, ia, ib, Vec3::Zero(), Vec3::UnitX(), mode, energy});
        };
        if constexpr (failure == FailureMode::brittle)
        {
          if (loads.tension >= tension_cap || loads.shear >= shear_cap) // kappa >= 1
          {
            // released: the stored energy in the scheme's time-centred form (eq. 5 with dD = 1)
            const double released = f.strain_energy + 0.5 * dt * elastic_power();
            if (ia < owned) // one rank books a bond held by two (SolverSettings)
              fracture += released;
            b_.dissipated[k] = released;
            fail(released, shear_governs() ? CrackMode::shear : CrackMode::tension);
            continue;
          }
        }
        else if (const double hat = std::max(1.0, b_.kappa_max[k]);
                 loads.tension > hat * tension_cap || loads.shear > hat * shear_cap)
        {
          // kappa above 1 and above the largest so far: damage grows
          const double kappa = std::max(loads.tension / tension_cap, loads.shear / shear_cap);
          b_.kappa_max[k] = kappa;
          if (b_.state[k] == BondState::intact)
          {
            // softening starts: kappa_u from the energy at the peak (eq. 4)
            const double peak_energy = f.strain_energy / (kappa * kappa);
            const bool shear = shear_governs();
            const double gf = shear ? constants.fracture_energy_II : constants.fracture_energy_I;
            b_.kappa_ultimate[k] = std::max(1.0, gf * area / peak_energy);
            b_.failure_mode[k] = shear ? CrackMode::shear : CrackMode::tension;
            b_.state[k] = BondState::softening;
          }
          const double D = softening_damage(kappa, b_.kappa_ultimate[k]); // eq. (3)
          const double released =
              (D - b_.damage[k]) * (f.strain_energy + 0.5 * dt * elastic_power());
          if (ia < owned)
            fracture += released;
          b_.dissipated[k] += released;
          b_.damage[k] = D;
          if (D >= 1.0)
          {
            fail(b_.dissipated[k], b_.failure_mode[k]);
            continue;
          }
        }
        carried = 1.0 - b_.damage[k];
        if (carried < 1.0) // what the record reads (the resultants take carried below)
          for (int d = 0; d < 3; ++d)
            f.Fc[d] *= carried, f.Mc[d] *= carried;
      }
      // the particle resultants (bond_resultants; with dashpots their dashpot parts, kept
      // apart for their exact work in integrate), formed in the block's lanes, times 1 - D:
      // whole records, the lower particle's in registers, the upper's in memory
      const int lower = std::min(ia, ib), upper = std::max(ia, ib);
      if (lower != run)
        start_run(lower);
      constexpr bool scaled = failure != FailureMode::none;
      run_sum.template add<scaled>(block.lower[j], carried);
      ParticleRecord<S> upper_sum;
      double* const upper_at = sums + std::size_t(S) * std::size_t(upper);
      upper_sum.load(upper_at);
      upper_sum.template add<scaled>(block.upper[j], carried);
      upper_sum.store(upper_at);
      if constexpr (record)
      {
        if (ia < owned) // booked by the rank that owns end a (SolverSettings)
        {
          if constexpr (failure == FailureMode::none)
            strain += f.strain_energy;
          else
            strain += carried * f.strain_energy; // secant: (1 - D) U_e
          if (b_.state[k] == BondState::intact)
            intact_force += std::sqrt(f.Fc[0] * f.Fc[0] + f.Fc[1] * f.Fc[1] + f.Fc[2] * f.Fc[2]),
                ++intact;
        }
        if (records)
        {
          b_.force[k] = Vec3(f.Fc[0], f.Fc[1], f.Fc[2]);
          b_.moment[k] = Vec3(f.Mc[0], f.Mc[1], f.Mc[2]);
        }
      }
    }
  }
  end_run();
}

template <bool record, bool dashpots, FailureMode failure, bool smooth>
void ExplicitSolver::compute_bond_forces()
{
  double strain = 0, fracture = 0, intact_force = 0;
  long intact = 0;
  for (int phase = 0; phase < 3; ++phase)
  {
    const auto& ranges = phases_[phase];
    if (ranges.empty())
      continue;
    auto* buffers = crack_buffers_.data() + phase_buffer_[phase];
#pragma omp parallel for num_threads(settings_.threads) schedule(static, 1) reduction(+ : strain, fracture, intact_force, intact)
    for (std::size_t r = 0; r < ranges.size(); ++r)
      bond_range<record, dashpots, failure, smooth>(ranges[r].first, ranges[r].second, strain,
                                                    fracture, intact_force, intact, buffers[r]);
  }
  for (std::size_t r = 0; r < phases_[3].size(); ++r)
    bond_range<record, dashpots, failure, smooth>(phases_[3][r].first, phases_[3][r].second, strain,
                                                  fracture, intact_force, intact,
                                                  crack_buffers_[phase_buffer_[3] + r]);
  // the particles' bond resultants from the sums, which are left zero there for the next step
  // (the dashpot parts stay for integrate, which zeroes them after their last use)
  constexpr int S = particle_record_size<dashpots>;
  double* sums = particle_sums_.data();
  const long n = long(p_.size());
#pragma omp parallel for num_threads(settings_.threads) schedule(static)
  for (long i = 0; i < n; ++i)
  {
    double* r = sums + S * i;
    p_.force[std::size_t(i)] = Vec3(r + record_force);
    p_.torque[std::size_t(i)] = Vec3(r + record_moment);
    std::fill(r + record_force, r + record_dashpot_force, 0.0);
  }
  // ghosts' dashpot parts too: integrate, which zeroes them, covers the owned particles only
  if constexpr (dashpots)
    std::fill(sums + S * owned_, sums + S * p_.size(), 0.0);
  if constexpr (record)
  {
    energy_.strain = strain;
    intact_force_ = intact_force, n_intact_ = intact;
  }
  if constexpr (failure != FailureMode::none)
  {
    energy_.fracture += fracture;
    drain_crack_events();
  }
}

template <bool record> void ExplicitSolver::dispatch_bond_forces()
{
  // why: a specimen without smooth joints runs the loop without a word of their code
  auto run = [&]<FailureMode failure>()
  {
    if (b_.has_smooth_joints())
      dashpots_ ? compute_bond_forces<record, true, failure, true>()
                : compute_bond_forces<record, false, failure, true>();
    else
      dashpots_ ? compute_bond_forces<record, true, failure, false>()
                : compute_bond_forces<record, false, failure, false>();
  };
  switch (b_.failure.mode)
  {
  case FailureMode::none:
    run.template operator()<FailureMode::none>();
    break;
  case FailureMode::brittle:
    run.template operator()<FailureMode::brittle>();
    break;
  case FailureMode::softening:
    run.template operator()<FailureMode::softening>();
    break;
  }
}

// Serial, after the parallel loop: the failures of this step, with where they happened
// (positions x^n), in the order of the particles' user ids (ParticleStore::id), so the log
// depends neither on the thread partition nor on the spatial renumbering.
void ExplicitSolver::drain_crack_events()
{
  const std::size_t first = cracks_.size();
  for (auto& buffer : crack_buffers_)
  {
    for (auto& c : buffer)
    {
      const Vec3 &xa = p_.position[c.a], &xb = p_.position[c.b];
      c.midpoint = 0.5 * (xa + xb);
      c.axis = (xb - xa).normalized();
      if (const Vec3* N = b_.joint_normal(c.bond)) // a joint's crack lies in its plane
        c.axis = N->dot(c.axis) < 0 ? Vec3(-*N) : *N;
      --p_.coordination[c.a];
      --p_.coordination[c.b];
      const bool booked_here = std::size_t(c.a) < owned_; // a bond held by two ranks logs once
      c.a = p_.id[std::size_t(c.a)], c.b = p_.id[std::size_t(c.b)]; // the log shows user ids
      if (!booked_here)
        continue;
      ++broken_by_mode_[int(c.mode)];
      cracks_.push_back(c);
    }
    buffer.clear();
  }
  std::sort(cracks_.begin() + long(first), cracks_.end(),
            [](const CrackEvent& x, const CrackEvent& y)
            { return std::pair(x.a, x.b) < std::pair(y.a, y.b); });
}

std::vector<Vec3> ExplicitSolver::dashpot_forces() const
{
  std::vector<Vec3> out(p_.size(), Vec3::Zero());
  if (dashpots_)
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = Vec3(&particle_sums_[particle_record_size<true> * i + record_dashpot_force]);
  return out;
}

std::vector<Vec3> ExplicitSolver::dashpot_torques() const
{
  std::vector<Vec3> out(p_.size(), Vec3::Zero());
  if (dashpots_)
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = Vec3(&particle_sums_[particle_record_size<true> * i + record_dashpot_moment]);
  return out;
}

void ExplicitSolver::evaluate_bond_forces()
{
  std::fill(particle_sums_.begin(), particle_sums_.end(), 0.0);
  if (b_.has_smooth_joints())
    dashpots_ ? compute_bond_forces<true, true, FailureMode::none, true>()
              : compute_bond_forces<true, false, FailureMode::none, true>();
  else
    dashpots_ ? compute_bond_forces<true, true, FailureMode::none, false>()
              : compute_bond_forces<true, false, FailureMode::none, false>();
  sums_hold_evaluation_ = dashpots_; // a step zeroes the dashpot parts first
}

template void ExplicitSolver::dispatch_bond_forces<true>();
template void ExplicitSolver::dispatch_bond_forces<false>();
} // namespace dembridge::dem
