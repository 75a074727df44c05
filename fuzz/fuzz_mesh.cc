// libFuzzer target: the gmsh mesh reader on any bytes: our section check and $PhysicalNames
// reader (fem/mesh.h) and deal.II's GridIn::read_msh, as fem/mesh.cc uses them, into a serial
// triangulation. Input errors (std::runtime_error, deal.II's ExceptionBase) are expected;
// crashes, sanitizer reports, other exceptions, hangs and memory beyond libFuzzer's limit are
// findings (deal.II itself is not instrumented: its own memory errors show only as crashes).
#include "fem/mesh.h"
#include <cstddef>
#include <cstdint>
#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>
#include <sstream>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  dealii::deal_II_exceptions::disable_abort_on_exception();
  dealii::deal_II_exceptions::suppress_stacktrace_in_exceptions(); // no dladdr per input error
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    std::istringstream sections_in(text); // as fem/mesh.cc: refused before deal.II reads it
    dembridge::fem::check_msh_sections(sections_in, "fuzz.msh");
    std::istringstream names_in(text);
    dembridge::fem::read_physical_names(names_in, "fuzz.msh");
    std::istringstream mesh_in(text);
    dealii::Triangulation<3> tria;
    dealii::GridIn<3> grid_in;
    grid_in.attach_triangulation(tria);
    grid_in.read_msh(mesh_in);
  }
  catch (const std::runtime_error&)
  {
  }
  catch (const dealii::ExceptionBase&)
  {
  }
  return 0;
}
