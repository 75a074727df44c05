// The Python module `dembridge` (its compiled part, _dembridge): the library that the command
// line uses, called from Python. python/dembridge/__init__.py builds the user-facing API on it
// (run(), Run, Case, Model); this file starts MPI and deal.II once per interpreter, runs a case
// as `dembridge run` does and turns the library's errors into Python exceptions.
#include "app/cli/run_command.h"
#include "app/input/case_file.h"
#include "app/job/mpi_job.h"
#include "app/job/provenance.h"
#include "dem/core/progress.h"
#include "python/model_bindings.h"
#include <deal.II/base/mpi.h>
#include <iostream>
#include <memory>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace dembridge::python
{
namespace
{
/// MPI (and PETSc, through deal.II) for the interpreter's lifetime: started when the module is
/// imported, finalised at interpreter exit (atexit), once; one rank unless Python itself was
/// started by mpirun.
struct Runtime
{
  int argc = 1;
  char name[16] = "dembridge";
  char* argv_storage[2] = {name, nullptr};
  char** argv = argv_storage;
  std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  std::unique_ptr<app::MpiJob> job;

  Runtime()
  {
    mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
    job = std::make_unique<app::MpiJob>(MPI_COMM_WORLD);
  }
};

Runtime*& runtime()
{
  static Runtime* instance = nullptr;
  return instance;
}

void shut_down()
{
  delete runtime();
  runtime() = nullptr;
}

/// Runs a case file as `dembridge run CASE --set ... --output-dir DIR` does; returns the exit code.
int run_case_file(const std::string& case_file, const std::vector<std::string>& overrides,
                  const std::string& output_dir)
{
  // summary.json's command_line: the command that makes the same run from a shell
  std::vector<std::string> words{"dembridge", "run", case_file, "--output-dir", output_dir};
  for (const auto& o : overrides)
    words.insert(words.end(), {"--set", o});
  std::vector<const char*> argv;
  for (const auto& w : words)
    argv.push_back(w.c_str());
  app::set_command_line(int(argv.size()), argv.data());
  app::RunOptions options;
  options.case_file = case_file;
  options.overrides = overrides;
  options.output_dir = output_dir;
  return rethrow_as_case_error([&] { return app::run_case(*runtime()->job, options); });
}

/// Reads and checks a case (every key declared, values matching their patterns) without running
/// it: the parameters as deal.II prints them in JSON (summary.json's `parameters`).
std::string check_case_file(const std::string& case_file, const std::vector<std::string>& overrides)
{
  return rethrow_as_case_error(
      [&]
      {
        const auto prm = app::read_case(case_file, overrides);
        std::ostringstream out;
        prm->print_parameters(out, dealii::ParameterHandler::ShortJSON);
        return out.str();
      });
}
} // namespace
void bind_calibrate(py::module_& m); // python/calibrate_bindings.cc
} // namespace dembridge::python

PYBIND11_MODULE(_dembridge, m)
{
  using namespace dembridge::python;
  m.doc() = "dembridge's library (the compiled part of the dembridge package)";
  register_case_error(m);
  if (!dembridge::python::runtime())
  {
    dembridge::python::runtime() = new Runtime();
    py::module_::import("atexit").attr("register")(py::cpp_function(&shut_down));
  }
  // long phases without an observer (random packing) report on stdout, as the CLI does
  dembridge::dem::progress_sink() = [](const std::string& line) { std::cout << line << std::endl; };
  m.def("run_case_file", &run_case_file, py::arg("case_file"), py::arg("overrides"),
        py::arg("output_dir"), py::call_guard<py::gil_scoped_release>(),
        "Runs a case file as `dembridge run` does (summary.json and the output files in "
        "output_dir); raises CaseError with the CLI's one-line message.");
  m.def("check_case_file", &check_case_file, py::arg("case_file"), py::arg("overrides"),
        "Reads and checks a case without running it; returns its parameters as JSON text.");
  bind_model(m);
  bind_calibrate(m);
}
