// The Coupling section of a case file (see coupling_parameters.h).
#include "coupling/coupling_parameters.h"
#include "dem/core/number_list.h"
#include "dem/model/case_config.h"
#include <sstream>
#include <stdexcept>
#include <string>

namespace dembridge::coupling
{
using dealii::ParameterHandler;
using dealii::Patterns::Bool;
using dealii::Patterns::Double;
using dealii::Patterns::Integer;
using dealii::Patterns::List;
using dealii::Patterns::Selection;

namespace
{
/// One size for every axis, or one per axis x, y, z.
Vec3 sizes_per_axis(const std::string& text, const std::string& where)
{
  std::vector<double> sizes;
  try
  {
    sizes = dem::parse_numbers(text, where);
  }
  catch (const std::runtime_error& e)
  {
    throw dem::InputError(e.what());
  }
  if (sizes.size() != 1 && sizes.size() != 3)
    throw dem::InputError(where + ": give one value or three (x, y, z)");
  return sizes.size() == 1 ? Vec3::Constant(sizes[0]) : Vec3(sizes[0], sizes[1], sizes[2]);
}

void parse_adaptive_region(ParameterHandler& prm, AdaptiveRegionSettings& a)
{
  prm.enter_subsection("Adaptive region");
  {
    a.enabled = prm.get_bool("enabled");
    a.threshold = prm.get_double("threshold");
    a.band_threshold = prm.get_double("band threshold");
    a.averaging_radius = prm.get_double("averaging radius");
    a.maximum_particles = std::size_t(prm.get_integer("maximum particles"));
    a.layers_ahead = prm.get_integer("layers ahead");
    a.crack_check_interval = prm.get_integer("crack check interval");
    a.envelope_coarsening = prm.get_integer("envelope coarsening");
    a.fine_margin = prm.get_integer("fine margin");
    if (a.envelope_coarsening < 1)
      throw dem::InputError(
          "Coupling/Adaptive region/envelope coarsening: " + std::to_string(a.envelope_coarsening) +
          " is below 1 (the FE grid keeps every k-th line of the envelope's "
          "cells away from the region; 1: every line)");
    if (a.fine_margin < 0)
      throw dem::InputError(
          "Coupling/Adaptive region/fine margin: " + std::to_string(a.fine_margin) +
          " is negative (cells kept fine beyond the region's faces; 0: the "
          "growth's layers and the averaging radius)");
    const std::string lo = prm.get("envelope lower"), hi = prm.get("envelope upper");
    if (lo.empty() != hi.empty())
      throw dem::InputError("Coupling/Adaptive region/envelope " +
                            std::string(lo.empty() ? "lower" : "upper") +
                            ": give both corners of the envelope, or neither");
    a.envelope_given = !lo.empty();
    if (a.envelope_given)
    {
      a.envelope_lo = dem::parse_vec3(lo, "Coupling/Adaptive region/envelope lower");
      a.envelope_hi = dem::parse_vec3(hi, "Coupling/Adaptive region/envelope upper");
    }
    if (a.enabled && !(a.threshold > 0 && a.threshold <= 1))
    {
      std::ostringstream m;
      m << "Coupling/Adaptive region/threshold: " << a.threshold
        << " lies outside (0, 1] (the share of the bonds' strength at which the continuum turns "
           "into particles)";
      throw dem::InputError(m.str());
    }
    if (a.enabled && !(a.band_threshold > 0 && a.band_threshold <= 1))
    {
      std::ostringstream m;
      m << "Coupling/Adaptive region/band threshold: " << a.band_threshold
        << " lies outside (0, 1]";
      throw dem::InputError(m.str());
    }
  }
  prm.leave_subsection();
}

void parse_pulse(ParameterHandler& prm, CoupledCase& c)
{
  prm.enter_subsection("Pulse");
  c.pulse.enabled = prm.get_bool("enabled");
  c.pulse.axis = int(std::string("xyz").find(prm.get("axis")));
  c.pulse.centre = prm.get_double("centre");
  c.pulse.wavelength = prm.get_double("wavelength");
  c.pulse.amplitude = prm.get_double("amplitude");
  c.pulse.envelope = prm.get_double("envelope");
  c.pulse.direction = prm.get_integer("direction");
  if (c.pulse.enabled && c.pulse.direction == 0)
    throw dem::InputError("Coupling/Pulse/direction: +1 or -1");
  if (c.pulse.enabled && !(c.pulse.wavelength > 0))
    throw dem::InputError("Coupling/Pulse/wavelength: must be positive");
  prm.leave_subsection();
}

/// The band and the FE mesh around the particle region.
void declare_band_and_mesh(ParameterHandler& prm)
{
  prm.declare_entry("band width", "0", Double(0),
                    "Width L of the handshake band (m), inside the particle region along its "
                    "faces that lie inside the FE domain; at least two particle diameters. "
                    "0: three particle diameters.");
  prm.declare_entry("particle region file", "", dealii::Patterns::Anything(),
                    "The particle region as the volume of a gmsh mesh (.msh 2.2 or 4.1, "
                    "tetrahedra or hexahedra) inside the FE domain, relative to the case file's "
                    "folder (or a mesh of the build's meshes folder). Its bounding box replaces "
                    "Particles/origin and box size; the packing's particles outside the volume are "
                    "dropped; the band lies along its surface inside the domain. Empty: the box "
                    "Particles/origin + box size.");
  prm.declare_entry("weight floor", "0.1", Double(0, 0.5),
                    "Smallest mass weight of either side in the band (0 < f < 0.5): keeps the "
                    "explicit step where one side's mass would vanish.");
  prm.declare_entry("element size", "0.01", List(Double(0), 1, 3),
                    "FE cell size outside the band (m): one value or one per axis x, y, z. The "
                    "FE mesh is graded so that cell faces lie on the band's planes.");
  prm.declare_entry("band element size", "0", Double(0),
                    "FE cell size across the band (m); 0: the smallest element size.");
  prm.declare_entry("far element size", "0", List(Double(0), 1, 3),
                    "Away from the band the FE cells grow by 'element growth' per cell up to "
                    "this size (m; one value or x, y, z); 0: every cell of 'element size'.");
  prm.declare_entry("element growth", "1.2", Double(1, 2),
                    "Ratio of neighbouring cells' sizes where they grow away from the band.");
}

/// The continuum's tensor, the tie and its solve.
void declare_tensor_and_tie(ParameterHandler& prm)
{
  prm.declare_entry("continuum tensor", "closed form",
                    Selection("closed form|periodic|measured|file"),
                    "The continuum's elasticity tensor, from the particle region's packing: "
                    "closed form (simple cubic lattice: C11 = k_n/d, C44 = k_s/(2d)), periodic "
                    "(one periodic cell of a cubic, hcp or fcc lattice), measured (six uniform "
                    "strains on the packing itself; random packings), file (Coupling/tensor "
                    "file).");
  prm.declare_entry("tensor file", "", dealii::Patterns::Anything(),
                    "elasticity.json written by `dembridge elasticity` (its stiffness_tensor), "
                    "relative to the case file's folder.");
  prm.declare_entry("tying", "particle", Selection("particle|node"),
                    "particle: each interface particle's velocity tied to the FE velocity at "
                    "its position (bridging domain); node: FE nodes slaved to the particles "
                    "(master-slave).");
  prm.declare_entry("constraint solve", "exact", Selection("exact|lumped"),
                    "exact: the multipliers by CG on G M^-1 G^T + diag(1/m_p); lumped: its "
                    "row-sum diagonal (local, approximate).");
}

/// Damping of both sides, the driven supports' ramp, the rest criterion.
void declare_damping_and_ramps(ParameterHandler& prm)
{
  prm.declare_entry("mass damping", "0", Double(0),
                    "Mass-proportional damping c (1/s) on both sides (-c M v, -c m v): "
                    "quasi-static runs; its dissipation is booked.");
  prm.declare_entry("fine scale damping", "0", Double(0),
                    "Damping (1/s) of the part of a band particle's motion the FE field cannot "
                    "carry, scaled by 1 - alpha (node tying only).");
  prm.declare_entry("ramp time", "0", Double(0),
                    "Driven FE supports (FEM/Boundary conditions with a non-zero value) reach "
                    "their value at this time (s); 0: at once.");
  prm.declare_entry("ramp profile", "smooth", Selection("smooth|linear"),
                    "Ramp of the driven supports: smooth 3 s^2 - 2 s^3 (no shock) or linear s.");
  prm.declare_entry("rest tolerance", "0", Double(0, 1),
                    "Stop once at rest after the last ramp: the kinetic share of both sides "
                    "K / (K + U) below this at five consecutive records; 0: run to the end "
                    "time.");
}

/// Subsection Adaptive region (adaptive_region.h).
void declare_adaptive_region(ParameterHandler& prm)
{
  prm.enter_subsection("Adaptive region");
  prm.declare_entry("enabled", "false", Bool(),
                    "Grow the particle region while the run goes: FE cells whose averaged "
                    "utilisation (the continuum's stress against the bonds' strengths, "
                    "docs/adaptive.md) passes the threshold turn into bonded particles, by whole "
                    "layers of cells. The particle box (Particles/origin, box size) is the region "
                    "at the start; one MPI process; lattice packings.");
  prm.declare_entry("threshold", "0.7", Double(),
                    "Utilisation in (0, 1] at which a cell turns into particles (1: at the "
                    "bonds' mean strength).");
  prm.declare_entry("band threshold", "0.8", Double(),
                    "Failure index in (0, 1] of a band bond (its whole force against its own "
                    "strength) at which its cell turns into particles: where damage nears the "
                    "band, which is held elastic.");
  prm.declare_entry("averaging radius", "0", Double(),
                    "Radius of the non-local average of the utilisation (m); 0: the band width.");
  prm.declare_entry("maximum particles", "0", Integer(0),
                    "The region grows no further once it would hold more particles (the run "
                    "says so and goes on); 0: no cap.");
  prm.declare_entry("layers ahead", "2", Integer(0),
                    "Whole layers of cells added beyond the least that puts a marked cell "
                    "deeper than the band (fewer, larger growths).");
  prm.declare_entry("crack check interval", "10", Integer(0),
                    "While bonds break, growth is checked every this many steps instead of at "
                    "every record (Output/history interval); 0: at every record only.");
  prm.declare_entry("envelope coarsening", "4", Integer(),
                    "k >= 1: inside the envelope, away from the region, the FE grid keeps every "
                    "k-th line of the envelope's cells (cells k times the band element size); 1: "
                    "every line.");
  prm.declare_entry("fine margin", "0", Integer(),
                    "Cells of the band element size kept on either side of the region's faces "
                    "per axis (the FE grid's fine zone; it widens as the region grows, and a "
                    "continuum refined under load rings: docs/adaptive.md); 0: the envelope's "
                    "whole extent along each axis where the region has a face inside the domain.");
  prm.declare_entry("envelope lower", "", dealii::Patterns::Anything(),
                    "Lower corner x, y, z of the box the region may grow in (m); empty: the FE "
                    "domain. Its cells have the band element size near the region.");
  prm.declare_entry("envelope upper", "", dealii::Patterns::Anything(),
                    "Upper corner x, y, z of that box (m); empty: the FE domain.");
  prm.leave_subsection();
}

/// Subsection Pulse: the wave runs' initial pulse.
void declare_pulse(ParameterHandler& prm)
{
  prm.enter_subsection("Pulse");
  prm.declare_entry("enabled", "false", Bool(),
                    "Start from a longitudinal pulse A exp(-(s/(e lambda))^2) cos(2 pi s / "
                    "lambda), s the distance from its centre along the axis (wave runs).");
  prm.declare_entry("axis", "x", Selection("x|y|z"), "Direction of the bar.");
  prm.declare_entry("centre", "0", Double(), "Centre of the pulse on the axis (m).");
  prm.declare_entry("wavelength", "0.1", Double(0), "Dominant wavelength lambda (m).");
  prm.declare_entry("amplitude", "1e-6", Double(0), "A (m).");
  prm.declare_entry("envelope", "1", Double(0), "e: Gaussian width in wavelengths.");
  prm.declare_entry("direction", "1", Integer(-1, 1),
                    "+1 or -1: the direction it travels along the axis.");
  prm.leave_subsection();
}
} // namespace

void declare_coupling_parameters(ParameterHandler& prm)
{
  prm.enter_subsection("Coupling");
  declare_band_and_mesh(prm);
  declare_tensor_and_tie(prm);
  declare_damping_and_ramps(prm);
  declare_adaptive_region(prm);
  declare_pulse(prm);
  prm.leave_subsection();
}

void parse_coupling_section(ParameterHandler& prm, CoupledCase& c)
{
  prm.enter_subsection("Coupling");
  auto& s = c.settings;
  const double radius = c.particles.particles.radius;
  s.geometry.band_width = prm.get_double("band width");
  if (s.geometry.band_width == 0)
    s.geometry.band_width = 6 * radius;
  s.geometry.weight_floor = prm.get_double("weight floor");
  s.element_size = sizes_per_axis(prm.get("element size"), "Coupling/element size");
  s.band_element_size = prm.get_double("band element size");
  s.far_element_size = sizes_per_axis(prm.get("far element size"), "Coupling/far element size");
  s.element_growth = prm.get_double("element growth");
  if (s.band_element_size == 0)
    s.band_element_size = s.element_size.minCoeff();
  if (!(s.element_size.minCoeff() > 0))
    throw dem::InputError("Coupling/element size: must be positive");
  const std::string tensor = prm.get("continuum tensor");
  c.tensor = tensor == "closed form" ? coupling::TensorSource::closed_form
             : tensor == "periodic"  ? coupling::TensorSource::periodic
             : tensor == "measured"  ? coupling::TensorSource::measured
                                     : coupling::TensorSource::file;
  c.tensor_file = prm.get("tensor file");
  c.region_file = prm.get("particle region file");
  if (c.tensor == coupling::TensorSource::file && c.tensor_file.empty())
    throw dem::InputError("Coupling/tensor file: continuum tensor = file needs an elasticity.json");
  s.tying = prm.get("tying") == "node" ? coupling::Tying::node : coupling::Tying::particle;
  s.solve = prm.get("constraint solve") == "lumped" ? coupling::ConstraintSolve::lumped
                                                    : coupling::ConstraintSolve::exact;
  s.mass_damping = prm.get_double("mass damping");
  s.fine_scale_damping = prm.get_double("fine scale damping");
  if (s.fine_scale_damping > 0 && s.tying != coupling::Tying::node)
    throw dem::InputError("Coupling/fine scale damping: acts with node tying only (tying = node)");
  c.ramp_time = prm.get_double("ramp time");
  c.smooth_ramp = prm.get("ramp profile") == "smooth";
  parse_adaptive_region(prm, s.adaptive);
  parse_pulse(prm, c);
  prm.leave_subsection();

  // the common step: Simulation/time step (auto or a value) and its safety factor
  s.time_step = c.particles.run.time_step;
  s.time_step_safety = c.particles.run.safety;
}
} // namespace dembridge::coupling
