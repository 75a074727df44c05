#pragma once
// The Python module's DEM model (dembridge.Model): a DEM case built as `dembridge run` builds
// it, stepped from Python, its particle and bond state as NumPy arrays that view the model's
// own structure-of-arrays storage (no copy per step); and the module's exception, CaseError.
#include <functional>
#include <pybind11/pybind11.h>
#include <stdexcept>
#include <string>

namespace dembridge::python
{
/// A case that cannot be read, built or run: the CLI's one-line message (file, key, reason).
/// Python sees dembridge.CaseError, a ValueError.
class CaseError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Declares CaseError in the module.
void register_case_error(pybind11::module_& m);

/// Runs @p work; any error it throws is rethrown as CaseError with the CLI's one-line message.
template <typename Work> auto rethrow_as_case_error(Work&& work) -> decltype(work());

/// Declares dembridge._dembridge.Model.
void bind_model(pybind11::module_& m);

std::string one_line_message(const std::exception& e);

template <typename Work> auto rethrow_as_case_error(Work&& work) -> decltype(work())
{
  try
  {
    return work();
  }
  catch (const CaseError&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    throw CaseError(one_line_message(e));
  }
}
} // namespace dembridge::python
