#pragma once
// What a case says about contacts: the contact law (chosen once per run), its material
// constants, the Verlet skin of the neighbour search, and the rigid walls (planes with a
// prescribed velocity). Contacts act between particles that touch and have no intact bond (never
// bonded, or broken) and between particles and walls.
//
// Damping from a restitution coefficient e in (0, 1] (thesis section 2.5; Tsuji et al. 1992):
//   zeta = -ln e / sqrt(pi^2 + ln^2 e)      damping ratio of the linear law (c = 2 zeta sqrt(m k))
//   beta =  ln e / sqrt(pi^2 + ln^2 e)      = -zeta, the factor of the Hertz-Mindlin dashpot
// Units: stiffnesses N/m (rolling N·m/rad), moduli Pa, lengths m, velocities m/s.
#include "dem/core/particle_store.h"
#include "dem/core/types.h"
#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace dembridge::dem
{
enum class ContactModel : std::uint8_t
{
  none,         ///< no contacts (bonds only)
  linear,       ///< linear spring-dashpot with Coulomb friction (thesis eq. 12-13)
  hertz_mindlin ///< Hertz normal, Mindlin no-slip tangential, Tsuji damping (EDEM's default)
};

/// The names a user types in a case file, in enum order.
inline constexpr std::array<std::string_view, 3> contact_model_names = {
    {"none", "linear", "hertz_mindlin"}};
ContactModel contact_model_from_name(std::string_view name);
std::string contact_model_selection(); ///< "none|linear|hertz_mindlin"

/// The contacts of a case (CaseConfig::contacts).
struct ContactConfig
{
  ContactModel model = ContactModel::none;
  double youngs_modulus = 0;       ///< E of the particles (Hertz-Mindlin), Pa
  double poisson_ratio = 0.25;     ///< nu of the particles (Hertz-Mindlin)
  double normal_stiffness = 0;     ///< k_n (linear), N/m
  double tangential_stiffness = 0; ///< k_t (linear), N/m; 0: 2/7 k_n
  double restitution = 1;          ///< e in (0, 1]
  double friction = 0.5;           ///< Coulomb mu >= 0 (particle-particle and particle-wall)
  double rolling_friction = 0;     ///< mu_r >= 0 (Ai et al. 2011, model C); 0: no rolling spring
  double rolling_stiffness = 0;    ///< k_r, N·m/rad; 0: 2.25 k_n mu_r^2 R*^2 (Ai et al.)
  double skin = 0;                 ///< Verlet skin, m; 0: 0.2 x the smallest radius
  bool monitor = false;            ///< record the first contact (duration, restitution, ...)
  /// Two walls (lower, upper) that load a specimen between them: their forces and approach give
  /// the stress-strain curve (ContactForces::platens); empty: none.
  std::vector<std::string> platens;
  /// Peak stress of a tension test of the same specimen and micro-parameters, Pa; > 0: the
  /// platen test reports the ratio of compressive to tensile strength against it; 0: none.
  double reference_tensile_strength = 0;

  bool enabled() const { return model != ContactModel::none; }
  /// Throws InputError naming Contacts/<key> if a value is missing or non-physical.
  void validate() const;
  /// zeta = -ln e / sqrt(pi^2 + ln^2 e) (0 for e = 1).
  double damping_ratio() const;
};

/// A rigid plane: the particles live on the side its normal points to. It moves with a
/// prescribed velocity that ramps linearly from 0 over ramp_time and stops at end_time (like the
/// velocity loads, loads.h).
struct WallConfig
{
  std::string name;
  Vec3 point = Vec3::Zero();    ///< a point of the plane at t = 0, m
  Vec3 normal = Vec3::UnitZ();  ///< towards the particles (normalised on use)
  Vec3 velocity = Vec3::Zero(); ///< full velocity, m/s
  double ramp_time = 0;         ///< s
  double end_time = std::numeric_limits<double>::infinity(); ///< s: the wall stops here
  /// true: at t = 0 the plane is moved along its normal until it touches the outermost particle
  /// on its side (a platen laid on a specimen whose extent the case does not know)
  bool touch = false;

  /// Throws InputError naming Wall NAME/<key>.
  void validate() const;
};

/// Moves every wall with `touch` along its normal so that it touches the particle that reaches
/// furthest to its side (no overlap, no gap).
void place_touching_walls(std::vector<WallConfig>& walls, const ParticleStore& p);
} // namespace dembridge::dem
