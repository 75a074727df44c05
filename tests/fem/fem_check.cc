// fem_check — physics checks of the deal.II continuum layer against analytical values.
//   fem_check CHECK     with CHECK one of the names in main() below.
// Every check builds its case in code, runs dembridge::fem::run_case (through the FE mode's run,
// app/runs/fem_run.h, which writes the case's files) and compares with a closed-form value and a
// stated tolerance; results and rates are printed for the record.
#include "app/runs/fem_run.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

namespace
{
using nlohmann::json;
MPI_Comm comm = MPI_COMM_WORLD;

bool rank0()
{
  return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
}

/// A FEM case: "Section/Sub/key" -> value, applied on top of the declared defaults.
using Settings = std::map<std::string, std::string>;

json run(const Settings& settings, const std::string& output, MPI_Comm c = comm)
{
  dealii::ParameterHandler prm;
  dembridge::fem::declare_parameters(prm);
  for (const auto& [path, value] : settings)
  {
    std::vector<std::string> parts;
    std::stringstream in(path);
    for (std::string part; std::getline(in, part, '/');)
      parts.push_back(part);
    for (std::size_t i = 0; i + 1 < parts.size(); ++i)
      prm.enter_subsection(parts[i]);
    prm.set(parts.back(), value);
    for (std::size_t i = 0; i + 1 < parts.size(); ++i)
      prm.leave_subsection();
  }
  std::filesystem::create_directories(output);
  return dembridge::app::run_fem_case(dembridge::fem::parse_parameters(prm), output, c);
}

int failures = 0;
void expect_near(const std::string& what, const double value, const double reference,
                 const double rtol)
{
  const double error = std::abs(value - reference) / std::abs(reference);
  const bool ok = error <= rtol;
  if (rank0())
    std::printf("%s %-44s value %.10e reference %.10e rel.error %.3e (tol %.1e)\n",
                ok ? "PASS" : "FAIL", what.c_str(), value, reference, error, rtol);
  failures += !ok;
}

void expect(const std::string& what, const bool ok)
{
  if (rank0())
    std::printf("%s %s\n", ok ? "PASS" : "FAIL", what.c_str());
  failures += !ok;
}

std::string str(const double v)
{
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// ------------------------------------------------------------------------------------------
// Patch test: uniaxial compression of the 0.25 x 0.1 x 0.1 m box between symmetry planes; the
// displacement field is linear, so Q1 and Q2 reproduce it exactly and R = E A eps (1e-8).
void compression(const unsigned int degree, const bool cubic)
{
  const double L = 0.25, A = 0.1 * 0.1, strain = 1e-4;
  Settings s{{"FEM/degree", std::to_string(degree)},
             {"FEM/Mesh/box upper", "0.25,0.1,0.1"},
             {"FEM/Mesh/box subdivisions", "5,2,2"},
             {"FEM/Mesh/refinements", "1"},
             {"FEM/Boundary conditions/boundaries",
              "x-min: x; y-min: y; z-min: z; x-max: x = " + str(-strain * L)},
             {"FEM/Measurements/reaction boundary", "x-min"},
             {"FEM/Measurements/loaded boundary", "x-max"},
             {"FEM/Solver/tolerance", "1e-13"},
             {"FEM/Output/vtu", "false"}};
  double E = 4e9;
  if (cubic)
  {
    // Cubic symmetry (simple cubic packings): C11, C12, C44; E_x = (C11-C12)(C11+2C12)/(C11+C12).
    const double c11 = 10e9, c12 = 4e9, c44 = 3e9;
    E = (c11 - c12) * (c11 + 2 * c12) / (c11 + c12);
    std::ostringstream v;
    const double C[6][6] = {{c11, c12, c12, 0, 0, 0}, {c12, c11, c12, 0, 0, 0},
                            {c12, c12, c11, 0, 0, 0}, {0, 0, 0, c44, 0, 0},
                            {0, 0, 0, 0, c44, 0},     {0, 0, 0, 0, 0, c44}};
    for (int i = 0; i < 36; ++i)
      v << (i ? "," : "") << C[i / 6][i % 6];
    s["FEM/Material/model"] = "anisotropic";
    s["FEM/Material/voigt stiffness"] = v.str();
  }
  else
  {
    s["FEM/Material/youngs modulus"] = str(E);
    s["FEM/Material/poisson ratio"] = "0.3";
  }
  const json r = run(s, "compression");
  // The fixed face pushes back in +x against the compression: R_x = +E A eps.
  expect_near("reaction force = E A strain", r["reaction_force"], E * A * strain, 1e-8);
  expect_near("youngs_modulus from reaction (eq. 64)", r["youngs_modulus"], E, 1e-8);
}

// ------------------------------------------------------------------------------------------
// Equilibrium of every load type: a box clamped at x-min carries a traction, a total boundary
// force, a line force, a point force and a body force; the reaction at x-min balances each
// (sum of applied forces) to 1e-8.
void load_equilibrium()
{
  const double V = 0.25 * 0.1 * 0.1, A_end = 0.1 * 0.1;
  const std::vector<std::tuple<std::string, std::string, double>> loads{
      {"FEM/Loads/tractions", "x-max: 0,0,-2e5", -2e5 * A_end},
      {"FEM/Loads/boundary forces", "z-max: 0,0,-1000", -1000},
      {"FEM/Loads/line forces", "0.25,0,0.1 to 0.25,0.1,0.1: 0,0,-500", -500},
      {"FEM/Loads/point forces", "0.25,0.05,0.1: 0,0,-300", -300},
      {"FEM/Loads/body force", "0,0,-9074.25", -9074.25 * V}};
  for (const unsigned int degree : {1u, 2u})
    for (const auto& [key, value, total] : loads)
    {
      const Settings s{{"FEM/degree", std::to_string(degree)},
                       {"FEM/Mesh/box upper", "0.25,0.1,0.1"},
                       {"FEM/Mesh/box subdivisions", "5,2,2"},
                       {"FEM/Boundary conditions/boundaries", "x-min: xyz"},
                       {key, value},
                       {"FEM/Measurements/reaction boundary", "x-min"},
                       {"FEM/Measurements/reaction direction", "0,0,1"},
                       {"FEM/Solver/tolerance", "1e-12"},
                       {"FEM/Output/vtu", "false"}};
      const json r = run(s, "loads");
      expect_near("Q" + std::to_string(degree) + " reaction balances " + key, r["reaction_force"],
                  -total, 1e-8);
    }
}

// ------------------------------------------------------------------------------------------
// Timoshenko beams (paper eq. 29, thesis eq. 66) with the shear coefficient of a rectangular
// section, k = 6/5 (the 10/9 of the papers is for circular sections):
//   cantilever, tip load F:             d = F L^3 / (3 E I) + k F L / (G A)
//   simply supported, central load F:   d = F L^3 / (48 E I) + k F L / (4 G A)
struct Beam
{
  double L = 1.0, h = 0.1, w = 0.1, E = 4e9, nu = 0.3, F = 100.0;
  double I() const { return w * h * h * h / 12; }
  double A() const { return w * h; }
  double G() const { return E / (2 * (1 + nu)); }
  double cantilever() const { return F * L * L * L / (3 * E * I()) + 1.2 * F * L / (G() * A()); }
  double simply_supported() const
  {
    return F * L * L * L / (48 * E * I()) + 1.2 * F * L / (4 * G() * A());
  }
};

Settings beam_settings(const Beam& b, const unsigned int degree, const unsigned int refinements)
{
  return {{"FEM/degree", std::to_string(degree)},
          {"FEM/Mesh/box upper", str(b.L) + "," + str(b.w) + "," + str(b.h)},
          {"FEM/Mesh/refinements", std::to_string(refinements)},
          {"FEM/Material/youngs modulus", str(b.E)},
          {"FEM/Material/poisson ratio", str(b.nu)},
          {"FEM/Solver/tolerance", "1e-10"},
          {"FEM/Output/vtu", "false"}};
}

Settings cantilever_settings(const Beam& b, const unsigned int degree, const unsigned int level)
{
  Settings s = beam_settings(b, degree, level);
  s["FEM/Mesh/box subdivisions"] = "10,1,1";
  s["FEM/Boundary conditions/boundaries"] = "x-min: xyz";
  s["FEM/Loads/boundary forces"] = "x-max: 0,0," + str(-b.F);
  s["FEM/Measurements/deflection name"] = "tip_deflection";
  s["FEM/Measurements/deflection points"] = str(b.L) + "," + str(b.w / 2) + "," + str(b.h / 2);
  return s;
}

// Simply supported on the end faces (u_z = 0 over x = 0 and x = L: a shear support that leaves
// the section free to rotate), axial and lateral rigid motion removed on the neutral axis, and
// the load as a line force across the top at midspan. The deflection is read on the neutral
// axis at midspan, away from the line load's local (logarithmic) indentation.
Settings simply_supported_settings(const Beam& b, const unsigned int degree,
                                   const unsigned int level)
{
  Settings s = beam_settings(b, degree, level);
  const std::string h2 = str(b.h / 2), w2 = str(b.w / 2), L2 = str(b.L / 2);
  s["FEM/Mesh/box subdivisions"] = "10,1,1";
  s["FEM/Boundary conditions/boundaries"] = "x-min: z; x-max: z";
  s["FEM/Boundary conditions/lines"] = "0,0," + h2 + " to 0," + str(b.w) + "," + h2 + ": x";
  s["FEM/Boundary conditions/points"] = "0," + w2 + "," + h2 + ": y";
  s["FEM/Loads/line forces"] =
      L2 + ",0," + str(b.h) + " to " + L2 + "," + str(b.w) + "," + str(b.h) + ": 0,0," + str(-b.F);
  s["FEM/Measurements/deflection points"] = L2 + "," + w2 + "," + h2;
  return s;
}

/// Three nested meshes (h, h/2, h/4): observed order p = log2((d1-d0)/(d2-d1)) and the
/// Richardson extrapolation d2 + (d2-d1)/(2^p-1).
void convergence(const std::string& name, const std::string& key, const double reference,
                 const std::function<Settings(unsigned int, unsigned int)>& settings,
                 const unsigned int degree, const unsigned int first_level, const double rtol)
{
  std::vector<double> d;
  for (unsigned int level = first_level; level < first_level + 3; ++level)
  {
    const json r = run(settings(degree, level), name);
    d.push_back(r[key]);
    if (rank0())
      std::printf("%s Q%u level %u: n_dofs %8d  %s %.8e  rel.error %+.4e  CG iterations %d\n",
                  name.c_str(), degree, level, int(r["n_dofs"]), key.c_str(), d.back(),
                  (d.back() - reference) / reference, int(r["solver_iterations"]));
  }
  const double p = std::log2((d[1] - d[0]) / (d[2] - d[1]));
  const double extrapolated = d[2] + (d[2] - d[1]) / (std::pow(2.0, p) - 1);
  if (rank0())
    std::printf("%s Q%u: observed convergence order %.2f, Richardson %.8e\n", name.c_str(), degree,
                p, extrapolated);
  expect(name + " Q" + std::to_string(degree) + ": deflection converges monotonically",
         (d[1] - d[0]) * (d[2] - d[1]) > 0 && std::abs(d[2] - d[1]) < std::abs(d[1] - d[0]));
  expect_near(name + " Q" + std::to_string(degree) + " Richardson vs Timoshenko", extrapolated,
              reference, rtol);
  // Q1 (trilinear, stiff in bending) is still a few per cent off on the finest of the three
  // meshes; its Richardson value is what meets the 1 % criterion. Q2 meets it on every mesh.
  if (degree == 2)
    expect_near(name + " Q2 finest mesh vs Timoshenko", d[2], reference, rtol);
}

// ------------------------------------------------------------------------------------------
// The same beam on all ranks of MPI_COMM_WORLD and on each rank alone (MPI_COMM_SELF): the
// deflections agree to the solver tolerance (CG stops at 1e-12 |b|; we require 1e-8).
void mpi_matches_serial(const Beam& beam)
{
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  expect("running on " + std::to_string(n_ranks) + " ranks (>= 2)", n_ranks >= 2);
  Settings s = simply_supported_settings(beam, 2, 1);
  s["FEM/Solver/tolerance"] = "1e-12";
  s["FEM/Output/vtu"] = "true";
  const json parallel = run(s, "parallel", MPI_COMM_WORLD);
  const json serial = run(s, "serial_rank" + std::to_string(rank), MPI_COMM_SELF);
  expect_near("midspan deflection, " + std::to_string(n_ranks) + " ranks vs 1 rank",
              parallel["midspan_deflection"], serial["midspan_deflection"], 1e-8);
  expect_near("strain energy, " + std::to_string(n_ranks) + " ranks vs 1 rank",
              parallel["strain_energy"], serial["strain_energy"], 1e-8);
}

// ------------------------------------------------------------------------------------------
// Bad input: each case must throw std::runtime_error with a one-line message that names the
// parameter (Section/Key) and the reason.
void bad_input(const std::string& mesh_file)
{
  const Settings box{{"FEM/Output/vtu", "false"},
                     {"FEM/Boundary conditions/boundaries", "x-min: xyz"}};
  const auto with = [&](Settings s, const Settings& more)
  {
    for (const auto& [k, v] : more)
      s[k] = v;
    return s;
  };
  const std::vector<std::pair<Settings, std::string>> cases{
      {with(box, {{"FEM/Mesh/source", "gmsh"}, {"FEM/Mesh/file", "no_such_mesh.msh"}}),
       "FEM/Mesh/file: mesh file 'no_such_mesh.msh' does not exist"},
      {with(box, {{"FEM/Boundary conditions/boundaries", "support: xyz"}}),
       "FEM/Boundary conditions/boundaries: boundary 'support' is not a face or physical group"},
      {with(box, {{"FEM/Material/poisson ratio", "0.5"}}), "FEM/Material/poisson ratio"},
      {with(box, {{"FEM/Material/poisson ratio", "-1"}}), "FEM/Material/poisson ratio"},
      {with(box, {{"FEM/Loads/line forces", "0.1,0.03,0.1 to 0.2,0.03,0.1: 0,0,-1"}}),
       "FEM/Loads/line forces: the segment lies on no mesh edge"},
      {with(box, {{"FEM/Material/model", "anisotropic"},
                  {"FEM/Material/voigt stiffness", "1,2,0,0,0,0, 2,1,0,0,0,0, 0,0,1,0,0,0, "
                                                   "0,0,0,1,0,0, 0,0,0,0,1,0, 0,0,0,0,0,1"}}),
       "FEM/Material/voigt stiffness: the 6x6 matrix is not positive definite"},
      {with(box, {{"FEM/Measurements/deflection points", "9,9,9"}}),
       "FEM/Measurements/deflection points: point lies outside the mesh"},
  };
  std::vector<std::pair<Settings, std::string>> all = cases;
  if (!mesh_file.empty())
  {
    const Settings gmsh{
        {"FEM/Mesh/source", "gmsh"}, {"FEM/Mesh/file", mesh_file}, {"FEM/Output/vtu", "false"}};
    all.push_back({with(gmsh, {{"FEM/Boundary conditions/boundaries", "x-min: xyz"}}),
                   "FEM/Boundary conditions/boundaries: boundary 'x-min' is not a face or "
                   "physical group of the mesh (known: "});
    all.push_back({with(gmsh, {{"FEM/Boundary conditions/boundaries", "pin: xyz; roller: z"},
                               {"FEM/Loads/boundary forces", "pin_edge: 0,0,-1000"}}),
                   "FEM/Loads/boundary forces: boundary 'pin_edge' has no faces"});
  }
  for (const auto& [settings, expected] : all)
  {
    std::string message = "(no exception)";
    try
    {
      run(settings, "bad_input");
    }
    catch (const std::runtime_error& e)
    {
      message = e.what();
    }
    expect("'" + message + "' contains '" + expected + "' on one line",
           message.find(expected) != std::string::npos && message.find('\n') == std::string::npos);
  }
}

// ------------------------------------------------------------------------------------------
// Three-point bending of the gmsh specimen (examples/fem_bending.prm setup, thesis Fig. 28):
// three nested meshes, Richardson estimate, and the gap to the Timoshenko beam formulas
//   eq. (66): d = F Le^3 / (48 E I) + F Le fs / (4 G A)
//   eq. (68): d = F (8 Le^3 - 4 b^2 Le + b^3) / (384 E I) + (F Le - F b) fs / (4 G A)
// with Le = 0.24 m (strip centres), b = 0.01 m, fs = 6/5 (rectangle; the thesis' 10/9 is the
// circular bond value). The beam is deep (Le/h = 2.4): the gap is physics (support and load
// indentation, non-plane sections), not discretisation, and is printed, not asserted.
void specimen_bending(const std::string& mesh_file)
{
  const double E = 4e9, nu = 0.3, F = 1000, Le = 0.24, b = 0.01, h = 0.1, w = 0.1;
  const double I = w * h * h * h / 12, A = w * h, G = E / (2 * (1 + nu));
  std::vector<double> d;
  for (unsigned int level = 0; level < 3; ++level)
  {
    const Settings s{{"FEM/degree", "2"},
                     {"FEM/Mesh/source", "gmsh"},
                     {"FEM/Mesh/file", mesh_file},
                     {"FEM/Mesh/refinements", std::to_string(level)},
                     {"FEM/Material/youngs modulus", str(E)},
                     {"FEM/Material/poisson ratio", str(nu)},
                     {"FEM/Boundary conditions/boundaries", "pin: xyz; roller: yz"},
                     {"FEM/Loads/boundary forces", "load: 0,0," + str(-F)},
                     {"FEM/Measurements/deflection points", "0.125,0.05,0.1; 0.125,0.05,0"},
                     {"FEM/Measurements/reaction boundary", "pin"},
                     {"FEM/Measurements/reaction direction", "0,0,1"},
                     {"FEM/Output/vtu", level == 2 ? "true" : "false"}};
    const json r = run(s, "specimen");
    d.push_back(r["midspan_deflection"]);
    if (rank0())
      std::printf("specimen Q2 level %u: n_dofs %8d  midspan_deflection %.8e  (top %.6e, "
                  "bottom %.6e)  CG iterations %d\n",
                  level, int(r["n_dofs"]), d.back(), double(r["midspan_deflection_points"][0]),
                  double(r["midspan_deflection_points"][1]), int(r["solver_iterations"]));
    const double reactions = double(r["reaction_force"]);
    expect("pin carries about half the load (" + str(reactions) + " N)",
           std::abs(reactions - F / 2) < 0.01 * F);
  }
  const double p = std::log2((d[1] - d[0]) / (d[2] - d[1]));
  const double richardson = d[2] + (d[2] - d[1]) / (std::pow(2.0, p) - 1);
  const auto eq66 = [&](double fs)
  { return F * Le * Le * Le / (48 * E * I) + F * Le * fs / (4 * G * A); };
  const auto eq68 = [&](double fs)
  {
    return F * (8 * Le * Le * Le - 4 * b * b * Le + b * b * b) / (384 * E * I) +
           (F * Le - F * b) * fs / (4 * G * A);
  };
  if (rank0())
  {
    std::printf("specimen Q2: observed order %.2f, Richardson deflection %.6e m\n", p, richardson);
    for (const double fs : {6.0 / 5.0, 10.0 / 9.0})
      std::printf("specimen: fs = %.4f  eq.66 %.6e m (FE %+.2f %%)  eq.68 %.6e m (FE %+.2f %%)\n",
                  fs, eq66(fs), 100 * (richardson / eq66(fs) - 1), eq68(fs),
                  100 * (richardson / eq68(fs) - 1));
  }
  expect("specimen: deflection converges monotonically",
         (d[1] - d[0]) * (d[2] - d[1]) > 0 && std::abs(d[2] - d[1]) < std::abs(d[1] - d[0]));
  // The strip edges, where fixed meets free (supports) or loaded meets free (load), carry
  // r^(1/2) displacement singularities (flat-punch type), so point displacements converge as
  // h^(2 * 1/2) = h^1 for any degree: the observed order must be about 1, which is what makes
  // the Richardson estimate with that order the mesh-converged value.
  expect("specimen: observed order " + str(p) + " in [0.8, 1.5] (r^1/2 singularities)",
         p > 0.8 && p < 1.5);
  if (rank0())
    std::printf("specimen: finest mesh is %.2f %% below the Richardson estimate\n",
                100 * (1 - d[2] / richardson));
}

// ------------------------------------------------------------------------------------------
// Explicit dynamics: a bar (L = 1 m, 0.1 x 0.1 m, nu = 0 so that the 3D motion is exactly 1D)
// fixed axially at x = 0 and free at x = L, released from its first mode
// u_x = a sin(pi x / 2L) with zero velocity. First longitudinal eigenfrequency
//   f_1 = c / (4 L),  c = sqrt(E / rho).
// Energy: the shadow energy of central differences is conserved exactly for a linear system.
// Measured (docs/fem.md): f_1 within 4.9e-5 (Q1) and 2.1e-5 (Q2), held within 2e-4; the shadow
// energy's oscillation 9e-15 and 6e-14, its drift 2e-15 and 8e-15, held below 1e-12.
void bar_dynamics(const unsigned int degree)
{
  const double E = 4e9, rho = 925, L = 1.0;
  const Settings s{{"FEM/problem", "dynamics"},
                   {"FEM/degree", std::to_string(degree)},
                   {"FEM/Mesh/box upper", str(L) + ",0.1,0.1"},
                   {"FEM/Mesh/box subdivisions", degree == 1 ? "20,2,2" : "10,1,1"},
                   {"FEM/Material/youngs modulus", str(E)},
                   {"FEM/Material/poisson ratio", "0"},
                   {"FEM/Material/density", str(rho)},
                   {"FEM/Boundary conditions/boundaries", "x-min: x"},
                   {"FEM/Dynamics/steps", "1000"},
                   {"FEM/Dynamics/time step factor", "0.9"},
                   {"FEM/Dynamics/initial displacement", "1e-5*sin(pi*x/(2*" + str(L) + ")); 0; 0"},
                   {"FEM/Dynamics/probe points", str(L) + ",0.05,0.05"},
                   {"FEM/Output/vtu", "false"}};
  const json r = run(s, "bar");
  const double f1 = std::sqrt(E / rho) / (4 * L);
  const std::string q = "Q" + std::to_string(degree);
  if (rank0())
    std::printf("bar %s: n_dofs %d, dt %.4e s (stable %.4e s), %d zero crossings in %.4e s\n",
                q.c_str(), int(r["n_dofs"]), double(r["time_step"]), double(r["stable_time_step"]),
                int(r["zero_crossings"]), double(r["end_time"]));
  expect_near("bar " + q + ": first longitudinal eigenfrequency", r["natural_frequency"], f1, 2e-4);
  expect("bar " + q + ": shadow energy oscillation " +
             str(r["shadow_energy_relative_oscillation"]) + " < 1e-12 (round-off)",
         double(r["shadow_energy_relative_oscillation"]) < 1e-12);
  expect("bar " + q + ": shadow energy drift over 1000 steps " +
             str(r["shadow_energy_relative_drift"]) + " below 1e-12 (round-off)",
         std::abs(double(r["shadow_energy_relative_drift"])) < 1e-12);
  if (rank0())
    std::printf("bar %s: total energy with v_n = mean of half-step velocities oscillates by "
                "%.3e (O((omega dt)^2), not conserved by the scheme)\n",
                q.c_str(), double(r["total_energy_relative_oscillation"]));
}

} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string check = argc > 1 ? argv[1] : "";
  try
  {
    const Beam beam;
    if (check == "compression")
    {
      compression(1, false);
      compression(2, false);
      compression(1, true);
    }
    else if (check == "loads")
      load_equilibrium();
    else if (check == "cantilever")
    {
      const auto s = [&](unsigned int q, unsigned int l)
      { return cantilever_settings(beam, q, l); };
      convergence("cantilever", "tip_deflection", beam.cantilever(), s, 1, 1, 0.01);
      convergence("cantilever", "tip_deflection", beam.cantilever(), s, 2, 0, 0.01);
    }
    else if (check == "simply_supported")
    {
      const auto s = [&](unsigned int q, unsigned int l)
      { return simply_supported_settings(beam, q, l); };
      convergence("simply_supported", "midspan_deflection", beam.simply_supported(), s, 1, 1, 0.01);
      convergence("simply_supported", "midspan_deflection", beam.simply_supported(), s, 2, 0, 0.01);
    }
    else if (check == "specimen")
      specimen_bending(argv[2]);
    else if (check == "bar")
    {
      bar_dynamics(1);
      bar_dynamics(2);
    }
    else if (check == "mpi")
      mpi_matches_serial(beam);
    else if (check == "bad_input")
      bad_input(argc > 2 ? argv[2] : "");
    else
      throw std::runtime_error("unknown check '" + check + "'");
  }
  catch (const std::exception& e)
  {
    if (rank0())
      std::cerr << "FAIL exception: " << e.what() << std::endl;
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
