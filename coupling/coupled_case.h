#pragma once
// A coupled case as the user describes it, and the CoupledProblem it makes (coupled_problem.h).
//
// The user writes what a DEM case and an FE case would hold, plus the band:
//   particles  the packing of the particle region: Particles/origin and box size are the
//              particle box, or the bounding box of a gmsh volume (Coupling/particle region file)
//              whose particles alone are kept (the handshake band lies inside it, along its faces
//              that are inside the FE domain), with its bonds, groups (a load point, a deflection
//              probe) and loads (dem::CaseConfig);
//   continuum  the FE domain (FEM/Mesh box), density, supports and loads (fem::Parameters).
//              A support with a non-zero value is a prescribed displacement: it is driven from 0
//              to its value along the ramp below (linear, or smooth 3 s^2 - 2 s^3), as a DEM
//              displacement load is;
//   band       width, weight floor, element sizes, tying, damping (CouplingSettings).
// The continuum's stiffness tensor comes from the packing itself (both sides the same
// material), chosen by `tensor`:
//   closed_form  the simple cubic lattice, C11 = k_n/d, C12 = 0, C44 = k_s/(2d)
//                (dem/measurements/elasticity_tensor.h, 3.);
//   periodic     the ideal lattice from one periodic cell (cubic, HCP, FCC; ibid. 2.);
//   measured     six uniform strains on the particle region's own packing (ibid. 1.), for
//                random packings;
//   file         `stiffness_tensor` of an elasticity.json (`dembridge elasticity`).
// An initial longitudinal pulse (measurements.h) may be given for wave runs: it starts on the
// side its centre lies on, with that side's discrete phase speed.
#include "coupling/coupled_problem.h"
#include "coupling/measurements.h"
#include "dem/model/case_config.h"
#include "fem/parameters.h"
#include <memory>
#include <string>

namespace dembridge::coupling
{
enum class TensorSource
{
  closed_form,
  periodic,
  measured,
  file
};

struct PulseConfig
{
  bool enabled = false;
  int axis = 0;
  double centre = 0;     ///< m
  double wavelength = 0; ///< m
  double amplitude = 1e-6;
  double envelope = 1;
  int direction = 1;
};

struct CoupledCase
{
  dem::CaseConfig particles;
  fem::Parameters continuum;
  CouplingSettings settings; ///< geometry and tensor are filled by make_coupled_problem
  TensorSource tensor = TensorSource::closed_form;
  std::string tensor_file; ///< for TensorSource::file (absolute or relative to the cwd)
  /// The particle region as a gmsh volume (region_volume.h; absolute, relative to the cwd or in
  /// the build's meshes folder); empty: the box Particles/origin + box size. Its bounding box
  /// becomes the packing's box, and only the particles inside it are kept.
  std::string region_file;
  double ramp_time = 0;    ///< s, driven boundaries
  bool smooth_ramp = true; ///< 3 s^2 - 2 s^3 instead of s
  PulseConfig pulse;
};

/// The continuum's tensor (Pa, Voigt 6x6) for the case's packing and tensor source; throws
/// std::runtime_error naming Coupling/continuum tensor when the source does not fit the packing.
Voigt6x6 continuum_tensor(const CoupledCase& c);

/// Makes @p region the particle region: the handshake's (its bounding box the particle box) and
/// the packing's (its bounding box the packing's box; kept: the particles inside it).
void set_particle_region(std::shared_ptr<const RegionVolume> region, HandshakeGeometry& g,
                         dem::ParticleSource& packing);

/// Fills the geometry and tensor, turns non-zero FE supports into driven boundaries, builds
/// and sets up the problem and gives it its initial state (the pulse, or rest). Collective.
/// Throws std::runtime_error naming the key on bad input.
std::unique_ptr<CoupledProblem> make_coupled_problem(CoupledCase& c, MPI_Comm comm);

/// +1: the pulse starts in the continuum, -1: in the particles, 0: no pulse.
int pulse_side(const CoupledCase& c);

/// The end of the last load ramp (DEM loads and driven boundaries), s.
double last_ramp_end(const CoupledCase& c);
} // namespace dembridge::coupling

namespace dembridge::coupling
{
/// What a damage run (Damage/failure set) asks but its set-up cannot show, one line each naming
/// the key: a notch (Particles/remove box) reaching outside the particle region, where the
/// continuum is not notched; a loaded group with particles outside the particle-only zone (in
/// the band its bonds are held elastic and blended, beyond it there are none). Empty for runs
/// without damage. Rank 0 (the particle model's).
std::vector<std::string> damage_setup_warnings(const CoupledCase& c, CoupledProblem& p);
} // namespace dembridge::coupling
