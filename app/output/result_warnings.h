#pragma once
// Results that must not look complete when they are not. A figure the run could not measure
// (a modulus over a zero strain, a reaction that stayed zero, a bonded specimen with loose
// particles, a linear solution that rotated far) is named in summary.json's "warnings" and
// printed ("dembridge: warning: ..." on stderr, and again under the figures `run` prints),
// each line beginning with the key it concerns. A bonded specimen that forms no bond at all is
// refused.
#include "dem/core/particle_store.h"
#include "dem/model/case_config.h"
#include <nlohmann/json.hpp>
#include <string>

namespace dembridge::app
{
/// Appends @p line to summary["warnings"] (created when absent) and, when @p print, writes it to
/// stderr as "dembridge: warning: LINE".
void add_warning(nlohmann::json& summary, const std::string& line, bool print = true);

/// Every number in @p summary that is not finite (at any depth: "energy.kinetic") becomes null
/// with a warning "KEY: undefined (nan): ..." unless a warning already begins with "KEY:";
/// summary["warnings"] exists afterwards (empty when all is well).
void flag_undefined_figures(nlohmann::json& summary, bool print = true);

/// After bond formation: refuses (dem::InputError naming Bonds/contact radius multiplier and the
/// multiplier that would bond) a bonded specimen, one with a failure law, that formed no bond;
/// warns when a specimen with bonds has particles without any.
void check_bond_coverage(const dem::ParticleStore& p, std::size_t n_bonds,
                         const dem::CaseConfig& config, nlohmann::json& summary, bool print = true);

/// An explicit run needs a positive end time: throws dem::InputError naming Simulation/end time,
/// unless the run only writes its packing (end time 0 with a Particles/save file @p save_file).
void check_explicit_end_time(double end_time, const std::string& save_file = "");
} // namespace dembridge::app
