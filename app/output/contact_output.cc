#include "app/output/contact_output.h"

namespace dembridge::app
{
ContactOutput::ContactOutput(const dem::Model& model)
{
  for (const auto& c : model.contributions)
    if (const auto* found = dynamic_cast<const dem::ContactForces*>(c.get()))
      contacts_ = found;
}

std::string ContactOutput::history_header() const
{
  if (!contacts_)
    return {};
  std::string h = ",n_contacts";
  for (std::size_t w = 0; w < contacts_->walls(); ++w)
    for (const char* q : {"position", "fx", "fy", "fz"})
      h += "," + contacts_->wall(w).name + "_" + q;
  if (contacts_->platens().enabled)
    h += ",platen_stress,platen_strain";
  return h;
}

void ContactOutput::history_row(std::ostream& out, double time) const
{
  if (!contacts_)
    return;
  out << ',' << contacts_->active_contacts();
  for (std::size_t w = 0; w < contacts_->walls(); ++w)
  {
    const auto& wall = contacts_->wall(w);
    const dem::Vec3& f = contacts_->force_on_wall(w);
    out << ',' << wall.point(time).dot(wall.normal) << ',' << f.x() << ',' << f.y() << ',' << f.z();
  }
  if (contacts_->platens().enabled)
    out << ',' << contacts_->platens().stress << ',' << contacts_->platens().strain;
}

void ContactOutput::summary(nlohmann::json& j, double time) const
{
  if (!contacts_)
    return;
  const auto& c = *contacts_;
  j["contact_model"] = std::string(dem::contact_model_names[std::size_t(c.material().model)]);
  j["n_contacts"] = c.active_contacts();
  j["contact_updates"] = c.contact_updates();
  j["neighbour_list_builds"] = c.list_builds();
  j["neighbour_search_seconds"] = c.search_seconds();
  j["contact_seconds"] = c.contact_seconds();
  j["contact_updates_per_second"] =
      c.contact_seconds() > 0 ? double(c.contact_updates()) / c.contact_seconds() : 0.0;
  j["contact_activation_energy"] = c.activation_energy();
  for (std::size_t w = 0; w < c.walls(); ++w)
  {
    const auto& wall = c.wall(w);
    const dem::Vec3 f = c.force_on_wall(w), u = wall.displacement(time);
    j["walls"][wall.name] = {{"force", {f.x(), f.y(), f.z()}},
                             {"normal_force", -f.dot(wall.normal)},
                             {"displacement", {u.x(), u.y(), u.z()}}};
  }
  const auto& mon = c.monitor();
  if (mon.enabled)
  {
    j["max_overlap"] = mon.max_overlap;
    j["max_contact_force"] = mon.max_force;
    if (mon.finished)
    {
      j["contact_duration"] = mon.duration();
      j["restitution_coefficient"] = mon.restitution();
    }
    else // no contact closed and opened again during the run
      j["contact_duration"] = j["restitution_coefficient"] = nullptr;
  }
  const auto& t = c.platens();
  if (t.enabled)
  {
    j["peak_stress"] = t.peak_stress;
    j["strain_at_peak"] = t.strain_at_peak;
    j["time_at_peak"] = t.time_at_peak;
    j["final_stress"] = t.stress;
    j["final_strain"] = t.strain;
    j["platen_area"] = t.area;
    j["platen_distance"] = t.length;
    if (const double ref = c.material().reference_tensile_strength; ref > 0)
    {
      j["reference_tensile_strength"] = ref;
      j["compressive_to_tensile_strength_ratio"] = t.peak_stress / ref;
    }
  }
}
} // namespace dembridge::app
