// libFuzzer target: the case-file reader on any text: the scan for empty files and repeated
// keys (app/input/case_scan.h), a text opening with '{' as JSON (app/input/case_json.h), deal.II's two-pass
// ParameterHandler parse (app/input/case_file.h), and the translation of every mode the file can
// name: a DEM case (app/input/dem_parameters.h) with its size estimate (the memory guard's), the FE
// parameters, a coupled case with its run settings (app/input/coupled_parameters.h), and the output
// settings. Tiny lattice and row cases (estimate below 200 particles) are also built into a
// model, so that the builder's own checks are reached; larger builds are left to the bad-input
// tests: under AddressSanitizer a 2,000-particle build took about 0.15 s, which kept this target
// at 6 executions a second.
// Input errors (dem::InputError, std::runtime_error from the reader, deal.II's ExceptionBase) are
// the expected outcome; crashes, sanitizer reports, other exceptions, hangs and memory beyond
// libFuzzer's limit are findings. Nothing is written: `save file` is cleared.
#include "app/input/case_file.h"
#include "app/input/dem_parameters.h"
#include "dem/model/model.h"
#include "dem/model/size_estimate.h"
#ifdef DEMBRIDGE_HAVE_FEM
#include "app/input/coupled_parameters.h"
#include "fem/parameters.h"
#endif
#include <cstddef>
#include <cstdint>
#include <deal.II/base/exceptions.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  dealii::deal_II_exceptions::disable_abort_on_exception(); // deal.II asserts throw instead
  // why: a deal.II exception symbolises its stack trace (dladdr) when it is built, which took a
  // quarter of this target's time; the expected input errors do not need it
  dealii::deal_II_exceptions::suppress_stacktrace_in_exceptions();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  namespace dem = dembridge::dem;
  namespace app = dembridge::app;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    // a text that opens with '{' is read as a JSON case (app/input/case_json.h)
    const auto first = text.find_first_not_of(" \t\r\n");
    const bool json = first != std::string::npos && text[first] == '{';
    auto prm = app::read_case_text(text, json ? "fuzz.json" : "fuzz.prm", {});
    const std::string mode = prm->get("Mode");
    app::parse_output_settings(*prm);
#ifdef DEMBRIDGE_HAVE_FEM
    if (mode == "fem")
    {
      dembridge::fem::parse_parameters(*prm);
      return 0;
    }
    if (mode == "coupled")
    {
      const auto c = app::parse_coupled_case(*prm);
      app::parse_coupled_run_settings(*prm, c);
      return 0;
    }
#endif
    dem::CaseConfig config = app::parse_dem_case(*prm);
    config.particles.save_file.clear();
    const dem::SizeEstimate estimate = dem::estimate_size(config);
    using K = dem::ParticleSource::Kind;
    const bool quick = config.particles.kind != K::random && config.particles.kind != K::file;
    if (quick && estimate.particles < 200 && estimate.bonds < 2000)
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
