#pragma once
// The memory a new allocation can still get on this machine, for the guards that refuse a case
// too big to build (dem/model/size_estimate.h, fem/mesh.cc). Header-only so that every layer
// can use it without linking the DEM core.
#include <cstdio>
#include <fstream>
#include <string>

namespace dembridge
{
/// MemAvailable of /proc/meminfo (the kernel's estimate of what can be allocated without
/// swapping), in bytes; 0 where unknown (not Linux): then no guard refuses anything.
inline double available_memory_bytes()
{
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  double kb = 0;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:")
      return kb * 1024.0;
  return 0.0;
}

/// "1.5 GB", "230 MB": bytes in the nearest decimal unit, three significant digits.
inline std::string human_bytes(double bytes)
{
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000 && u < 6)
    bytes /= 1000, ++u;
  char text[64];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[u]);
  return text;
}
} // namespace dembridge
