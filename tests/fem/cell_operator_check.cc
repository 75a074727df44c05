// cell_operator_check — the explicit step's cell-by-cell stiffness operator and its stable-step
// bound (fem/element_operator.h) against the assembled matrix and exact eigenvalues.
//   cell_operator_check product   K u cell by cell = the assembled K u to 1e-12 (relative to
//                                 max |K u|) on a graded, weighted mesh (serial or mpirun -np 2)
//   cell_operator_check bound     omega_max^2 of M^-1 K, exact (dense eigenvalues), lies below
//                                 the element bound, which lies below Gershgorin's
//   cell_operator_check incompatible
//                                 Q1 cells with incompatible modes (fem/incompatible_modes.h):
//                                 pure bending of long cells stores the exact strain energy
//                                 (1e-10) where plain Q1 locks; a uniform strain leaves the
//                                 interior nodes free of force (patch test, 1e-10)
#include "fem/explicit_dynamics.h"

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>

namespace
{
using namespace dembridge;
using namespace dealii;
MPI_Comm comm = MPI_COMM_WORLD;
int failures = 0;

bool rank0()
{
  return Utilities::MPI::this_mpi_process(comm) == 0;
}

void expect(const bool ok, const char* what, const double value, const double bound)
{
  if (rank0())
    std::printf("%s %-60s %.6e (bound %.6e)\n", ok ? "PASS" : "FAIL", what, value, bound);
  failures += !ok;
}

/// A cubic-tensor bar 1 x 0.2 x 0.1 m with cells graded along x and stiffness and mass
/// weights that vary along x as the handshake band's do (so that most cells have their own K_e).
fem::Parameters bar(const std::string& subdivisions, const bool incompatible = false,
                    const bool supported = true)
{
  ParameterHandler prm;
  fem::declare_fem_parameters(prm);
  prm.enter_subsection("FEM");
  prm.set("problem", "dynamics");
  prm.set("incompatible modes", incompatible ? "true" : "false");
  prm.enter_subsection("Mesh");
  prm.set("box upper", "1, 0.2, 0.1");
  prm.set("box subdivisions", subdivisions);
  prm.leave_subsection();
  prm.enter_subsection("Material");
  prm.set("model", "anisotropic");
  // a cubic lattice's tensor: C11 = 3.14 GPa, C12 = 0, C44 = 0.37 GPa
  prm.set("voigt stiffness", "3.14e9,0,0,0,0,0, 0,3.14e9,0,0,0,0, 0,0,3.14e9,0,0,0, "
                             "0,0,0,0.37e9,0,0, 0,0,0,0,0.37e9,0, 0,0,0,0,0,0.37e9");
  prm.set("density", "925");
  prm.leave_subsection();
  prm.enter_subsection("Boundary conditions");
  prm.set("boundaries", supported ? "x-min: xyz" : "");
  prm.leave_subsection();
  prm.leave_subsection();
  return fem::parse_parameters(prm);
}

class Wavy : public Function<3>
{
public:
  Wavy() : Function<3>(3) {}
  double value(const Point<3>& x, const unsigned int c) const override
  {
    return 1e-5 * std::sin(7.1 * x[0] + 3.3 * c) * std::cos(11.0 * x[1] - 2.0 * x[2] + c);
  }
};

void setup(fem::ExplicitDynamics& fe)
{
  // weights as in a band 0.3 m long from x = 0.6 m: 1 - alpha and a floored mass weight
  fe.set_weights([](const Point<3>& x)
                 { return x[0] < 0.6 ? 1.0 : std::max(0.0, 0.9 - x[0]) / 0.3; },
                 [](const Point<3>& x)
                 { return x[0] < 0.6 ? 1.0 : 0.1 + 0.9 * (0.9 - std::min(0.9, x[0])) / 0.3; });
  fe.setup();
}

void product()
{
  fem::ExplicitDynamics fe(bar("25,5,3"), comm);
  setup(fe);
  fe.set_initial_state(Wavy(), Functions::ZeroFunction<3>(3));
  const auto& op = fe.element_operator();
  if (rank0())
    std::printf("cells %zu (this rank), element matrices %zu, DoFs %u\n", op.n_cells(),
                op.n_groups(), unsigned(fe.get_dof_handler().n_dofs()));
  expect(op.active(), "the Q1 mesh uses the cell-by-cell operator", double(op.n_groups()), 0);
  fem::LA::MPI::Vector cells(fe.owned_dofs(), comm), assembled(fe.owned_dofs(), comm),
      u(fe.owned_dofs(), comm);
  u = fe.displacement();
  op.vmult(cells, fe.displacement());
  fe.stiffness_matrix().vmult(assembled, u);
  const double scale = assembled.linfty_norm();
  cells -= assembled;
  const double error = cells.linfty_norm() / scale;
  expect(scale > 0 && error < 1e-12, "max |K u (cells) - K u (assembled)| / max |K u|", error,
         1e-12);
}

/// Dense M^-1/2 K M^-1/2 on the moving DoFs (serial, small meshes).
double exact_omega2(const fem::ExplicitDynamics& fe)
{
  const auto n = fe.get_dof_handler().n_dofs();
  std::vector<unsigned int> moving;
  for (unsigned int i = 0; i < n; ++i)
    if (fe.inverse_lumped_mass()(i) > 0)
      moving.push_back(i);
  Eigen::MatrixXd a(moving.size(), moving.size());
  for (std::size_t r = 0; r < moving.size(); ++r)
    for (std::size_t c = 0; c < moving.size(); ++c)
      a(r, c) = fe.stiffness_matrix().el(moving[r], moving[c]) /
                std::sqrt(fe.lumped_mass()(moving[r]) * fe.lumped_mass()(moving[c]));
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

void bound()
{
  for (const char* subdivisions : {"8,2,2", "12,3,2", "6,1,1"})
  {
    fem::ExplicitDynamics fe(bar(subdivisions), comm);
    setup(fe);
    // Gershgorin alone: max_i sum_j |K_ij| / M_ii over the moving DoFs
    double gershgorin = 0;
    for (unsigned int i = 0; i < fe.get_dof_handler().n_dofs(); ++i)
      if (fe.inverse_lumped_mass()(i) > 0)
      {
        double sum = 0;
        for (auto e = fe.stiffness_matrix().begin(i); e != fe.stiffness_matrix().end(i); ++e)
          sum += std::abs(e->value());
        gershgorin = std::max(gershgorin, sum / fe.lumped_mass()(i));
      }
    const double exact = exact_omega2(fe), used = fe.frequency_bound();
    if (rank0())
      std::printf("%s cells: omega_max^2 exact %.6e, element bound / exact %.4f, Gershgorin / "
                  "exact %.4f\n",
                  subdivisions, exact, used / exact, gershgorin / exact);
    expect(exact <= used * (1 + 1e-12), "exact omega_max^2 <= the bound used", exact, used);
    expect(used <= gershgorin * (1 + 1e-12), "the bound used <= Gershgorin's", used, gershgorin);
    // the stable step follows from it
    const double dt = fe.stable_time_step();
    expect(std::abs(dt - 2 / std::sqrt(used)) <= 1e-12 * dt, "stable step = 2 / sqrt(bound)", dt,
           2 / std::sqrt(used));
  }
}
/// Pure bending about y of the cubic bar (C12 = 0, so no anticlastic curvature):
///   u_x = -kappa x (z - z0),  u_y = 0,  u_z = kappa x^2 / 2,  eps_xx = -kappa (z - z0) only,
/// strain energy U = 1/2 C11 kappa^2 I L with I = b h^3 / 12 about the mid-plane z0.
class Bending : public Function<3>
{
public:
  Bending() : Function<3>(3) {}
  static constexpr double kappa = 1e-3, z0 = 0.05;
  double value(const Point<3>& x, const unsigned int c) const override
  {
    return c == 0 ? -kappa * x[0] * (x[2] - z0) : c == 2 ? 0.5 * kappa * x[0] * x[0] : 0.0;
  }
};

/// A uniform strain with every component (linear field, patch test).
class UniformStrain : public Function<3>
{
public:
  UniformStrain() : Function<3>(3) {}
  double value(const Point<3>& x, const unsigned int c) const override
  {
    static const double e[3][3] = {{1e-4, 3e-5, -2e-5}, {3e-5, -5e-5, 4e-5}, {-2e-5, 4e-5, 2e-4}};
    return e[c][0] * x[0] + e[c][1] * x[1] + e[c][2] * x[2];
  }
};

double strain_energy(const fem::ExplicitDynamics& fe, fem::LA::MPI::Vector& Ku)
{
  fem::LA::MPI::Vector u(fe.owned_dofs(), comm);
  u = fe.displacement();
  fe.stiffness_matrix().vmult(Ku, u);
  return 0.5 * (u * Ku);
}

void incompatible()
{
  const double C11 = 3.14e9, b = 0.2, h = 0.1, L = 1.0;
  const double exact = 0.5 * C11 * Bending::kappa * Bending::kappa * (b * h * h * h / 12) * L;
  // cells 0.1 x 0.1 x 0.05 m (aspect 2 along the beam) and 0.25 x 0.1 x 0.05 m (aspect 5)
  for (const char* subdivisions : {"10,2,2", "4,2,2"})
    for (const bool enriched : {true, false})
    {
      fem::ExplicitDynamics fe(bar(subdivisions, enriched), comm);
      fe.setup();
      fe.set_initial_state(Bending(), Functions::ZeroFunction<3>(3));
      fem::LA::MPI::Vector Ku(fe.owned_dofs(), comm);
      const double U = strain_energy(fe, Ku);
      if (rank0())
        std::printf("%s cells, %s: bending energy / exact = %.10f\n", subdivisions,
                    enriched ? "Q1 + incompatible modes" : "Q1", U / exact);
      if (enriched)
        expect(std::abs(U / exact - 1) < 1e-10,
               "incompatible modes: |U / U_exact - 1| in pure bending", std::abs(U / exact - 1),
               1e-10);
      else // the trilinear cells lock: a parasitic shear strain stiffens them
        expect(U / exact - 1 > 1e-2, "plain Q1: U / U_exact - 1 (locking) above 1 %", U / exact - 1,
               1e-2);
    }
  // patch test: a uniform strain is in equilibrium at every node not on the boundary (no
  // support, which would hold the x = 0 face at u = 0)
  fem::ExplicitDynamics fe(bar("6,3,3", true, false), comm);
  fe.setup();
  fe.set_initial_state(UniformStrain(), Functions::ZeroFunction<3>(3));
  fem::LA::MPI::Vector Ku(fe.owned_dofs(), comm);
  strain_energy(fe, Ku);
  const double scale = Ku.linfty_norm();
  double interior = 0;
  std::map<types::global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(fe.get_mapping(), fe.get_dof_handler(), support);
  for (const auto& [i, x] : support)
    if (x[0] > 1e-9 && x[0] < 1 - 1e-9 && x[1] > 1e-9 && x[1] < 0.2 - 1e-9 && x[2] > 1e-9 &&
        x[2] < 0.1 - 1e-9)
      interior = std::max(interior, std::abs(Ku(i)));
  expect(scale > 0 && interior < 1e-10 * scale,
         "incompatible modes: uniform strain, max interior |K u| / max |K u|", interior / scale,
         1e-10);
}
} // namespace

int main(int argc, char** argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string check = argc > 1 ? argv[1] : "";
  try
  {
    if (check == "product")
      product();
    else if (check == "bound")
      bound();
    else if (check == "incompatible")
      incompatible();
    else
    {
      std::fprintf(stderr,
                   "cell_operator_check: unknown check '%s' (product, bound, incompatible)\n",
                   check.c_str());
      return 2;
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "cell_operator_check: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
