#include "app/output/dem_history.h"

namespace dembridge::app
{
std::string history_header(const dem::Model& model, const ContactOutput& contacts)
{
  std::string h = "step,time,kinetic_energy,strain_energy,damping_energy,external_work,"
                  "fracture_energy,contact_strain_energy,friction_energy,contact_damping_energy,"
                  "wall_work,energy_balance_error,max_speed,unbalanced_force_ratio,n_broken_bonds";
  for (const auto& g : model.groups)
    for (const char* q : {"ux", "uy", "uz", "fx", "fy", "fz"})
      h += "," + g.name + "_" + q;
  return h + contacts.history_header() + "\n";
}

void history_row(std::ostream& out, const HistoryRecord& r, const dem::ParticleStore& particles,
                 const std::vector<dem::Group>& groups, const ContactOutput& contacts)
{
  const auto& e = r.energy;
  out << r.step << ',' << r.time << ',' << e.kinetic << ',' << e.strain << ',' << e.damping << ','
      << e.external << ',' << e.fracture << ',' << e.contact_strain << ',' << e.friction << ','
      << e.contact_damping << ',' << e.wall_work << ',' << e.relative_error() << ',' << r.max_speed
      << ',' << r.unbalanced_force_ratio << ',' << r.broken_bonds;
  for (const auto& g : groups)
  {
    const dem::Vec3 u = dem::mean_displacement(particles, g), f = dem::total_force(particles, g);
    out << ',' << u.x() << ',' << u.y() << ',' << u.z() << ',' << f.x() << ',' << f.y() << ','
        << f.z();
  }
  contacts.history_row(out, r.time);
  out << '\n';
}
} // namespace dembridge::app
