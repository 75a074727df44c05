#pragma once
// history.csv of a DEM run: one row per record of an explicit run, one per load step of a static
// run, the same columns for both (README: step, time, the energy terms, the balance error, the
// largest speed, the unbalanced-force ratio, broken bonds, each group's mean displacement and
// force, the contacts' and walls' columns).
#include "app/output/contact_output.h"
#include "dem/core/energy.h"
#include "dem/model/model.h"
#include <ostream>
#include <string>

namespace dembridge::app
{
/// The header line (with its newline).
std::string history_header(const dem::Model& model, const ContactOutput& contacts);

/// The figures of one row beside the groups' and contacts' columns.
struct HistoryRecord
{
  long step = 0;
  double time = 0;
  dem::EnergyBalance energy;
  double max_speed = 0, unbalanced_force_ratio = 0;
  long broken_bonds = 0;
};

/// One row (with its newline); the groups' columns from @p particles (mean displacement, total
/// force: support reactions on held DOFs).
void history_row(std::ostream& out, const HistoryRecord& r, const dem::ParticleStore& particles,
                 const std::vector<dem::Group>& groups, const ContactOutput& contacts);
} // namespace dembridge::app
