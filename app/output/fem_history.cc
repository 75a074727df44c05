#include "app/output/fem_history.h"
#include "dem/core/output_file.h"

namespace dembridge::app
{
FemHistory::FemHistory(const std::filesystem::path& path, const bool root,
                       const std::size_t n_probes, const std::int64_t resume_length)
    : root_(root)
{
  row_.precision(12);
  if (!root_)
    return;
  const bool resumed = resume_length >= 0;
  file_.open(path, resumed);
  if (resumed)
  {
    file_.resume_at(resume_length);
    return;
  }
  std::ostream& out = file_.stream();
  out << "step,time";
  for (std::size_t k = 0; k < n_probes; ++k)
    out << ",probe" << k << "_ux,probe" << k << "_uy,probe" << k << "_uz";
  out << ",kinetic_energy,kinetic_energy_shadow,strain_energy,load_potential,"
         "total_energy,shadow_energy\n";
}

void FemHistory::add(const fem::DynamicsRow& row)
{
  if (!root_)
    return;
  const auto& e = row.energies;
  row_.str("");
  row_ << row.step << "," << row.time;
  for (const auto& v : row.probe_displacements)
    row_ << "," << v[0] << "," << v[1] << "," << v[2];
  row_ << "," << e.kinetic << "," << e.kinetic_shadow << "," << e.strain << "," << e.load_potential
       << "," << e.total() << "," << e.shadow_total() << "\n";
  file_.stream() << row_.str();
}

void write_timing_log(const std::filesystem::path& dir, const std::string& table, const bool root)
{
  if (!root)
    return;
  dem::OutputFile log(dir / "timing.log"); // failures name the file and the reason
  log << table;
  log.close();
}
} // namespace dembridge::app
