// dembridge.calibrate(targets, output_dir=None, set=None, plot=True): `dembridge calibrate`
// from Python (app/studies/calibrate.h). It writes the same output folder (calibration.json,
// calibration.png, the calibrated cases) and returns calibration.json as a dict. Input the
// command line refuses raises dembridge.CaseError with the same line; a target out of the bond
// model's reach is not an input error: the dict says so ("reached": False, "failure": the line
// the command line ends with), as calibration.json does.
#include "app/studies/calibrate.h"
#include "python/model_bindings.h"
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace dembridge::python
{
namespace
{
/// A str or os.PathLike as a path string.
std::string path_text(const py::object& path)
{
  return py::str(py::module_::import("os").attr("fspath")(path));
}

py::object calibrate(const py::object& targets, const py::object& output_dir,
                     const py::object& settings, bool plot)
{
  app::CalibrateOptions options;
  options.targets_file = path_text(targets);
  // the package's own --set conversion (a dict or "Section/Key=value" strings)
  options.overrides =
      py::module_::import("dembridge").attr("overrides")(settings).cast<std::vector<std::string>>();
  if (!output_dir.is_none())
    options.output_dir = path_text(output_dir);
  options.plot = plot;
  options.progress = false; // the iterations are in the returned dict
  std::string report;
  {
    py::gil_scoped_release release;
    report = rethrow_as_case_error([&] { return app::calibrate(options).report.dump(); });
  }
  return py::module_::import("json").attr("loads")(report);
}
} // namespace

void bind_calibrate(py::module_& m)
{
  m.def("calibrate", &calibrate, py::arg("targets"), py::arg("output_dir") = py::none(),
        py::arg("set") = py::none(), py::arg("plot") = true,
        "Finds the bond parameters that give a case the targets of its Calibration section, as "
        "`dembridge calibrate TARGETS --output-dir DIR --set ...` does (docs/calibration.md); "
        "returns calibration.json as a dict (\"reached\", \"calibrated\", each iteration). "
        "Raises CaseError for input the command line refuses.");
}
} // namespace dembridge::python
