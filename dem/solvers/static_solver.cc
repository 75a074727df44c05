#include "dem/solvers/static_solver.h"
#include "dem/bonds/bond_matrix.h"
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

namespace dembridge::dem
{
namespace
{
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector = Eigen::VectorXd;
using Sparse = Eigen::SparseMatrix<double>; // column-major, int indices

const std::string rigid_body_message =
    "static solver: the supports leave rigid-body motion free (singular stiffness matrix); fix "
    "enough DOFs of the specimen (Groups/fixed) to hold it in place";

/// The network's stiffness as 6x6 particle blocks, lower block triangle: diagonal blocks per
/// particle, off-diagonal blocks (rows i, columns j, i > j) in CSR order over the column j.
/// Why blocks: 148k bonds give 21M scalar triplets (340 MB); the blocks hold the same matrix in
/// about a sixth of that and give the free-DOF matrix and K * u without a hash or a search.
struct BlockMatrix
{
  std::vector<Matrix6> diag;
  std::vector<int> start; ///< column j's blocks: [start[j], start[j+1])
  std::vector<int> row;
  std::vector<Matrix6> off;

  /// y = K x over all 6n DOFs (symmetric: each off block acts twice).
  Vector multiply(const Vector& x) const
  {
    Vector y = Vector::Zero(x.size());
    for (std::size_t j = 0; j < diag.size(); ++j)
    {
      y.segment<6>(6 * j).noalias() += diag[j] * x.segment<6>(6 * j);
      for (int k = start[j]; k < start[j + 1]; ++k)
      {
        const int i = row[k];
        y.segment<6>(6 * i).noalias() += off[k] * x.segment<6>(6 * j);
        y.segment<6>(6 * j).noalias() += off[k].transpose() * x.segment<6>(6 * i);
      }
    }
    return y;
  }
};

/// Assembles K_g = T K_l T^T of every intact bond (thesis eq. 32 with T = diag(R, R, R, R)).
BlockMatrix assemble_blocks(const ParticleStore& p, const BondStore& b)
{
  const std::size_t n = p.size();
  BlockMatrix K;
  K.diag.assign(n, Matrix6::Zero());
  // Block pattern: one block per distinct bonded pair (duplicate bonds add into one block).
  std::vector<std::pair<int, int>> pairs; // (column j = lower index, row i)
  std::vector<std::size_t> bond_ids;
  for (std::size_t k = 0; k < b.size(); ++k)
    if (b.state[k] == BondState::intact && b.a[k] != b.b[k])
    {
      pairs.push_back({std::min(b.a[k], b.b[k]), std::max(b.a[k], b.b[k])});
      bond_ids.push_back(k);
    }
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return pairs[x] < pairs[y]; });
  std::vector<int> block_of(pairs.size());
  K.start.assign(n + 1, 0);
  for (std::size_t q = 0; q < order.size(); ++q)
  {
    const auto& pr = pairs[order[q]];
    if (q == 0 || pr != pairs[order[q - 1]])
    {
      K.row.push_back(pr.second);
      ++K.start[pr.first + 1];
    }
    block_of[order[q]] = int(K.row.size()) - 1;
  }
  std::partial_sum(K.start.begin(), K.start.end(), K.start.begin());
  K.off.assign(K.row.size(), Matrix6::Zero());

  // Why a one-entry cache: a lattice has one bond type, so this skips nearly every B^T D B
  // product there; elsewhere it costs one comparison per bond.
  std::array<double, 6> last_key{};
  last_key[5] = -1;
  Matrix12 Kl;
  for (std::size_t q = 0; q < pairs.size(); ++q)
  {
    const std::size_t k = bond_ids[q];
    const std::array<double, 6> key = {
        b.kn[k], b.ks[k], b.ktor[k], b.kben[k], b.contact_fraction[k], b.rest_length[k]};
    const Eigen::Matrix3d R = bond_frame(b.rest_axis[k]); // local -> global
    if (const Vec3* N = b.joint_normal(k)) // a smooth joint (smooth_joint.h): its own matrix
    {
      const Vec3 local_normal = R.transpose() * *N;
      Kl = smooth_joint_matrix(b.stiffness(k), key[5], local_normal);
      last_key[5] = -1;
    }
    else if (key != last_key)
    {
      Kl = unified_bond_matrix(b.stiffness(k), key[5]);
      last_key = key;
    }
    Matrix12 Kg;
    for (int I = 0; I < 4; ++I) // 3x3 blocks: R K_IJ R^T (cheaper than the 12x12 product)
      for (int J = 0; J <= I; ++J)
      {
        Kg.block<3, 3>(3 * I, 3 * J) = R * Kl.block<3, 3>(3 * I, 3 * J) * R.transpose();
        Kg.block<3, 3>(3 * J, 3 * I) = Kg.block<3, 3>(3 * I, 3 * J).transpose();
      }
    const int a = b.a[k], c = b.b[k];
    K.diag[a] += Kg.block<6, 6>(0, 0);
    K.diag[c] += Kg.block<6, 6>(6, 6);
    // lower block: rows = higher particle index
    if (c > a)
      K.off[block_of[q]] += Kg.block<6, 6>(6, 0);
    else
      K.off[block_of[q]] += Kg.block<6, 6>(0, 6);
  }
  return K;
}

/// Union-find over intact bonds: the component (root) of every particle.
std::vector<int> components(std::size_t n, const BondStore& b)
{
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x)
  {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]]; // path halving
    return x;
  };
  for (std::size_t k = 0; k < b.size(); ++k)
    if (b.state[k] == BondState::intact)
    {
      const int ra = find(b.a[k]), rb = find(b.b[k]);
      if (ra != rb)
        parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  for (std::size_t i = 0; i < n; ++i)
    parent[i] = find(int(i));
  return parent;
}

/// Displacement factor of a prescribed velocity at time t: integral of Load::factor over
/// [0, t] (s), i.e. value * this = the displacement the explicit solver has imposed.
double motion_integral(const Load& l, double t)
{
  const double T = l.ramp_time;
  if (T > 0 && t < T)
    return 0.5 * t * t / T;
  return T > 0 ? t - 0.5 * T : t;
}

Quat rotation_of(const Vec3& theta) // exp(theta) as a unit quaternion
{
  const double a = theta.norm();
  if (a < 1e-300)
    return Quat::Identity();
  return Quat(Eigen::AngleAxisd(a, theta / a));
}

Sparse scaled_free_matrix(const BlockMatrix& K, const std::vector<int>& index, const Vector& scale,
                          long n_free)
{
  // Lower triangle, column-major, rows ascending: free DOFs are numbered particle by particle,
  // so within column (j, l) the rows are j's own DOFs k >= l, then each row block i > j in order.
  const std::size_t n = K.diag.size();
  std::vector<int> outer(std::size_t(n_free) + 1, 0);
  long nnz = 0;
  for (std::size_t j = 0; j < n; ++j)
  {
    int free_j = 0, below = 0;
    for (int l = 0; l < 6; ++l)
      free_j += index[6 * j + l] >= 0;
    for (int k = K.start[j]; k < K.start[j + 1]; ++k)
      for (int l = 0; l < 6; ++l)
        below += index[6 * K.row[k] + l] >= 0;
    int rank = 0;
    for (int l = 0; l < 6; ++l)
      if (index[6 * j + l] >= 0)
      {
        outer[index[6 * j + l] + 1] = free_j - rank + below;
        nnz += free_j - rank + below;
        ++rank;
      }
  }
  std::partial_sum(outer.begin(), outer.end(), outer.begin());
  Sparse A(n_free, n_free);
  A.resizeNonZeros(nnz);
  std::copy(outer.begin(), outer.end(), A.outerIndexPtr());
  int* inner = A.innerIndexPtr();
  double* value = A.valuePtr();
  for (std::size_t j = 0; j < n; ++j)
    for (int l = 0; l < 6; ++l)
    {
      const int c = index[6 * j + l];
      if (c < 0)
        continue;
      long pos = outer[c];
      for (int k = l; k < 6; ++k)
        if (const int r = index[6 * j + k]; r >= 0)
          inner[pos] = r, value[pos++] = scale[r] * K.diag[j](k, l) * scale[c];
      for (int q = K.start[j]; q < K.start[j + 1]; ++q)
        for (int k = 0; k < 6; ++k)
          if (const int r = index[6 * K.row[q] + k]; r >= 0)
            inner[pos] = r, value[pos++] = scale[r] * K.off[q](k, l) * scale[c];
    }
  return A;
}
} // namespace

StaticResult solve_static(Model& model, const StaticSettings& settings)
{
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  ParticleStore& p = model.particles;
  const std::size_t n = p.size();
  StaticResult res;
  res.n_dofs = long(6 * n);
  const double t = settings.time;
  const bool final_state = !std::isfinite(t);

  // Fixed DOFs, prescribed displacements g and external loads f (6 per particle).
  std::vector<std::uint8_t> fixed(n, 0);
  Vector g = Vector::Zero(6 * n), f = Vector::Zero(6 * n);
  for (const auto& c : model.constraints)
    for (int i : model.groups.at(c.group).members)
      fixed[i] |= c.dofs;
  for (const auto& l : model.loads)
  {
    // final state: only the loads that are never removed; otherwise as the explicit solver at t
    if (final_state ? std::isfinite(l.end_time) : !l.active(t))
      continue;
    const auto& members = model.groups.at(l.group).members;
    const int offset = l.kind == LoadKind::moment || l.kind == LoadKind::angular_velocity ? 3 : 0;
    if (l.prescribes_motion())
    {
      if (final_state && l.kind != LoadKind::displacement)
        throw InputError("Load " + l.name + "/type: the static solver's final state has no " +
                         "displacement for a prescribed velocity (it grows without end): use " +
                         "type = displacement");
      const Vec3 d = l.kind == LoadKind::displacement
                         ? Vec3(l.value * (final_state ? 1.0 : l.displacement_fraction(t)))
                         : Vec3(l.value * motion_integral(l, t));
      for (int i : members)
        for (int k = 0; k < 3; ++k)
          if (l.components & (1u << k))
          {
            fixed[i] |= std::uint8_t(1u << (k + offset));
            g[6 * i + offset + k] = d[k];
          }
    }
    else
    {
      if (l.kind == LoadKind::pressure && l.ratio != 0)
        throw InputError("Load " + l.name + "/ratio: a pressure that follows another load's " +
                         "stress needs the explicit solver (the static solver takes p_0 only)");
      // group total shared equally, as ExplicitSolver::apply_loads does
      const Vec3 total =
          l.kind == LoadKind::pressure ? Vec3(l.value * (l.pressure * l.area)) : l.value;
      const Vec3 share = total * ((final_state ? 1.0 : l.factor(t)) / double(members.size()));
      for (int i : members)
        f.segment<3>(6 * i + offset) += share;
    }
  }

  for (const auto& d : settings.prescribed)
  {
    if (d.index < 0 || std::size_t(d.index) >= n)
      throw InputError("static solver: prescribed displacement of particle " +
                       std::to_string(d.index) + ", which does not exist");
    fixed[d.index] |= d.dofs;
    for (int k = 0; k < 6; ++k)
      if (d.dofs & (1u << k))
        g[6 * d.index + k] = d.value[k];
  }

  // A bond cluster with no support stays at rest when unloaded (the explicit solver leaves it
  // there) and is held in place; loaded, it would accelerate forever: no static solution.
  const std::vector<std::uint8_t> constrained = fixed; // before holding idle clusters
  const std::vector<int> root = components(n, model.bonds);
  std::vector<char> supported(n, 0), loaded(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    supported[root[i]] |= fixed[i] != 0;
    loaded[root[i]] |= f.segment<6>(6 * i).squaredNorm() > 0;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!supported[root[i]])
    {
      if (loaded[root[i]])
        throw InputError(rigid_body_message + " (particle " + std::to_string(i) +
                         " is loaded in a bonded cluster without any support)");
      fixed[i] = 63;
    }
  // A sphere without any intact bond (a rattler of a random packing) carries nothing: as in the
  // explicit solver it stays where its supports and prescribed motion put it.
  long held_rattlers = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (p.coordination[i] == 0 && fixed[i] != 63) // unsupported ones are already held
    {
      if (loaded[root[i]])
        throw InputError(rigid_body_message + " (particle " + std::to_string(i) +
                         " is loaded but has no bond)");
      fixed[i] = 63, ++held_rattlers;
    }
  res.held_unbonded = held_rattlers;

  const BlockMatrix K = assemble_blocks(p, model.bonds);
  std::vector<int> index(6 * n, -1);
  long n_free = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 6; ++k)
      if (!(fixed[i] & (1u << k)))
        index[6 * i + k] = int(n_free++);
  res.n_free_dofs = n_free;

  // rhs = f_f - K_fc g_c; Jacobi scaling S = diag(K_ff)^-1/2
  const Vector Kg = K.multiply(g);
  Vector rhs(n_free), scale(n_free);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 6; ++k)
      if (const int r = index[6 * i + k]; r >= 0)
      {
        const double d = K.diag[i](k, k);
        if (!(d > 0))
          throw InputError(rigid_body_message + " (particle " + std::to_string(i) +
                           " has no stiffness)");
        scale[r] = 1.0 / std::sqrt(d);
        rhs[r] = f[6 * i + k] - Kg[6 * i + k];
      }
  const Sparse A = scaled_free_matrix(K, index, scale, n_free);
  const Vector b = scale.cwiseProduct(rhs);
  const auto t1 = clock::now();
  res.assembly_seconds = std::chrono::duration<double>(t1 - t0).count();

  using Method = StaticSettings::Method;
  Vector y;
  auto solve_direct = [&]
  {
    res.method = "SimplicialLDLT";
    Eigen::SimplicialLDLT<Sparse, Eigen::Lower> ldlt(A);
    // Scaled pivots are O(1) for a supported network; a free rigid-body mode leaves one at
    // round-off level (or negative) instead of exactly zero, which info() alone misses.
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-10))
      throw InputError(rigid_body_message);
    y = ldlt.solve(b);
  };
  // Returns false if CG did not converge (max. 2 n iterations).
  auto solve_cg = [&](bool ic)
  {
    if (!ic && settings.iterative_solver && n_free >= settings.iterative_solver_min_unknowns)
    {
      const StaticLinearSystem system{
          A, b, index, scale, p.reference_position, settings.cg_tolerance};
      StaticLinearSolution s = settings.iterative_solver(system);
      res.method = s.method;
      res.iterations = s.iterations;
      res.setup_seconds = s.setup_seconds;
      y = std::move(s.y);
      return s.converged;
    }
    res.method = ic ? "ConjugateGradient+IncompleteCholesky" : "ConjugateGradient+Jacobi";
    auto run = [&](auto& cg)
    {
      cg.setTolerance(settings.cg_tolerance);
      cg.compute(A);
      if (cg.info() != Eigen::Success)
        throw InputError(rigid_body_message);
      y = cg.solve(b);
      res.iterations = long(cg.iterations());
      return cg.info() == Eigen::Success;
    };
    if (ic)
    {
      // Natural ordering: generated packings are numbered lattice-wise (banded); AMD took
      // longer to compute and needed more iterations (measured, 19k DOFs HCP).
      Eigen::ConjugateGradient<
          Sparse, Eigen::Lower,
          Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>>>
          cg;
      return run(cg);
    }
    // The system is already Jacobi-scaled, so the identity preconditioner is Jacobi CG.
    Eigen::ConjugateGradient<Sparse, Eigen::Lower, Eigen::IdentityPreconditioner> cg;
    return run(cg);
  };

  // Mean particle index distance across bonds: ~1 for chains (a banded matrix, which LDL^T
  // factors in O(n) and CG converges on slowly: bending makes cond ~ n^4), a whole lattice
  // layer for 3-D packings (where LDL^T fills in and Jacobi CG wins by 10x and more).
  double gap = 0;
  long intact = 0;
  for (std::size_t k = 0; k < model.bonds.size(); ++k)
    if (model.bonds.state[k] == BondState::intact)
      gap += std::abs(model.bonds.a[k] - model.bonds.b[k]), ++intact;
  gap /= double(std::max(intact, 1L));
  const bool direct = settings.method == Method::direct ||
                      (settings.method == Method::automatic &&
                       (n_free <= settings.direct_limit || gap <= settings.banded_gap));
  if (n_free == 0)
    res.method = "none (every DOF prescribed)";
  else if (direct)
    solve_direct();
  else if (!solve_cg(settings.method == Method::cg_incomplete_cholesky))
  {
    if (settings.method != Method::automatic)
      throw InputError(rigid_body_message + " (" + res.method + " did not converge in " +
                       std::to_string(res.iterations) + " iterations)");
    solve_direct(); // automatic: the factorisation decides (solution or singular)
  }

  // u on all DOFs, reactions and residual with the unscaled blocks
  Vector u = g;
  for (std::size_t d = 0; d < 6 * n; ++d)
    if (const int r = index[d]; r >= 0)
      u[d] = scale[r] * y[r];
  const Vector Ku = K.multiply(u);
  double res2 = 0;
  for (std::size_t d = 0; d < 6 * n; ++d)
    if (index[d] >= 0)
      res2 += (Ku[d] - f[d]) * (Ku[d] - f[d]);
  res.residual = std::sqrt(res2) / std::max(rhs.norm(), 1e-300);
  const auto t2 = clock::now();
  res.solve_seconds = std::chrono::duration<double>(t2 - t1).count();

  for (std::size_t i = 0; i < n; ++i)
  {
    p.position[i] = p.reference_position[i] + u.segment<3>(6 * i);
    p.orientation[i] = rotation_of(u.segment<3>(6 * i + 3));
    p.velocity[i].setZero();
    p.angular_velocity[i].setZero();
    p.dof_mask[i] = constrained[i];
    for (int k = 0; k < 6; ++k)
    {
      // constrained: reaction (K u - f), as ExplicitSolver stores it; free: unbalanced f - K u
      const double r = Ku[6 * i + k] - f[6 * i + k];
      (k < 3 ? p.force[i][k] : p.torque[i][k - 3]) = index[6 * i + k] < 0 ? r : -r;
    }
  }
  return res;
}
} // namespace dembridge::dem
