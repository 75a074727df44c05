#pragma once
// Where a binary comes from: the version of CMake's project() and the git commit of the
// source tree it was built from (with "-dirty" when tracked files differed from that commit;
// "unknown" when built without git or outside a git checkout).
#include <string>

namespace dembridge::app
{
std::string version();
std::string git_commit();
} // namespace dembridge::app
