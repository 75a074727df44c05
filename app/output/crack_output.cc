#include "app/output/crack_output.h"
#include "app/checkpoint/checkpoint.h"
#include "app/output/particle_vtu_file.h"
#include "dem/core/output_file.h"
#include "dem/measurements/crack_orientation.h"
#include "dem/measurements/failure_measurements.h"
#include "dem/model/groups.h"
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <set>

namespace dembridge::app
{
CrackOutput::CrackOutput(std::filesystem::path dir, bool write_vtu, bool failure_law)
    : dir_(std::move(dir)), write_vtu_(write_vtu), failure_law_(failure_law)
{
}

void CrackOutput::update(const dem::ExplicitSolver& s)
{
  const auto& all = s.cracks();
  const std::size_t from = cracks_.size();
  cracks_.insert(cracks_.end(), all.begin() + long(from), all.end());
  classify(s, from);
}

void CrackOutput::classify(const dem::ExplicitSolver& s, std::size_t from)
{
  const dem::BondStore& b = s.bonds();
  const dem::ParticleStore& p = s.particles();
  has_classes_ = !b.bond_class.empty(), has_grains_ = !p.grain.empty();
  classes_.resize(from), intergranular_.resize(from);
  for (std::size_t k = from; k < cracks_.size(); ++k)
  {
    const std::size_t bond = cracks_[k].bond; // the solver's order
    classes_.push_back(has_classes_ ? std::uint8_t(b.bond_class[bond]) : 0);
    intergranular_.push_back(has_grains_ &&
                             p.grain[std::size_t(b.a[bond])] != p.grain[std::size_t(b.b[bond])]);
  }
}

void CrackOutput::visit_state(dem::StateArchive& a, const dem::ExplicitSolver& s)
{
  dem::StateGroup group(a, "crack_output");
  std::size_t taken = cracks_.size();
  a.io("taken", taken);
  visit_file_list(a, "snapshots", files_);
  if (!a.loading())
    return;
  if (taken > s.cracks().size())
    throw dem::InputError(a.where() + "taken: more cracks than the solver's log holds");
  cracks_.assign(s.cracks().begin(), s.cracks().begin() + long(taken));
  classify(s, 0);
}

void CrackOutput::snapshot(double time, long step)
{
  if (!write_vtu_ || !failure_law_)
    return;
  const std::size_t n = cracks_.size();
  std::vector<dem::Vec3> points(n), axis(n);
  std::vector<double> t(n), energy(n), axis_values(3 * n);
  std::vector<std::uint8_t> mode(n);
  std::vector<std::int64_t> a(n), b(n), bond(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto& c = cracks_[k];
    points[k] = c.midpoint, t[k] = c.time, energy[k] = c.energy;
    mode[k] = std::uint8_t(c.mode == dem::CrackMode::shear); // 0 tension, 1 shear
    a[k] = c.a, b[k] = c.b, bond[k] = std::int64_t(c.bond);
    for (int d = 0; d < 3; ++d)
      axis_values[3 * k + std::size_t(d)] = c.axis[d];
  }
  VtuFile file(points, VtuFile::Cells::vertices);
  file.point_data("time", t);
  file.cell_data("mode", mode);
  file.point_data("energy", energy);
  file.point_data("particle_a", a);
  file.point_data("particle_b", b);
  file.point_data("bond", bond);
  file.point_data("axis", axis_values, 3);
  if (has_classes_)
    file.cell_data("class", classes_);
  char name[40];
  std::snprintf(name, sizeof name, "cracks_%06zu.vtu", files_.size());
  file.write(dir_ / name, time, step);
  files_.emplace_back(time, name);
}

void CrackOutput::finish() const
{
  if (!failure_law_)
    return;
  const std::filesystem::path file = dir_ / "cracks.csv", part = dir_ / "cracks.csv.part";
  {
    dem::OutputFile out(part); // failures name the file and the reason
    out << "time,x,y,z,axis_x,axis_y,axis_z,mode,energy,particle_a,particle_b,bond"
        << (has_classes_ ? ",class" : "") << (has_grains_ ? ",grains" : "") << '\n'
        << std::setprecision(10);
    for (std::size_t k = 0; k < cracks_.size(); ++k)
    {
      const auto& c = cracks_[k];
      out << c.time << ',' << c.midpoint.x() << ',' << c.midpoint.y() << ',' << c.midpoint.z()
          << ',' << c.axis.x() << ',' << c.axis.y() << ',' << c.axis.z() << ','
          << (c.mode == dem::CrackMode::shear ? "shear" : "tension") << ',' << c.energy << ','
          << c.a << ',' << c.b << ',' << c.bond;
      if (has_classes_)
        out << ',' << dem::bond_class_names[classes_[k]];
      if (has_grains_)
        out << ',' << (intergranular_[k] ? "intergranular" : "transgranular");
      out << '\n';
    }
    out.close();
  }
  std::filesystem::rename(part, file);
  if (write_vtu_)
  {
    write_pvd(dir_ / "cracks.pvd", files_);
  }
}

void add_bond_class_summary(nlohmann::json& j, const dem::ParticleStore& p, const dem::BondStore& b)
{
  if (b.bond_class.empty()) // no microstructure (dem/bonds/bond_class.h)
    return;
  std::array<long, dem::bond_class_count> all{}, broken{};
  long intergranular = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
  {
    ++all[std::size_t(b.bond_class[k])];
    if (b.state[k] != dem::BondState::broken)
      continue;
    ++broken[std::size_t(b.bond_class[k])];
    intergranular +=
        !p.grain.empty() && p.grain[std::size_t(b.a[k])] != p.grain[std::size_t(b.b[k])];
  }
  for (std::size_t c = 0; c < dem::bond_class_count; ++c)
  {
    const std::string name(dem::bond_class_names[c]);
    j["bonds_per_class"][name] = all[c];
    j["broken_bonds_per_class"][name] = broken[c];
  }
  if (!p.grain.empty())
  {
    j["n_grains"] = std::set<std::int32_t>(p.grain.begin(), p.grain.end()).size();
    j["broken_bonds_intergranular"] = intergranular;
    long all_broken = 0;
    for (long n : broken)
      all_broken += n;
    j["broken_bonds_transgranular"] = all_broken - intergranular;
  }
}

void add_crack_summary(nlohmann::json& j, const std::vector<dem::CrackEvent>& cracks,
                       const dem::ParticleStore& p, const dem::BondStore& b, int layers,
                       int layer_axis, int load_axis)
{
  long tension = 0;
  for (const auto& c : cracks)
    tension += c.mode == dem::CrackMode::tension;
  j["n_broken_bonds"] = cracks.size();
  j["broken_bonds_tension"] = tension;
  j["broken_bonds_shear"] = long(cracks.size()) - tension;
  j["broken_bond_fraction"] = b.size() > 0 ? double(cracks.size()) / double(b.size()) : 0.0;
  add_bond_class_summary(j, p, b);
  if (load_axis >= 0 && b.has_failure())
  {
    // against the load axis, and against each axis (a confined test's splitting cracks open
    // across the free axis, not the confined one: the angle from the load alone misses it)
    const dem::CrackOrientation h = dem::crack_orientation(cracks, load_axis, 9);
    auto& o = j["crack_orientation"];
    o = {{"load_axis", std::string(1, "xyz"[h.axis])},
         {"normal_angle_edges_deg", h.edges},
         {"isotropic_fraction", h.isotropic_fraction},
         {"counts", h.counts},
         {"fraction", h.fraction},
         {"mean_normal_angle_deg", h.mean_angle},
         {"along_load_fraction", h.along_load_fraction}};
    for (int axis = 0; axis < 3; ++axis)
    {
      const dem::CrackOrientation a = dem::crack_orientation(cracks, axis, 9);
      o["from_axis"][std::string(1, "xyz"[axis])] = {
          {"counts", a.counts}, {"fraction", a.fraction}, {"mean_normal_angle_deg", a.mean_angle}};
    }
  }
  if (!cracks.empty())
  {
    const auto& first = cracks.front();
    j["first_crack"] = {{"time", first.time},
                        {"position", {first.midpoint.x(), first.midpoint.y(), first.midpoint.z()}},
                        {"mode", first.mode == dem::CrackMode::tension ? "tension" : "shear"}};
  }
  if (layers > 0)
  {
    const auto [lo, hi] = dem::reference_extent(p);
    const dem::DamageLayers d = dem::damage_layers(p, b, lo, hi, layer_axis, layers);
    j["damage_layers"] = {{"axis", std::string(1, "xyz"[d.axis])},
                          {"edges", d.edges},
                          {"n_bonds", d.bonds},
                          {"n_broken", d.broken},
                          {"broken_fraction", d.broken_fraction},
                          {"localisation", d.localisation},
                          {"band", d.band}};
  }
}

void add_peak_stress(nlohmann::json& j, const std::vector<double>& force,
                     const std::vector<double>& displacement, double area, double gauge_length)
{
  const dem::PeakLoad peak = dem::peak_of(force, displacement);
  if (peak.index < 0 || !(area > 0) || !(gauge_length > 0))
    return;
  j["peak_stress"] = std::abs(peak.load) / area;
  j["strain_at_peak"] = std::abs(peak.displacement) / gauge_length;
  // the load at the end of the run over the peak: how far past the peak the run went
  j["final_to_peak_load"] = peak.load != 0 ? force.back() / peak.load : 0.0;
}

void add_peak_load(nlohmann::json& j, const std::vector<double>& load,
                   const std::vector<double>& deflection)
{
  const dem::PeakLoad peak = dem::peak_of(load, deflection);
  if (peak.index < 0)
    return;
  j["peak_load"] = std::abs(peak.load);
  j["deflection_at_peak"] = std::abs(peak.displacement);
  j["final_to_peak_load"] = peak.load != 0 ? load.back() / peak.load : 0.0;
}
} // namespace dembridge::app
