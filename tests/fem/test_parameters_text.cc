// fem::case_file_text is the inverse of fem::parse_parameters: the case file a derived FE model
// (`dembridge verify`) writes parses back to the Parameters that ran, bit for bit.
//  1. every key declare_fem_parameters declares is written (a key left out would read back as
//     its default, unseen by the round trip below);
//  2. a case that sets every list and a number that needs 17 digits reads back to the same
//     Parameters (field by field, exact), and writing those gives the same text;
//  3. each FE case file given on the command line (the examples) does likewise.
#include "fem/parameters.h"
#include "fem/parameters_text.h"
#include <cstdio>
#include <deal.II/base/parameter_handler.h>
#include <regex>
#include <sstream>
#include <string>

using namespace dembridge::fem;

namespace
{
int failures = 0;
void check(bool ok, const std::string& what)
{
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  failures += ok ? 0 : 1;
}

void declare(dealii::ParameterHandler& prm)
{
  prm.declare_entry("Mode", "fem", dealii::Patterns::Anything());
  declare_fem_parameters(prm);
}

Parameters parse_text(const std::string& text)
{
  dealii::ParameterHandler prm;
  declare(prm);
  prm.parse_input_from_string(text);
  return parse_parameters(prm);
}

Parameters parse_file(const std::string& file)
{
  dealii::ParameterHandler prm;
  declare(prm);
  prm.parse_input(file, "", true); // other sections of an example are not the FE model's
  return parse_parameters(prm);
}

int count_set_lines(const std::string& text)
{
  static const std::regex set_line(R"(^\s*set [^=]+=)");
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);)
    n += std::regex_search(line, set_line) ? 1 : 0;
  return n;
}

bool same_points(const std::vector<Point<3>>& a, const std::vector<Point<3>>& b)
{
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i])
      return false;
  return true;
}

/// Every field, compared exactly.
bool same(const Parameters& a, const Parameters& b)
{
  bool ok =
      a.problem == b.problem && a.degree == b.degree &&
      a.incompatible_modes == b.incompatible_modes && a.mesh_source == b.mesh_source &&
      a.mesh_file == b.mesh_file && a.box_lower == b.box_lower && a.box_upper == b.box_upper &&
      a.subdivisions == b.subdivisions && a.refinements == b.refinements &&
      a.remove_lower == b.remove_lower && a.remove_upper == b.remove_upper &&
      a.fit_planes == b.fit_planes && a.material == b.material &&
      a.youngs_modulus == b.youngs_modulus && a.poisson_ratio == b.poisson_ratio &&
      a.density == b.density && a.voigt_stiffness == b.voigt_stiffness &&
      a.body_force == b.body_force && a.solver_tolerance == b.solver_tolerance &&
      a.max_iterations == b.max_iterations && a.amg_strong_threshold == b.amg_strong_threshold &&
      a.n_steps == b.n_steps && a.time_step_factor == b.time_step_factor &&
      a.initial_displacement == b.initial_displacement &&
      same_points(a.probe_points, b.probe_points) && a.deflection_name == b.deflection_name &&
      same_points(a.deflection_points, b.deflection_points) &&
      a.deflection_direction == b.deflection_direction &&
      a.reaction_boundary == b.reaction_boundary && a.reaction_direction == b.reaction_direction &&
      a.loaded_boundary == b.loaded_boundary && a.reaction_boundaries == b.reaction_boundaries &&
      a.stress_layer_axis == b.stress_layer_axis && a.stress_layer_edges == b.stress_layer_edges &&
      a.write_vtu == b.write_vtu && a.base_name == b.base_name && a.output_every == b.output_every;
  ok = ok && a.patches.size() == b.patches.size();
  for (std::size_t i = 0; ok && i < a.patches.size(); ++i)
    ok = a.patches[i].name == b.patches[i].name && a.patches[i].lower == b.patches[i].lower &&
         a.patches[i].upper == b.patches[i].upper;
  ok = ok && a.boundary_constraints.size() == b.boundary_constraints.size();
  for (std::size_t i = 0; ok && i < a.boundary_constraints.size(); ++i)
    ok = a.boundary_constraints[i].boundary == b.boundary_constraints[i].boundary &&
         a.boundary_constraints[i].components == b.boundary_constraints[i].components &&
         a.boundary_constraints[i].value == b.boundary_constraints[i].value;
  ok = ok && a.line_constraints.size() == b.line_constraints.size();
  for (std::size_t i = 0; ok && i < a.line_constraints.size(); ++i)
    ok = a.line_constraints[i].a == b.line_constraints[i].a &&
         a.line_constraints[i].b == b.line_constraints[i].b &&
         a.line_constraints[i].components == b.line_constraints[i].components;
  ok = ok && a.point_constraints.size() == b.point_constraints.size();
  for (std::size_t i = 0; ok && i < a.point_constraints.size(); ++i)
    ok = a.point_constraints[i].p == b.point_constraints[i].p &&
         a.point_constraints[i].components == b.point_constraints[i].components;
  for (const auto* loads : {&a.boundary_forces, &a.tractions})
  {
    const auto& other = loads == &a.boundary_forces ? b.boundary_forces : b.tractions;
    ok = ok && loads->size() == other.size();
    for (std::size_t i = 0; ok && i < loads->size(); ++i)
      ok = (*loads)[i].boundary == other[i].boundary && (*loads)[i].vector == other[i].vector;
  }
  ok = ok && a.line_forces.size() == b.line_forces.size();
  for (std::size_t i = 0; ok && i < a.line_forces.size(); ++i)
    ok = a.line_forces[i].a == b.line_forces[i].a && a.line_forces[i].b == b.line_forces[i].b &&
         a.line_forces[i].force == b.line_forces[i].force;
  ok = ok && a.point_forces.size() == b.point_forces.size();
  for (std::size_t i = 0; ok && i < a.point_forces.size(); ++i)
    ok = a.point_forces[i].p == b.point_forces[i].p &&
         a.point_forces[i].force == b.point_forces[i].force;
  ok = ok && a.point_groups.size() == b.point_groups.size();
  for (std::size_t i = 0; ok && i < a.point_groups.size(); ++i)
    ok = a.point_groups[i].name == b.point_groups[i].name &&
         same_points(a.point_groups[i].points, b.point_groups[i].points);
  return ok;
}

void check_round_trip(const Parameters& p, const std::string& what)
{
  const std::string text = case_file_text(p, {"round trip"});
  const Parameters q = parse_text(text);
  check(same(p, q), what + ": the written case reads back to the same Parameters");
  check(case_file_text(q, {"round trip"}) == text, what + ": and writes the same text");
}

// Every list set, a number that needs all 17 digits (0.1 + 0.2), negative and tiny values.
const char* const rich_case = R"(set Mode = fem
subsection FEM
  set problem = dynamics
  set degree = 1
  set incompatible modes = true
  subsection Mesh
    set box lower = -0.5, 0, 0
    set box upper = 1, 0.30000000000000004, 2e-3
    set box subdivisions = 12, 3, 2
    set refinements = 1
    set remove box = 0.2, -1, -1 to 0.3, 0.1, 1
    set fit planes = true
    set patches = pin: 0,0,0 to 0.1,0.3,0; load: 0.4,0,0.002 to 0.6,0.3,0.002
  end
  subsection Material
    set model = anisotropic
    set density = 917
    set voigt stiffness = 11,12,13,14,15,16, 21,22,23,24,25,26, 31,32,33,34,35,36, 41,42,43,44,45,46, 51,52,53,54,55,56, 61,62,63,64,65,6.0000000000000009e9
  end
  subsection Boundary conditions
    set boundaries = x-min: xyz; x-max: x = -1.2345678901234567e-5; y-min: y
    set lines = 0,0,0 to 0,0.3,0: z
    set points = 1,0,0: xz
  end
  subsection Loads
    set boundary forces = load: 0,0,-1000
    set tractions = x-max: 5e6,0,0
    set line forces = 0,0,0.002 to 1,0,0.002: 0,0,-3
    set point forces = 0.5,0.15,0.002: 0,1e-300,-7
    set body force = 0,0,-9.81
  end
  subsection Solver
    set tolerance = 1e-12
    set max iterations = 333
    set amg strong threshold = 0.25
  end
  subsection Dynamics
    set steps = 77
    set time step factor = 0.5
    set initial displacement = 0; 0; 1e-4*x*(1-x)
    set probe points = 0.5,0.15,0.001; 1,0,0
  end
  subsection Measurements
    set deflection name = tip
    set deflection points = 1,0.15,0.001
    set deflection direction = 0,0,-2
    set reaction boundary = x-min
    set reaction direction = 3,4,0
    set loaded boundary = x-max
    set reaction boundaries = x-min, pin
    set point groups = top: 0.5,0,0.002; 0.5,0.3,0.002 | bottom: 0.5,0.15,0
    set stress layers = z: 0, 0.001, 0.002
  end
  subsection Output
    set vtu = false
    set base name = beam
    set every = 5
  end
end
)";
} // namespace

int main(int argc, char** argv)
{
  dealii::ParameterHandler declared;
  declare(declared);
  std::ostringstream defaults;
  declared.print_parameters(defaults, dealii::ParameterHandler::ShortPRM);
  const int n_keys = count_set_lines(defaults.str());
  const int n_written = count_set_lines(case_file_text(default_parameters()));
  check(n_written == n_keys, "every declared key is written (" + std::to_string(n_written) +
                                 " of " + std::to_string(n_keys) + ", Mode included)");

  check_round_trip(default_parameters(), "the defaults");
  const Parameters rich = parse_text(rich_case);
  check(rich.box_upper[1] == 0.1 + 0.2 &&
            rich.boundary_constraints[1].value == -1.2345678901234567e-5,
        "the rich case holds its 17-digit numbers");
  check_round_trip(rich, "a case with every list set");
  for (int i = 1; i < argc; ++i)
    check_round_trip(parse_file(argv[i]), argv[i]);
  std::printf("%s\n", failures ? "FAILED" : "PASSED");
  return failures ? 1 : 0;
}
