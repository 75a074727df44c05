// fem_driver — runs one FEM case file without the app, for the fem tests.
//   fem_driver CASE.prm OUTPUT_DIR [Section/Key=value ...]
// Declares the FEM subsections (and the app's top-level "Mode" entry, so that case files
// written for `dembridge run` are read unchanged), runs the case with the FE mode's output files
// (app/runs/fem_run.h) and writes summary.json.
#include "app/runs/fem_run.h"

#include <deal.II/base/mpi.h>

#include <fstream>
#include <iostream>

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool rank0 = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
  {
    if (argc < 3)
      throw std::runtime_error("usage: fem_driver CASE.prm OUTPUT_DIR [Section/Key=value ...]");
    dealii::ParameterHandler prm;
    prm.declare_entry("Mode", "fem", dealii::Patterns::Selection("fem|dem"), "Run mode.");
    dembridge::fem::declare_parameters(prm);
    prm.parse_input(argv[1]);
    for (int i = 3; i < argc; ++i)
    {
      // "A/B/key=value": enter A, B, set key.
      const std::string arg = argv[i];
      const auto eq = arg.find('=');
      const auto slash = arg.rfind('/', eq);
      if (eq == std::string::npos || slash == std::string::npos)
        throw std::runtime_error("override '" + arg + "' is not Section/Key=value");
      std::vector<std::string> sections;
      std::size_t start = 0;
      for (std::size_t s = arg.find('/'); s <= slash; s = arg.find('/', s + 1))
      {
        sections.push_back(arg.substr(start, s - start));
        start = s + 1;
      }
      for (const auto& s : sections)
        prm.enter_subsection(s);
      prm.set(arg.substr(slash + 1, eq - slash - 1), arg.substr(eq + 1));
      for (std::size_t k = 0; k < sections.size(); ++k)
        prm.leave_subsection();
    }
    const std::filesystem::path output = argv[2];
    std::filesystem::create_directories(output);
    const nlohmann::json summary =
        dembridge::app::run_fem_case(dembridge::fem::parse_parameters(prm), output, MPI_COMM_WORLD);
    if (rank0)
    {
      std::ofstream(output / "summary.json") << summary.dump(2) << "\n";
      std::cout << summary.dump(2) << std::endl;
    }
  }
  catch (const std::exception& e)
  {
    std::string what = e.what();
    // deal.II exceptions span several lines; print the first non-empty one.
    std::istringstream lines(what);
    std::string line;
    while (std::getline(lines, line) && line.find_first_not_of(" -") == std::string::npos)
    {
    }
    if (rank0)
      std::cerr << "error: " << line << std::endl;
    return 1;
  }
  return 0;
}
