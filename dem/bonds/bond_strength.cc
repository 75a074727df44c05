#include "dem/bonds/bond_strength.h"
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

namespace dembridge::dem
{
namespace
{
std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

void require_positive(double value, const std::string& key, const char* unit)
{
  if (!(value > 0) || !std::isfinite(value))
    throw InputError("Damage/" + key + ": must be positive (got " + number(value) + " " + unit +
                     ")");
}

/// Strengths drawn one after the other from one seeded stream.
class StrengthSampler
{
public:
  explicit StrengthSampler(const DamageConfig& c) : StrengthSampler(c, c.seed) {}
  StrengthSampler(const DamageConfig& c, std::uint64_t seed) : c_(c), rng_(seed)
  {
    if (c.scatter == StrengthScatter::weibull)
      weibull_scale_ = 1.0 / std::tgamma(1.0 + 1.0 / c.weibull_modulus);
  }

  double draw(double mean)
  {
    switch (c_.scatter)
    {
    case StrengthScatter::none:
      return mean;
    case StrengthScatter::normal:
      for (;;) // truncated to positive strengths: redraw
      {
        const double s = mean * (1.0 + c_.scatter_deviation * standard_normal());
        if (s > 0)
          return s;
      }
    case StrengthScatter::weibull:
      return mean * weibull_scale_ * std::pow(-std::log1p(-uniform()), 1.0 / c_.weibull_modulus);
    }
    return mean;
  }

private:
  /// U[0, 1) from the top 53 bits (std::uniform_real_distribution is not specified bit for bit).
  double uniform() { return double(rng_() >> 11) * 0x1.0p-53; }
  /// Box-Muller, both variates used in turn.
  double standard_normal()
  {
    if (has_spare_)
    {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform(), u2 = uniform(); // u1 in (0, 1]
    const double r = std::sqrt(-2.0 * std::log(u1)), t = 2.0 * std::numbers::pi * u2;
    spare_ = r * std::sin(t), has_spare_ = true;
    return r * std::cos(t);
  }

  const DamageConfig& c_;
  std::mt19937_64 rng_;
  double weibull_scale_ = 1;
  double spare_ = 0;
  bool has_spare_ = false;
};
/// splitmix64 (Steele et al. 2014): a bijective mix, so nearby grid cells get unrelated seeds.
std::uint64_t mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// The seed of a bond at midpoint m: the case's seed and m on a 0.1 um grid.
std::uint64_t position_seed(std::uint64_t seed, const Vec3& m)
{
  std::uint64_t h = mix(seed);
  for (int d = 0; d < 3; ++d)
    h = mix(h ^ std::uint64_t(std::llround(m[d] * 1e7)));
  return h;
}
} // namespace

void DamageConfig::validate() const
{
  if (law.mode == FailureMode::none)
    return;
  require_positive(tensile_strength, "tensile strength", "Pa");
  if (law.shear == ShearCriterion::constant)
    require_positive(shear_strength, "shear strength", "Pa");
  else
  {
    require_positive(cohesion, "cohesion", "Pa");
    if (!(friction_angle >= 0 && friction_angle < 90))
      throw InputError("Damage/friction angle: must lie in [0, 90) degrees (got " +
                       number(friction_angle) + ")");
  }
  if (!(law.moment_factor >= 0 && law.moment_factor <= 1))
    throw InputError("Damage/moment factor: must lie in [0, 1] (got " + number(law.moment_factor) +
                     ")");
  if (scatter == StrengthScatter::normal && !(scatter_deviation > 0 && scatter_deviation < 10))
    throw InputError("Damage/scatter: the relative standard deviation of a normal scatter must "
                     "lie in (0, 10) (got " +
                     number(scatter_deviation) + ")");
  if (scatter == StrengthScatter::weibull && !(weibull_modulus > 0 && weibull_modulus < 1e3))
    throw InputError("Damage/weibull modulus: must lie in (0, 1000) (got " +
                     number(weibull_modulus) + ")");
  if (law.mode == FailureMode::softening)
  {
    for (auto [g, key] : {std::pair{law.fracture_energy_I, "fracture energy mode I"},
                          std::pair{law.fracture_energy_II, "fracture energy mode II"}})
      if (!(g > 0) || !std::isfinite(g))
        throw InputError(std::string("Damage/") + key +
                         ": softening needs a positive fracture energy (got " + number(g) +
                         " J/m^2)");
  }
}

void assign_bond_strengths(BondStore& b, const DamageConfig& c, const std::vector<Vec3>* positions,
                           std::span<const ClassDamage> classes)
{
  c.validate();
  const std::size_t n = b.size();
  b.failure = c.law;
  if (c.law.shear == ShearCriterion::mohr_coulomb)
    b.failure.tan_friction = std::tan(c.friction_angle * std::numbers::pi / 180.0);
  const bool on = c.law.mode != FailureMode::none;
  b.tensile_strength.assign(on ? n : 0, 0.0);
  b.shear_strength.assign(on ? n : 0, 0.0);
  b.damage.assign(on ? n : 0, 0.0);
  b.kappa_max.assign(on ? n : 0, 0.0);
  b.kappa_ultimate.assign(on ? n : 0, 0.0);
  b.dissipated.assign(on ? n : 0, 0.0);
  b.failure_mode.assign(on ? n : 0, CrackMode::tension);
  if (!on)
    return;
  const double shear_mean = c.law.shear == ShearCriterion::constant ? c.shear_strength : c.cohesion;
  const bool by_class = !classes.empty() && b.bond_class.size() == n;
  if (by_class && classes.size() < bond_class_count)
    throw std::logic_error("assign_bond_strengths: a mean per bond class needed");
  b.failure.by_class = by_class;
  if (by_class)
    for (std::size_t k = 0; k < bond_class_count; ++k)
      b.failure.classes[k] = classes[k].law;
  auto means = [&](std::size_t k)
  {
    return by_class ? classes[std::size_t(b.bond_class[k])]
                    : ClassDamage{c.tensile_strength, shear_mean, b.failure};
  };
  if (c.scatter_by_position && c.scatter != StrengthScatter::none)
  {
    if (!positions)
      throw InputError("Damage/scatter key: position needs the particles' positions");
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vec3 mid = 0.5 * ((*positions)[b.a[k]] + (*positions)[b.b[k]]);
      StrengthSampler sample(c, position_seed(c.seed, mid));
      const ClassDamage mean = means(k);
      b.tensile_strength[k] = sample.draw(mean.tensile);
      b.shear_strength[k] = sample.draw(mean.shear);
    }
  }
  else
  {
    StrengthSampler sample(c);
    for (std::size_t k = 0; k < n; ++k)
    {
      const ClassDamage mean = means(k);
      b.tensile_strength[k] = sample.draw(mean.tensile);
      b.shear_strength[k] = sample.draw(mean.shear);
    }
  }
  if (c.law.mode != FailureMode::softening)
    return;
  // Snap-back (bond_damage.h eq. 4): G_f A >= U_peak of pure tension and of pure shear, each
  // bond against its class's G_f; the worst shortfall per key is named.
  double worst_I = 1, worst_II = 1;      // least G_f / (U_peak / A) over the bonds
  std::size_t needy_I = n, needy_II = n; // the bonds that fall short the most
  for (std::size_t k = 0; k < n; ++k)
  {
    const FailureConstants& law = b.failure_constants(k);
    const double area = std::numbers::pi * b.radius[k] * b.radius[k];
    const double u_I = b.tensile_strength[k] * b.tensile_strength[k] * area / (2 * b.kn[k]);
    const double u_II = b.shear_strength[k] * b.shear_strength[k] * area / (2 * b.ks[k]);
    if (law.fracture_energy_I < worst_I * u_I)
      worst_I = law.fracture_energy_I / u_I, needy_I = k;
    if (law.fracture_energy_II < worst_II * u_II)
      worst_II = law.fracture_energy_II / u_II, needy_II = k;
  }
  for (auto [needy, mode_II, key, what] :
       {std::tuple{needy_I, false, "fracture energy mode I", "sigma_t^2 A / (2 k_n)"},
        std::tuple{needy_II, true, "fracture energy mode II", "tau^2 A / (2 k_s)"}})
  {
    if (needy == n)
      continue;
    const FailureConstants& law = b.failure_constants(needy);
    const double g = mode_II ? law.fracture_energy_II : law.fracture_energy_I;
    const double s = mode_II ? b.shear_strength[needy] : b.tensile_strength[needy];
    const double k = mode_II ? b.ks[needy] : b.kn[needy];
    const double need = s * s * std::numbers::pi * b.radius[needy] * b.radius[needy] / (2 * k);
    const BondClass cls = by_class ? b.bond_class[needy] : BondClass::intra_grain;
    const std::string section = cls == BondClass::intra_grain
                                    ? std::string("Damage/")
                                    : "Bond class " + std::string(bond_class_name(cls)) + "/";
    throw InputError(
        section + key + ": " + number(g) +
        " J/m^2 is below the elastic energy per bond area at the peak, " + what + " = " +
        number(need) + " J/m^2 for the strongest bond" +
        (by_class ? " (a " + std::string(bond_class_name(cls)) + " bond)" : std::string()) +
        " (snap-back); use at least that");
  }
}
} // namespace dembridge::dem
