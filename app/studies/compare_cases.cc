// The case files `dembridge compare` derives from a coupled case (compare_cases.h).
#include "app/studies/compare_cases.h"
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "app/input/group_load_parameters.h"
#include "app/job/provenance.h"
#include "app/studies/verify.h"
#include "app/studies/verify_report.h"
#include <sstream>

namespace dembridge::app
{
namespace fs = std::filesystem;
using dem::Vec3;
using verify_detail::num;

namespace
{
std::string vec_text(const Vec3& v)
{
  return num(v.x()) + ", " + num(v.y()) + ", " + num(v.z());
}

std::string dof_text(std::uint8_t mask)
{
  std::string t;
  const char* names[3] = {"ux", "uy", "uz"};
  for (int d = 0; d < 3; ++d)
    if (mask & (1u << d))
      t += (t.empty() ? "" : ", ") + std::string(names[d]);
  return t;
}

std::string component_text(std::uint8_t mask)
{
  std::string t;
  for (int d = 0; d < 3; ++d)
    if (mask & (1u << d))
      t += (t.empty() ? "" : ", ") + std::string(1, "xyz"[d]);
  return t;
}

/// Drops the top-level subsections @p names (with everything nested in them) from a PRM text.
std::string without_sections(const std::string& text, const std::vector<std::string>& names)
{
  std::istringstream in(text);
  std::ostringstream out;
  int depth = 0, skip_depth = -1;
  for (std::string line; std::getline(in, line);)
  {
    const auto first = line.find_first_not_of(' ');
    const std::string t = first == std::string::npos ? "" : line.substr(first);
    if (t.rfind("subsection ", 0) == 0)
    {
      if (depth == 0 && skip_depth < 0)
        for (const auto& n : names)
          if (t.substr(11) == n)
            skip_depth = 0;
      ++depth;
      if (skip_depth >= 0)
        continue;
    }
    else if (t == "end")
    {
      --depth;
      if (skip_depth >= 0)
      {
        if (depth == skip_depth)
          skip_depth = -1;
        continue;
      }
    }
    if (skip_depth < 0)
      out << line << '\n';
  }
  return out.str();
}

} // namespace

/// The full-DEM case file: the coupled case's own parameters (after --set) with the particle
/// box of the layout, the supports as groups (and driven supports as loads), the mass damping
/// and the coupled run's time step; the Coupling and FEM sections left out.
std::string full_dem_text(const CompareOptions& o, const coupling::FullDemLayout& layout,
                          double time_step)
{
  auto prm = read_case(o.case_file, o.overrides);
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  std::vector<std::string> groups, loads;
  for (const auto& s : layout.supports)
    (s.driven ? loads : groups).push_back(s.name);
  std::vector<std::string> all_groups;
  for (const auto& s : layout.supports)
    all_groups.push_back(s.name);
  declare_group_parameters(*prm, all_groups);
  declare_load_parameters(*prm, loads);
  prm->set("Mode", "dem");
  auto join = [](std::string list, const std::vector<std::string>& more)
  {
    for (const auto& m : more)
      list += (list.find_first_not_of(" ") == std::string::npos ? "" : ", ") + m;
    return list;
  };
  prm->enter_subsection("Particles");
  prm->set("origin", vec_text(layout.origin));
  prm->set("box size", vec_text(layout.box_size));
  prm->leave_subsection();
  prm->enter_subsection("Damping");
  prm->set("mass damping", num(layout.mass_damping));
  prm->leave_subsection();
  prm->enter_subsection("Simulation");
  prm->set("time step", num(time_step));
  prm->leave_subsection();
  prm->enter_subsection("Groups");
  prm->set("names", join(prm->get("names"), all_groups));
  prm->leave_subsection();
  if (!loads.empty())
  {
    prm->enter_subsection("Loads");
    prm->set("names", join(prm->get("names"), loads));
    prm->leave_subsection();
  }
  static const char* faces[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
  for (const auto& s : layout.supports)
  {
    prm->enter_subsection("Group " + s.name);
    switch (s.selection.kind)
    {
    case dem::GroupSelection::Kind::box:
      prm->set("select", "box");
      prm->set("box min", vec_text(s.selection.box_min));
      prm->set("box max", vec_text(s.selection.box_max));
      break;
    case dem::GroupSelection::Kind::face:
      prm->set("select", "face");
      prm->set("face", faces[2 * s.selection.face_axis + (s.selection.face_upper ? 1 : 0)]);
      break;
    default:
      prm->set("select", "nearest");
      prm->set("point", vec_text(s.selection.point));
    }
    prm->set("fixed", dof_text(s.fixed));
    prm->leave_subsection();
    if (s.driven)
    {
      prm->enter_subsection("Load " + s.name);
      prm->set("group", s.name);
      prm->set("type", "displacement");
      prm->set("value", vec_text(s.displacement));
      prm->set("components", component_text(s.driven_components));
      prm->leave_subsection();
    }
  }
  std::string header = "# Full-DEM counterpart of " + fs::absolute(o.case_file).string() +
                       ", written by `dembridge compare` (coupling/full_models.h)\n";
  for (const auto& n : layout.notes)
    header += "# note: " + n + "\n";
  return without_sections(parameters_file_text(*prm, case_dir, header), {"Coupling", "FEM"});
}

/// The fixed-region case: the coupled case's own parameters (after --set) with the adaptive
/// region off and the adaptive run's final cells as its particle region (@p region_file, a gmsh
/// volume: coupling/fixed_region.h); the particle box its bounding box.
std::string coupled_fixed_text(const CompareOptions& o, const coupling::RegionCells& cells,
                               const fs::path& region_file)
{
  auto prm = read_case(o.case_file, o.overrides);
  const fs::path case_dir = fs::absolute(o.case_file).parent_path();
  prm->enter_subsection("Particles");
  prm->set("origin", vec_text(cells.lower()));
  prm->set("box size", vec_text(cells.upper() - cells.lower()));
  prm->leave_subsection();
  prm->enter_subsection("Coupling");
  prm->set("particle region file", region_file.string());
  prm->enter_subsection("Adaptive region");
  prm->set("enabled", false);
  prm->leave_subsection();
  prm->leave_subsection();
  const std::string header =
      "# Fixed-region counterpart of " + fs::absolute(o.case_file).string() +
      ", written by `dembridge compare` (coupling/fixed_region.h): the adaptive region off, the\n"
      "# particle region placed at the start as the " +
      std::to_string(cells.n_cells()) + " cells the adaptive run ended with (" +
      region_file.filename().string() + ")\n";
  return parameters_file_text(*prm, case_dir, header);
}

} // namespace dembridge::app
