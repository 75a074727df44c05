#pragma once
// Plain description of a DEM case, independent of how it was read (the app fills it from a
// deal.II parameter file; tests and benchmarks fill it directly).
#include "dem/bonds/bond_model.h"
#include "dem/bonds/bond_strength.h"
#include "dem/contacts/contact_config.h"
#include "dem/microstructure/microstructure.h"
#include "dem/model/groups.h"
#include "dem/model/loads.h"
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace dembridge::dem
{
struct ParticleSource
{
  enum class Kind
  {
    row,   ///< `count` spheres on a line from `origin` along `direction`
    file,  ///< CSV file with columns x, y, z, r (m)
    cubic, ///< simple cubic lattice filling `box_size`
    hcp,   ///< hexagonal close packing filling `box_size`
    fcc,   ///< face-centred cubic (ABC stacking of triangular layers) filling `box_size`
    random ///< random close packing of `box_size` (packing_random.h), mono- or polydisperse
  } kind = Kind::row;
  int count = 2;
  double radius = 0.01;       ///< m
  std::vector<double> radii;  ///< per particle (row), overrides radius
  double spacing = 0;         ///< m, centre distance (row); 0: neighbours touch
  Vec3 origin = Vec3::Zero(); ///< m
  Vec3 direction = Vec3::UnitX();
  Vec3 box_size = Vec3(0.25, 0.1, 0.1); ///< m (lattices)
  std::string file;
  double density = 2500;                  ///< kg/m^3
  bool scale_density_by_porosity = false; ///< thesis eq. 63: rho_p = rho / (1 - porosity)
  // random packings
  std::string distribution = "mono"; ///< mono | uniform | normal
  double radius_spread = 0;          ///< relative (see RandomPackingSettings)
  unsigned seed = 1;
  double target_porosity = 0.37;
  /// the jamming density predicted, not measured (RandomPackingSettings::predict_jamming)
  bool predict_jamming = true;
  std::string save_file; ///< if set, the generated particles are written here (CSV)
  /// A notch: particles whose centres lie inside [remove_box_min, remove_box_max] are removed
  /// before bonding (no removal while the box has no volume).
  Vec3 remove_box_min = Vec3::Zero(), remove_box_max = Vec3::Zero();
  /// Only the particles whose centres it accepts are kept, after the porosity is measured on the
  /// whole packing and before bonding: a coupled run's particle region of any shape. Empty: all.
  std::function<bool(const Vec3&)> keep;
};

struct GroupConfig
{
  std::string name;
  GroupSelection selection;
  std::uint8_t fixed = 0; ///< DofBit mask held at zero velocity
  double mass = 0;        ///< kg per particle; 0 keeps density * volume
  Vec3 initial_velocity = Vec3::Zero();
};

struct LoadConfig
{
  Load load;
  std::string group;
  std::string ratio_load; ///< a pressure's sigma_ref load (Load::ratio_load), by name
};

struct BondConfig
{
  BondMaterial material;
  double contact_radius_multiplier = 1.0;          ///< eta_r
  std::vector<std::pair<int, int>> explicit_bonds; ///< if non-empty: these bonds only
};

struct RunConfig
{
  double time_step = 0;          ///< s; 0: automatic (safety * critical)
  double safety = 0.8;           ///< fraction of the critical step used by "auto"
  double end_time = 1.0;         ///< s
  double quasi_static_speed = 0; ///< m/s; >0: stop after the ramps once max speed < this
  /// >0: stop after the ramps once the unbalanced-force ratio (ExplicitSolver) is below this
  double equilibrium_ratio = 0;
  long max_steps = 100000000;
  int threads = 1;
  double bond_damping_ratio = 0; ///< xi (thesis eq. 37)
  double particle_damping = 0;   ///< gamma (paper eq. 11-12)
  double mass_damping = 0;       ///< c (1/s): -c m v on the particles (explicit_solver.h)
  bool static_solver = false;    ///< true: linear static solve (static_solver.h) instead
  /// Keep per-bond force records (BondStore::force, 48 bytes a bond): the static run's figures,
  /// a coupled run's band check and the tests read them; an explicit full-DEM run does not
  /// (its ParaView bond files evaluate each bond on demand) and sets this false.
  bool bond_force_records = true;
};

struct MeasureConfig
{
  std::string deflection_group;               ///< empty: none
  std::string deflection_name = "deflection"; ///< summary key, e.g. tip_deflection
  Vec3 deflection_direction = -Vec3::UnitZ(); ///< deflection = mean displacement . direction
  std::string frequency_group;                ///< empty: none; free vibration after all loads end
  std::string modulus_fixed_group;            ///< empty: no axial modulus
  std::string modulus_loaded_group;           ///< reaction and displacement of this end give E
  int modulus_axis = 0;                       ///< 0, 1, 2
  std::vector<std::string> flexural_groups;   ///< pin, roller, loaded (top), bottom; empty: none
  double flexural_poisson_ratio = 0;          ///< nu from the uniaxial tests (thesis eq. 67)
  double form_factor = 1.2;                   ///< Timoshenko f_s (6/5: rectangle)
  int stress_layers = 0;                      ///< slabs of the specimen for eq. 54 averages
  int stress_layer_axis = 2;                  ///< slab normal
  int stress_histogram_bins = 20;             ///< particle stress histogram (Fig. 36)
  /// m^2, per axis: the specimen's cross-section normal to it where the particles' bounding box
  /// is not the specimen (Particles/specimen volume: the volume over its length along the axis,
  /// exact for a prism such as a core along its axis); 0: the bounding box.
  Vec3 section_area = Vec3::Zero();
};

struct CaseConfig
{
  std::string name = "case";
  ParticleSource particles;
  BondConfig bonds;
  std::vector<GroupConfig> groups;
  std::vector<LoadConfig> loads;
  RunConfig run;
  MeasureConfig measure;
  ContactConfig contacts;        ///< post-failure contacts (dem/contacts/); model none: off
  std::vector<WallConfig> walls; ///< rigid planes, contact partners of the particles
  DamageConfig damage;           ///< bond strengths and failure law (dem/bonds/bond_strength.h)
  /// grains, weak planes and their bond classes (dem/microstructure/); off by default
  MicrostructureConfig microstructure;
  /// Renumber particles and bonds into spatial order once built (dem/model/renumbering.h);
  /// false keeps the packing's own numbering (the tests compare the two).
  bool spatial_order = true;
};
} // namespace dembridge::dem
