// Kept apart from everything else: the build regenerates dembridge_git_commit.h when the commit
// changes, and only this small file recompiles.
#include "app/job/version.h"
#include "dembridge_git_commit.h"

namespace dembridge::app
{
std::string version()
{
  return DEMBRIDGE_VERSION;
}

std::string git_commit()
{
  return DEMBRIDGE_GIT_COMMIT;
}
} // namespace dembridge::app
