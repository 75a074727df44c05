// The FEM section as case-file text (see parameters_text.h): the inverse of parse_parameters.
#include "fem/parameters_text.h"
#include <cstdlib>
#include <deal.II/base/parameter_handler.h>
#include <iomanip>
#include <sstream>

namespace dembridge::fem
{
namespace
{
std::string point_text(const Tensor<1, 3>& v)
{
  return number_text(v[0]) + "," + number_text(v[1]) + "," + number_text(v[2]);
}
std::string point_text(const Point<3>& p)
{
  return point_text(static_cast<const Tensor<1, 3>&>(p));
}

std::string components_text(const ComponentSet& c)
{
  std::string s;
  for (int d = 0; d < 3; ++d)
    if (c[d])
      s += char('x' + d);
  return s;
}

std::string segment_text(const Point<3>& a, const Point<3>& b)
{
  return point_text(a) + " to " + point_text(b);
}

template <typename Item, typename Format>
std::string joined(const std::vector<Item>& items, const std::string& separator, Format format)
{
  std::string s;
  bool first = true;
  for (const auto& item : items)
  {
    s += (first ? "" : separator) + format(item);
    first = false;
  }
  return s;
}

std::string points_text(const std::vector<Point<3>>& points)
{
  return joined(points, "; ", [](const Point<3>& p) { return point_text(p); });
}

/// Writes "set KEY = VALUE" lines inside nested subsections, indented as case files are.
class SectionWriter
{
public:
  explicit SectionWriter(std::ostringstream& out) : out_(out) {}
  void enter(const std::string& name)
  {
    out_ << indent() << "subsection " << name << "\n";
    ++depth_;
  }
  void leave()
  {
    --depth_;
    out_ << indent() << "end\n";
  }
  void set(const std::string& key, const std::string& value)
  {
    out_ << indent() << "set " << key << " = " << value << "\n";
  }
  void set(const std::string& key, double value) { set(key, number_text(value)); }

private:
  std::string indent() const { return std::string(2 * depth_, ' '); }
  std::ostringstream& out_;
  int depth_ = 0;
};

void write_mesh(SectionWriter& w, const Parameters& p)
{
  w.enter("Mesh");
  w.set("source", p.mesh_source == MeshSource::box ? "box" : "gmsh");
  w.set("file", p.mesh_file);
  w.set("box lower", point_text(p.box_lower));
  w.set("box upper", point_text(p.box_upper));
  w.set("box subdivisions", std::to_string(p.subdivisions[0]) + "," +
                                std::to_string(p.subdivisions[1]) + "," +
                                std::to_string(p.subdivisions[2]));
  w.set("refinements", std::to_string(p.refinements));
  bool has_remove_box = true;
  for (unsigned int d = 0; d < 3; ++d)
    has_remove_box = has_remove_box && p.remove_upper[d] > p.remove_lower[d];
  w.set("remove box", has_remove_box ? segment_text(p.remove_lower, p.remove_upper) : "");
  w.set("fit planes", p.fit_planes ? "true" : "false");
  w.set("patches", joined(p.patches, "; ",
                          [](const BoundaryPatch& b)
                          { return b.name + ": " + segment_text(b.lower, b.upper); }));
  w.leave();
}

void write_material(SectionWriter& w, const Parameters& p)
{
  w.enter("Material");
  w.set("model", p.material == MaterialModel::isotropic ? "isotropic" : "anisotropic");
  w.set("youngs modulus", p.youngs_modulus);
  w.set("poisson ratio", p.poisson_ratio);
  w.set("density", p.density);
  std::string voigt;
  if (p.material == MaterialModel::anisotropic)
    for (std::size_t i = 0; i < p.voigt_stiffness.size(); ++i)
      voigt += (i ? ", " : "") + number_text(p.voigt_stiffness[i]);
  w.set("voigt stiffness", voigt);
  w.leave();
}

void write_constraints_and_loads(SectionWriter& w, const Parameters& p)
{
  w.enter("Boundary conditions");
  w.set("boundaries", joined(p.boundary_constraints, "; ",
                             [](const BoundaryConstraint& c)
                             {
                               return c.boundary + ": " + components_text(c.components) +
                                      (c.value != 0 ? " = " + number_text(c.value) : "");
                             }));
  w.set("lines", joined(p.line_constraints, "; ",
                        [](const LineConstraint& c)
                        { return segment_text(c.a, c.b) + ": " + components_text(c.components); }));
  w.set("points", joined(p.point_constraints, "; ",
                         [](const PointConstraint& c)
                         { return point_text(c.p) + ": " + components_text(c.components); }));
  w.leave();
  w.enter("Loads");
  auto boundary_load = [](const BoundaryLoad& l)
  { return l.boundary + ": " + point_text(l.vector); };
  w.set("boundary forces", joined(p.boundary_forces, "; ", boundary_load));
  w.set("tractions", joined(p.tractions, "; ", boundary_load));
  w.set("line forces", joined(p.line_forces, "; ",
                              [](const LineLoad& l)
                              { return segment_text(l.a, l.b) + ": " + point_text(l.force); }));
  w.set("point forces",
        joined(p.point_forces, "; ",
               [](const PointLoad& l) { return point_text(l.p) + ": " + point_text(l.force); }));
  w.set("body force", point_text(p.body_force));
  w.leave();
}

void write_measurements(SectionWriter& w, const Parameters& p)
{
  w.enter("Measurements");
  w.set("deflection name", p.deflection_name);
  w.set("deflection points", points_text(p.deflection_points));
  w.set("deflection direction", point_text(p.deflection_direction));
  w.set("reaction boundary", p.reaction_boundary);
  w.set("reaction direction", point_text(p.reaction_direction));
  w.set("loaded boundary", p.loaded_boundary);
  w.set("reaction boundaries",
        joined(p.reaction_boundaries, ", ", [](const std::string& s) { return s; }));
  w.set("point groups",
        joined(p.point_groups, " | ",
               [](const PointGroup& g) { return g.name + ": " + points_text(g.points); }));
  std::string layers;
  if (p.stress_layer_axis >= 0)
    layers = std::string(1, char('x' + p.stress_layer_axis)) + ": " +
             joined(p.stress_layer_edges, ", ", [](double e) { return number_text(e); });
  w.set("stress layers", layers);
  w.leave();
}
} // namespace

std::string number_text(double value)
{
  for (int digits = 15; digits <= 17; ++digits)
  {
    std::ostringstream s;
    s << std::setprecision(digits) << value;
    if (digits == 17 || std::strtod(s.str().c_str(), nullptr) == value)
      return s.str();
  }
  return {};
}

Parameters default_parameters()
{
  dealii::ParameterHandler prm;
  declare_fem_parameters(prm);
  return parse_parameters(prm);
}

std::string case_file_text(const Parameters& p, const std::vector<std::string>& header)
{
  std::ostringstream out;
  for (const auto& line : header)
    out << "# " << line << "\n";
  out << "set Mode = fem\n";
  SectionWriter w(out);
  w.enter("FEM");
  w.set("problem", p.problem == ProblemKind::static_elasticity ? "static" : "dynamics");
  w.set("degree", std::to_string(p.degree));
  w.set("incompatible modes", p.incompatible_modes ? "true" : "false");
  write_mesh(w, p);
  write_material(w, p);
  write_constraints_and_loads(w, p);
  w.enter("Solver");
  w.set("tolerance", p.solver_tolerance);
  w.set("max iterations", std::to_string(p.max_iterations));
  w.set("amg strong threshold", p.amg_strong_threshold);
  w.leave();
  w.enter("Dynamics");
  w.set("steps", std::to_string(p.n_steps));
  w.set("time step factor", p.time_step_factor);
  w.set("initial displacement", p.initial_displacement);
  w.set("probe points", points_text(p.probe_points));
  w.leave();
  write_measurements(w, p);
  w.enter("Output");
  w.set("vtu", p.write_vtu ? "true" : "false");
  w.set("base name", p.base_name);
  w.set("every", std::to_string(p.output_every));
  w.leave();
  w.leave();
  return out.str();
}
} // namespace dembridge::fem
