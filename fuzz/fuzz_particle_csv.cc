// libFuzzer target: the particle CSV reader (dem/packing/packings.h, read_particles) on any
// bytes, with the overlap and cell-list checks it runs. A refusal (InputError) is the expected
// outcome of bad input; anything else (a crash, a sanitizer report, another exception, a hang,
// memory beyond libFuzzer's limit) is a finding.
#include "dem/packing/packings.h"
#include <cstddef>
#include <cstdint>
#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  dembridge::dem::ParticleStore p;
  try
  {
    dembridge::dem::read_particles(in, "fuzz.csv", 1000, p);
  }
  catch (const dembridge::dem::InputError&)
  {
  }
  return 0;
}
