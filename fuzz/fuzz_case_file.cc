// libFuzzer target: the case-file reader on any text: the scan for empty files and repeated
// keys (app/case_scan.h), deal.II's two-pass ParameterHandler parse (app/case_file.h), the
// translation into a DEM case (app/dem_parameters.h) or the FE parameters, the size estimate of
// the memory guard, and for small lattice and row cases (estimate below 2,000 particles) the
// model build itself. Input errors (dem::InputError, std::runtime_error from the reader, deal.II's
// ExceptionBase) are the expected outcome; crashes, sanitizer reports, other exceptions, hangs
// and memory beyond libFuzzer's limit are findings. Nothing is written: `save file` is cleared.
#include "case_file.h"
#include "dem/model/model.h"
#include "dem/model/size_estimate.h"
#include "dem_parameters.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "fem/parameters.h"
#endif
#include <cstddef>
#include <cstdint>
#include <deal.II/base/exceptions.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  dealii::deal_II_exceptions::disable_abort_on_exception(); // deal.II asserts throw instead
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  namespace dem = dembridge::dem;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    auto prm = dembridge::app::read_case_text(text, "fuzz.prm", {});
    if (prm->get("Mode") == "fem")
    {
#ifdef DEMBRIDGE_HAVE_FEM
      dembridge::fem::parse_parameters(*prm);
#endif
      return 0;
    }
    dem::CaseConfig config = dembridge::app::parse_dem_case(*prm);
    config.particles.save_file.clear();
    const dem::SizeEstimate estimate = dem::estimate_size(config);
    using K = dem::ParticleSource::Kind;
    const bool quick = config.particles.kind != K::random && config.particles.kind != K::file;
    if (quick && estimate.particles < 2000 && estimate.bonds < 20000)
      dem::build_model(config);
  }
  catch (const dem::InputError&)
  {
  }
  catch (const std::runtime_error&)
  {
  }
  catch (const dealii::ExceptionBase&)
  {
  }
  return 0;
}
