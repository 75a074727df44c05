#include "app/runs/fem_checkpoints.h"
#include <csignal>
#include <cstdio>
#include <cstdlib>

namespace dembridge::app
{
fem::DynamicsCheckpoints fem_checkpoints(const dealii::ParameterHandler& prm,
                                         const CheckpointSettings& c)
{
  fem::DynamicsCheckpoints f;
  if (c.file.empty())
    return f;
  f.interval = prm.get_double({"Output"}, "checkpoint interval");
  f.wall_interval = prm.get_double({"Output"}, "checkpoint wall interval");
  f.resume = c.resume;
  f.write = [&c](long step, double time, const fem::DynamicsCheckpoints::Visit& visit)
  { write_checkpoint(c.file, make_checkpoint_header(c, step, time), visit); };
  f.read = [&c](const fem::DynamicsCheckpoints::Visit& visit)
  {
    read_checkpoint(c.file, visit);
    std::printf("resumed from %s: step %ld, t = %.6g s\n", c.file.string().c_str(), c.resumed_step,
                c.resumed_time);
  };
  if (const char* kill = std::getenv("DEMBRIDGE_TEST_KILL_AFTER_STEP")) // tests (checkpoint.h)
    f.after_step = [step = std::atol(kill)](long n)
    {
      if (n == step)
        std::raise(SIGKILL);
    };
  return f;
}
} // namespace dembridge::app
