#pragma once
// The processes `dembridge compare` starts: each model's run in a process of its own, so that its
// peak memory (the kernel's high-water mark of the process, memory_guard.h) is its own and not
// the largest of the models run before it, and the plot script. They are started from an argument
// vector (posix_spawnp), never through a shell: a case path with spaces or quotes stays one
// argument, and nothing in it is interpreted.
#include <filesystem>
#include <string>
#include <vector>

namespace dembridge::app
{
/// Runs @p argv (argv[0] a path, or a name looked up in PATH) and waits for it; its output goes to
/// ours, or (both streams) to @p log when given. Returns its exit code (128 + the signal when a
/// signal ended it). Throws std::runtime_error when it cannot be started.
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& log = {});

/// `dembridge run CASE --output-dir DIR [--set S]...` of this executable in a process of its own
/// (run_process); throws std::runtime_error naming @p what and the exit code when it fails.
void run_case_process(const std::string& what, const std::filesystem::path& case_file,
                      const std::vector<std::string>& overrides, const std::filesystem::path& dir);
} // namespace dembridge::app
