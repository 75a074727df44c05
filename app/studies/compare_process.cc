// Processes of `dembridge compare` from argument vectors (compare_process.h).
#include "app/studies/compare_process.h"
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <spawn.h>
#include <stdexcept>
#include <sys/wait.h>

extern char** environ;

namespace dembridge::app
{
namespace fs = std::filesystem;

int run_process(const std::vector<std::string>& argv, const fs::path& log)
{
  std::vector<char*> args;
  for (const auto& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log.empty())
  {
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  }
  std::cout.flush(); // the child writes to the same descriptors
  std::fflush(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw std::runtime_error("compare: cannot start " + argv[0] + ": " + std::strerror(error));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error("compare: lost " + argv[0] + ": " + std::strerror(errno));
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void run_case_process(const std::string& what, const fs::path& case_file,
                      const std::vector<std::string>& overrides, const fs::path& dir)
{
  std::vector<std::string> argv = {fs::read_symlink("/proc/self/exe").string(), "run",
                                   case_file.string(), "--output-dir", dir.string()};
  for (const auto& s : overrides)
    argv.insert(argv.end(), {"--set", s});
  std::cout << "compare: " << what << " (into " << dir.string() << ")" << std::endl;
  const int rc = run_process(argv);
  if (rc != 0)
    throw std::runtime_error("compare: " + what + " failed (exit " + std::to_string(rc) +
                             "); its message is above");
}
} // namespace dembridge::app
