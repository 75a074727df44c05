#pragma once
// What the contacts and walls of a DEM run write (dem/contacts/): history.csv columns (active
// contacts; per wall its position along its normal and the force the particles exert on it) and
// summary.json keys (n_contacts, per-wall force and displacement, the first contact's duration,
// overlap, force and restitution when Contacts/monitor is on, the platens' stress-strain peak
// and, given Contacts/reference tensile strength, the ratio of compressive to tensile strength).
// Nothing is written for a run without contacts.
#include "dem/contacts/contact_forces.h"
#include "dem/model/model.h"
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

namespace dembridge::app
{
class ContactOutput
{
public:
  explicit ContactOutput(const dem::Model& model);

  /// ",n_contacts,NAME_position,NAME_fx,NAME_fy,NAME_fz..." (empty without contacts)
  std::string history_header() const;
  void history_row(std::ostream& out, double time) const;
  void summary(nlohmann::json& j, double time) const;

private:
  const dem::ContactForces* contacts_ = nullptr;
};
} // namespace dembridge::app
