#include "app/input/dem_parameters.h"
#include "app/input/contact_parameters.h"
#include "app/input/damage_parameters.h"
#include "app/input/group_load_parameters.h"
#include "app/input/microstructure_parameters.h"
#include "app/input/parameter_values.h"
#include "app/input/specimen_volume.h"
#include <cmath>
#include <filesystem>
#include <sstream>

namespace dembridge::app
{
using dealii::ParameterHandler;
using dealii::Patterns::Anything;
using dealii::Patterns::Bool;
using dealii::Patterns::Double;
using dealii::Patterns::Integer;
using dealii::Patterns::List;
using dealii::Patterns::Selection;
namespace dem = dembridge::dem;

std::vector<std::string> split_names(const std::string& text)
{
  std::vector<std::string> out;
  for (auto& s : dealii::Utilities::split_string_list(text, ','))
    if (!s.empty())
      out.push_back(s);
  return out;
}

namespace
{
/// Particles: where the spheres come from (a row, a file, a lattice, a random packing), their
/// sizes, density and the notch removed before bonding.
void declare_particles_section(ParameterHandler& prm)
{
  prm.enter_subsection("Particles");
  prm.declare_entry("source", "row", Selection("row|file|cubic|hcp|fcc|random"),
                    "Where the spheres come from: a row (beams), a CSV file 'x, y, z, r' (m), a "
                    "simple cubic / HCP / FCC lattice or a random close packing filling 'box "
                    "size'.");
  prm.declare_entry("count", "2", Integer(1), "Number of particles of a row.");
  prm.declare_entry("radius", "0.01", Double(), "Particle radius (m), row and lattices.");
  prm.declare_entry("radii", "", List(Double(), 0),
                    "Per-particle radii of a row (m); overrides radius.");
  prm.declare_entry("spacing", "0", Double(0),
                    "Centre distance of a row (m); 0: neighbours touch.");
  prm.declare_entry("origin", "0, 0, 0", vector3,
                    "First particle centre of a row / lattice corner (m).");
  prm.declare_entry("direction", "1, 0, 0", vector3, "Axis of a row.");
  prm.declare_entry("box size", "0.25, 0.1, 0.1", vector3, "Box filled by a lattice (m).");
  prm.declare_entry("file", "", Anything(),
                    "Particle CSV file (source = file), relative to the case file.");
  prm.declare_entry("density", "2500", Double(), "Particle density (kg/m^3).");
  prm.declare_entry("scale density by porosity", "false", Bool(),
                    "Thesis eq. 63: particle density = density / (1 - porosity), so the specimen "
                    "has the mass of the continuum it stands for (porosity of the packing box).");
  prm.declare_entry("distribution", "mono", Selection("mono|uniform|normal"),
                    "Radius distribution of a random packing (mean = radius).");
  prm.declare_entry("radius spread", "0", Double(0),
                    "Random packing: uniform half-width / mean, or normal std dev / mean.");
  prm.declare_entry("seed", "1", Integer(0), "Random packing seed (same seed, same packing).");
  prm.declare_entry("target porosity", "0.37", Double(0, 1),
                    "Random packing: stop growing at this porosity (or when jammed).");
  prm.declare_entry("jamming estimate", "predicted", Selection("measured|predicted"),
                    "Random packing: how the jamming density of the box is found before the pass "
                    "that packs to it. predicted: from the box's wall area (one pass; a measured "
                    "pass follows when the prediction misses by more than 0.2 % in radius); "
                    "measured: a first pass capped at full size (about three passes in all, "
                    "three times the time, the same porosity and coordination; the speed "
                    "benchmarks use it, so that their recorded packings stay the same).");
  prm.declare_entry("save file", "", Anything(),
                    "Write the generated particles to this CSV file (x, y, z, r), for reuse.");
  prm.declare_entry("remove box min", "0, 0, 0", vector3,
                    "A notch: particles whose centres lie in the box [remove box min, remove box "
                    "max] (m) are removed before bonding; both 0: none.");
  prm.declare_entry("remove box max", "0, 0, 0", vector3, "Upper corner of the remove box (m).");
  prm.declare_entry("specimen volume", "", Anything(),
                    "A specimen of any shape (a cylindrical core): a gmsh volume mesh (.msh, "
                    "relative to the case file, or by name from the build's meshes folder). The "
                    "packing (cubic, hcp, fcc, random) fills the volume's bounding box instead of "
                    "'origin' and 'box size'; the spheres wholly inside the volume (centre inside, "
                    "at least 'radius' from its surface) are kept. Empty: the box.");
  prm.leave_subsection();
}

/// Bonds: the bond model, its elastic constants and which particles are bonded.
void declare_bonds_section(ParameterHandler& prm)
{
  prm.enter_subsection("Bonds");
  prm.declare_entry("model", "timoshenko", Selection(dem::bond_model_selection()),
                    "Bond model (Chen et al. 2022): parallel_bond (PBM), euler_bernoulli (EBBM), "
                    "timoshenko (TBBM).");
  prm.declare_entry("youngs modulus", "4e9", Double(), "Bond Young's modulus E_b (Pa).");
  prm.declare_entry("poisson ratio", "0.3", Double(), "Bond Poisson's ratio nu_b, in (-1, 0.5).");
  prm.declare_entry("radius multiplier", "1", Double(),
                    "Bond radius = multiplier x smaller particle radius.");
  prm.declare_entry("contact radius multiplier", "1", Double(),
                    "Bond particles whose contact radii (multiplier x radius) touch or overlap.");
  prm.declare_entry("stiffness ratio", "0", Double(0),
                    "PBM only: k_n/k_s (kappa); 0 gives 2(1 + nu_b) (paper eq. 8). Thesis: 4.2.");
  prm.declare_entry("normal stiffness per area", "0", Double(0),
                    "PBM only: k̄_n (Pa/m), the thesis' E_b/(2 r_p); 0 gives E_b / L_b.");
  prm.declare_entry("pairs", "", Anything(),
                    "Explicit bonds 'i-j, k-l' (particle indices); empty: bond by contact radius.");
  prm.leave_subsection();
}

/// Damping: bond dashpots, local and mass-proportional damping.
void declare_damping_section(ParameterHandler& prm)
{
  prm.enter_subsection("Damping");
  prm.declare_entry(
      "bond damping ratio", "0", Double(0),
      "Damping ratio xi of the bond dashpots, scaled by coordination (thesis eq. 35-37).");
  prm.declare_entry("particle damping", "0", Double(0, 0.999),
                    "Particle (local) damping gamma in [0, 1) (paper eq. 11-12).");
  prm.declare_entry("mass damping", "0", Double(0),
                    "Mass-proportional damping c (1/s): the force -c m v on every particle's "
                    "translation, as Coupling/mass damping applies in a coupled run (damping "
                    "ratio c / (2 omega) for a mode of angular frequency omega).");
  prm.leave_subsection();
}

/// Simulation: the solver, the time step, when the run stops, threads and load steps.
void declare_simulation_section(ParameterHandler& prm)
{
  prm.enter_subsection("Simulation");
  prm.declare_entry("solver", "explicit", Selection("explicit|static"),
                    "explicit: Verlet dynamics with damping; static: the equilibrium of the "
                    "linearised bond network, solved directly (loads at full value, displacement "
                    "loads at their value; velocity loads are refused).");
  prm.declare_entry("time step", "auto", Anything(),
                    "Time step (s), or 'auto' for 'time step safety' x the critical step.");
  prm.declare_entry("time step safety", "0.8", Double(0, 1),
                    "Fraction of the critical step used by 'auto'.");
  prm.declare_entry("end time", "1", Double(0), "Simulated time (s).");
  prm.declare_entry(
      "quasi-static speed", "0", Double(0),
      "Stop after the load ramps once the largest particle speed is below this (m/s); 0: off.");
  prm.declare_entry(
      "equilibrium ratio", "0", Double(0),
      "Stop after the load ramps once the unbalanced-force ratio (mean net force on free "
      "particles / mean bond force, PFC's convention) is below this; 0: off. Unlike the "
      "quasi-static speed it cannot fire at the turning point of an oscillation.");
  prm.declare_entry("max steps", "100000000", Integer(1), "Step limit.");
  prm.declare_entry("threads", "1", Integer(1, 256),
                    "Threads for the force and update loops and the random packing (which is "
                    "bitwise the same on any count).");
  prm.declare_entry("static linear solver", "auto", Selection("auto|cg|gamg"),
                    "Static solver's iterative solve: cg = Jacobi-preconditioned conjugate "
                    "gradients (Eigen), gamg = CG with PETSc's algebraic multigrid (iterations "
                    "nearly flat in the particle count), auto = gamg from 150,000 unknowns "
                    "where PETSc is built in, else cg. On one rank small and banded systems are "
                    "factorised whatever this says; under mpirun every system is solved on the "
                    "ranks by PETSc (gamg, or CG for cg).");
  prm.declare_entry("load steps", "1", Integer(1, 100000),
                    "Static solver: equilibria at t_k = k end time / N, k = 1..N, one history.csv "
                    "row each (the last is the final state).");
  prm.leave_subsection();
}

/// Groups/names and Loads/names: the lists whose members get their own sections.
void declare_group_and_load_names(ParameterHandler& prm)
{
  prm.enter_subsection("Groups");
  prm.declare_entry("names", "", Anything(),
                    "Comma-separated group names; each needs a 'subsection Group NAME'.");
  prm.leave_subsection();
  prm.enter_subsection("Loads");
  prm.declare_entry("names", "", Anything(),
                    "Comma-separated load names; each needs a 'subsection Load NAME'.");
  prm.leave_subsection();
}

/// Measurements: the figures of summary.json and the groups they are measured on.
void declare_measurements_section(ParameterHandler& prm)
{
  prm.enter_subsection("Measurements");
  prm.declare_entry("deflection group", "", Anything(),
                    "Group whose mean displacement is the deflection.");
  prm.declare_entry("deflection name", "deflection",
                    Selection("deflection|tip_deflection|midspan_deflection"),
                    "Key of the deflection in summary.json.");
  prm.declare_entry("deflection direction", "0, 0, -1", vector3,
                    "Deflection = mean displacement . direction.");
  prm.declare_entry(
      "frequency group", "", Anything(),
      "Group whose free vibration (after every load has ended) gives natural_frequency.");
  prm.declare_entry("modulus groups", "", Anything(),
                    "'fixed, loaded': end groups of a uniaxial test; gives youngs_modulus (thesis "
                    "eq. 64) and the Poisson's ratios from the bounding particles (eq. 65).");
  prm.declare_entry("modulus axis", "x", Selection("x|y|z"),
                    "Loading axis of the uniaxial test; summary.json's crack_orientation gives the "
                    "angles of the crack normals from it.");
  prm.declare_entry("flexural groups", "", Anything(),
                    "'pin, roller, loaded, bottom': three-point bending groups (span along x, load "
                    "along z); gives flexural_modulus by thesis eq. 67 and 69.");
  prm.declare_entry("flexural poisson ratio", "0", Double(-1, 0.5),
                    "nu (mean of nu_xy, nu_xz from the uniaxial tests) used by eq. 67/69.");
  prm.declare_entry("form factor", "1.2", Double(0),
                    "Timoshenko form factor f_s (rectangle: 6/5).");
  prm.declare_entry("stress layers", "0", Integer(0),
                    "Number of equal slabs of the specimen along 'stress layer axis' whose "
                    "average stresses (thesis eq. 54) go into summary.json (stress_layers); 0: "
                    "none.");
  prm.declare_entry("stress layer axis", "z", Selection("x|y|z"), "Normal of the stress slabs.");
  prm.declare_entry("stress histogram bins", "20", Integer(1),
                    "Bins of the particle stress histogram (thesis Fig. 36) in summary.json.");
  prm.leave_subsection();
}

/// Output: history and ParaView intervals, and checkpoints.
void declare_output_section(ParameterHandler& prm)
{
  prm.enter_subsection("Output");
  prm.declare_entry("history interval", "100", Integer(1), "Steps between history.csv rows.");
  prm.declare_entry("snapshot interval", "0", Integer(0),
                    "Steps between ParaView snapshots; 0: first and last step only.");
  prm.declare_entry("write vtu", "true", Bool(), "Write ParaView files (particles, bonds).");
  prm.declare_entry("checkpoint interval", "0", Double(0),
                    "Simulated time between checkpoints (s; explicit runs): OUTPUT/checkpoint.h5, "
                    "resumed by 'dembridge run CASE --resume OUTPUT' (docs/checkpoint.md); "
                    "0: none.");
  prm.declare_entry("checkpoint wall interval", "0", Double(0),
                    "Wall-clock time between checkpoints (s), beside or instead of 'checkpoint "
                    "interval'; 0: none.");
  prm.leave_subsection();
}
} // namespace

void declare_dem_parameters(ParameterHandler& prm)
{
  declare_particles_section(prm);
  declare_bonds_section(prm);
  declare_damping_section(prm);
  declare_simulation_section(prm);
  declare_group_and_load_names(prm);
  declare_measurements_section(prm);
  declare_contact_parameters(prm);
  declare_output_section(prm);
  declare_damage_parameters(prm);
  declare_microstructure_parameters(prm);
}

namespace
{
/// Mode = coupled: its particles are cut by Coupling/particle region file, which would replace
/// a specimen volume's cut. Mode is declared with the whole case (declare_all_parameters).
bool coupled_mode(ParameterHandler& prm)
{
  try
  {
    return prm.get("Mode") == "coupled";
  }
  catch (const std::exception&)
  {
    return false;
  }
}

/// Particles: the source of the spheres; a file source must name a file that exists.
void parse_particles_section(ParameterHandler& prm, dem::CaseConfig& c)
{
  using K = dem::ParticleSource::Kind;
  [[maybe_unused]] const bool coupled = coupled_mode(prm); // unused without the gmsh reader
  prm.enter_subsection("Particles");
  {
    auto& s = c.particles;
    const std::string src = prm.get("source");
    s.kind = src == "row"     ? K::row
             : src == "file"  ? K::file
             : src == "cubic" ? K::cubic
             : src == "hcp"   ? K::hcp
             : src == "fcc"   ? K::fcc
                              : K::random;
    s.distribution = prm.get("distribution");
    s.radius_spread = prm.get_double("radius spread");
    s.seed = unsigned(prm.get_integer("seed"));
    s.target_porosity = prm.get_double("target porosity");
    s.predict_jamming = prm.get("jamming estimate") == "predicted";
    s.save_file = prm.get("save file");
    s.count = prm.get_integer("count");
    s.radius = prm.get_double("radius");
    s.radii = get_doubles(prm, "radii");
    s.spacing = prm.get_double("spacing");
    s.origin = get_vec3(prm, "origin");
    s.direction = get_vec3(prm, "direction");
    s.box_size = get_vec3(prm, "box size");
    s.file = prm.get("file");
    s.density = prm.get_double("density");
    s.scale_density_by_porosity = prm.get_bool("scale density by porosity");
    s.remove_box_min = get_vec3(prm, "remove box min");
    s.remove_box_max = get_vec3(prm, "remove box max");
    if (s.kind == K::file && s.file.empty())
      throw dem::InputError("Particles/file: source = file needs a file name");
    // the path tried, absolute: a relative one is resolved against the working directory,
    // which `dembridge run` sets to the case file's folder
    if (s.kind == K::file)
    {
      const auto tried = std::filesystem::absolute(s.file).lexically_normal();
      std::error_code ec;
      if (!std::filesystem::exists(tried, ec))
        throw dem::InputError("Particles/file: '" + s.file + "' does not exist (looked for " +
                              tried.string() + ")");
    }
    if (const std::string volume = prm.get("specimen volume"); !volume.empty())
#ifdef DEMBRIDGE_HAVE_COUPLING
    {
      if (coupled)
        throw dem::InputError("Particles/specimen volume: '" + volume +
                              "': a coupled run's particles fill Coupling/particle region file "
                              "(Mode = coupled); leave the key empty");
      c.measure.section_area = apply_specimen_volume(s, volume);
    }
#else
      throw dem::InputError("Particles/specimen volume: '" + volume +
                            "': this build has no gmsh reader (built without deal.II's FE "
                            "layers); leave the key empty for the box");
#endif
  }
  prm.leave_subsection();
}

/// Bonds: the bond material and the explicit pairs 'i-j', if any.
void parse_bonds_section(ParameterHandler& prm, dem::CaseConfig& c)
{
  prm.enter_subsection("Bonds");
  {
    auto& m = c.bonds.material;
    m.model = dem::bond_model_from_name(prm.get("model"));
    m.youngs_modulus = prm.get_double("youngs modulus");
    m.poisson_ratio = prm.get_double("poisson ratio");
    m.radius_multiplier = prm.get_double("radius multiplier");
    m.stiffness_ratio = prm.get_double("stiffness ratio");
    m.normal_stiffness_per_area = prm.get_double("normal stiffness per area");
    c.bonds.contact_radius_multiplier = prm.get_double("contact radius multiplier");
    for (const auto& pair : split_names(prm.get("pairs")))
    {
      const auto dash = pair.find('-', 1);
      try
      {
        if (dash == std::string::npos)
          throw std::invalid_argument("no dash");
        c.bonds.explicit_bonds.push_back(
            {std::stoi(pair.substr(0, dash)), std::stoi(pair.substr(dash + 1))});
      }
      catch (const std::exception&)
      {
        throw dem::InputError("Bonds/pairs: cannot read '" + pair + "' (expected 'i-j')");
      }
    }
  }
  prm.leave_subsection();
}

/// Damping.
void parse_damping_section(ParameterHandler& prm, dem::CaseConfig& c)
{
  prm.enter_subsection("Damping");
  c.run.bond_damping_ratio = prm.get_double("bond damping ratio");
  c.run.particle_damping = prm.get_double("particle damping");
  c.run.mass_damping = prm.get_double("mass damping");
  prm.leave_subsection();
}

/// Simulation: the time step ('auto' or a positive number) and when the run stops.
void parse_simulation_section(ParameterHandler& prm, dem::CaseConfig& c)
{
  prm.enter_subsection("Simulation");
  {
    const std::string dt = prm.get("time step");
    if (dt == "auto")
      c.run.time_step = 0;
    else
    {
      try
      {
        std::size_t used = 0;
        c.run.time_step = std::stod(dt, &used);
        if (used != dt.size())
          throw std::invalid_argument(dt);
      }
      catch (const std::exception&)
      {
        throw dem::InputError("Simulation/time step: '" + dt + "' is neither 'auto' nor a number");
      }
      if (!(c.run.time_step > 0))
        throw dem::InputError("Simulation/time step: must be positive or 'auto'");
    }
    c.run.static_solver = prm.get("solver") == "static";
    c.run.safety = prm.get_double("time step safety");
    c.run.end_time = prm.get_double("end time");
    c.run.quasi_static_speed = prm.get_double("quasi-static speed");
    c.run.equilibrium_ratio = prm.get_double("equilibrium ratio");
    c.run.max_steps = prm.get_integer("max steps");
    c.run.threads = prm.get_integer("threads");
  }
  prm.leave_subsection();
}

/// Measurements: the groups measured on must come in the counts their tests need.
void parse_measurements_section(ParameterHandler& prm, dem::CaseConfig& c)
{
  prm.enter_subsection("Measurements");
  c.measure.deflection_group = prm.get("deflection group");
  c.measure.deflection_name = prm.get("deflection name");
  c.measure.deflection_direction = get_vec3(prm, "deflection direction");
  c.measure.frequency_group = prm.get("frequency group");
  {
    const auto ends = split_names(prm.get("modulus groups"));
    if (ends.size() == 2)
      c.measure.modulus_fixed_group = ends[0], c.measure.modulus_loaded_group = ends[1];
    else if (!ends.empty())
      throw dem::InputError(
          "Measurements/modulus groups: expected two group names 'fixed, loaded'");
    c.measure.modulus_axis = prm.get("modulus axis")[0] - 'x';
    c.measure.flexural_groups = split_names(prm.get("flexural groups"));
    if (!c.measure.flexural_groups.empty() && c.measure.flexural_groups.size() != 4)
      throw dem::InputError(
          "Measurements/flexural groups: expected four group names 'pin, roller, loaded, bottom'");
    c.measure.flexural_poisson_ratio = prm.get_double("flexural poisson ratio");
    c.measure.form_factor = prm.get_double("form factor");
    c.measure.stress_layers = int(prm.get_integer("stress layers"));
    c.measure.stress_layer_axis = prm.get("stress layer axis")[0] - 'x';
    c.measure.stress_histogram_bins = int(prm.get_integer("stress histogram bins"));
  }
  if (!(c.measure.deflection_direction.norm() > 0))
    throw dem::InputError("Measurements/deflection direction: must be a non-zero vector");
  prm.leave_subsection();
}
} // namespace

dem::CaseConfig parse_dem_case(ParameterHandler& prm)
{
  dem::CaseConfig c;
  parse_particles_section(prm, c);
  parse_bonds_section(prm, c);
  parse_damping_section(prm, c);
  parse_simulation_section(prm, c);
  c.groups = parse_group_sections(prm);
  c.loads = parse_load_sections(prm);
  parse_contact_parameters(prm, c);
  parse_measurements_section(prm, c);
  c.damage = parse_damage_parameters(prm);
  c.microstructure = parse_microstructure_parameters(prm, c.bonds.material, c.damage);
  return c;
}

OutputSettings parse_output_settings(ParameterHandler& prm)
{
  OutputSettings o;
  prm.enter_subsection("Output");
  o.history_interval = prm.get_integer("history interval");
  o.snapshot_interval = prm.get_integer("snapshot interval");
  o.write_vtu = prm.get_bool("write vtu");
  o.checkpoint_interval = prm.get_double("checkpoint interval");
  o.checkpoint_wall_interval = prm.get_double("checkpoint wall interval");
  prm.leave_subsection();
  prm.enter_subsection("Simulation");
  o.load_steps = int(prm.get_integer("load steps"));
  prm.leave_subsection();
  return o;
}
} // namespace dembridge::app