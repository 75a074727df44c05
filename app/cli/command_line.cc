#include "app/cli/command_line.h"
#include "app/input/case_file.h"
#include <deal.II/base/parameter_handler.h>
#include <iostream>
#include <stdexcept>

namespace dembridge::app
{
std::string usage_error(CLI::App& app, int argc, char** argv, const std::string& what)
{
  if (argc > 1 && argv[1][0] != '-')
  {
    std::string known;
    bool found = false;
    for (const auto* sub : app.get_subcommands({}))
    {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found = found || sub->get_name() == argv[1];
    }
    if (!found)
      return "unknown subcommand '" + std::string(argv[1]) + "' (expected " + known + ")";
  }
  return one_line(what);
}

void refuse_empty_paths(const CLI::App& app)
{
  for (const auto* command : app.get_subcommands())
    for (const char* name : {"--output-dir", "--resume"})
      if (const auto* option = command->get_option_no_throw(name);
          option && option->count() > 0 && option->as<std::string>().empty())
        throw std::runtime_error(std::string(name) + ": the path is empty (name a folder" +
                                 (name == std::string("--output-dir")
                                      ? ", or leave the option out for the default one)"
                                      : ")"));
}

CLI::App* add_print_parameters_command(CLI::App& app)
{
  return app.add_subcommand("print-parameters",
                            "Print every parameter with its default and documentation");
}

int print_parameters(const MpiJob& job)
{
  dealii::ParameterHandler prm;
  declare_all_parameters(prm, {"<name>"}, {"<name>"}, {"<name>"});
  if (job.root())
    prm.print_parameters(std::cout, dealii::ParameterHandler::Text);
  return 0;
}
} // namespace dembridge::app
