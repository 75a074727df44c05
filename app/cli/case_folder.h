#pragma once
// Work on a case inside the case file's folder, as `dembridge run` does it: paths inside a case
// (particle files, meshes) are relative to that folder, and an input error names the file. The
// command line (run_command.cc) and the Python module (python/model_bindings.cc) both use it.
#include "dem/core/types.h"
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace dembridge::app
{
/// Runs @p work with the working directory at @p case_file's folder and restores it after, also
/// when @p work throws. A dem::InputError is rethrown as a std::runtime_error whose message starts
/// with the file's name (the message itself names the key and the reason); so is any other
/// std::runtime_error (the FE layer's input errors) that does not name the file already.
template <typename Work> decltype(auto) in_case_folder(const std::string& case_file, Work&& work)
{
  namespace fs = std::filesystem;
  struct RestoreFolder
  {
    fs::path previous = fs::current_path();
    ~RestoreFolder()
    {
      std::error_code ignored; // a destructor must not throw; the folder was there before
      fs::current_path(previous, ignored);
    }
  } restore;
  fs::current_path(fs::absolute(case_file).parent_path());
  try
  {
    return work();
  }
  catch (const dem::InputError& e)
  {
    throw std::runtime_error(fs::path(case_file).filename().string() + ": " + e.what());
  }
  catch (const std::runtime_error& e)
  {
    const std::string name = fs::path(case_file).filename().string(), what = e.what();
    throw std::runtime_error(what.rfind(name, 0) == 0 ? what : name + ": " + what);
  }
}
} // namespace dembridge::app
