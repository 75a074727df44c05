#!/usr/bin/env python3
"""Write errors name the file and the operating system's reason (dem/core/output_file.h).

usage: write_errors.py DEMBRIDGE CASE OUT KILL_AFTER_STEP [--set KEY=VALUE]...

Without mounting anything (root or not):
  a full disk   a run killed after step KILL_AFTER_STEP (past its first checkpoint, before its
                second) is resumed with one of the files the
                resumed run writes (summary.json.part, particle_stress.csv.part, particles.pvd in
                the staging folder, checkpoint.h5.tmp) made a symbolic link to /dev/full, which refuses every
                write with ENOSPC: "No space left on device";
  a file limit  fresh runs under RLIMIT_FSIZE with SIGXFSZ ignored, so that a write past the
                limit fails with EFBIG ("File too large"): 4 KiB with ParaView output (the first
                snapshot crosses it) and without (history.csv.part crosses it).
Each run must fail with exit code 1 and one line on stderr that names the file by its full path
and the reason. Under the limit, Open MPI's daemon of a one-process run (which the limit reaches
too) keeps its data in memory, not in shared-memory files the limit refuses (PMIX_MCA_gds=hash),
and does not report signals (OMPI_MCA_ess_base_forward_signals=none). Plain python3.
"""
import os
import resource
import shutil
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checkpoint_resume import fail  # noqa: E402

FILE_LIMIT = 4096  # bytes
CHECKPOINT_LIMIT = 200000  # above the test case's checkpoint (125 kB), below its history (360 kB)


def main():
    args = sys.argv[1:]
    if len(args) < 4:
        fail(__doc__)
    exe, case, out, kill_after = args[0], args[1], os.path.abspath(args[2]), args[3]
    sets = args[4:] + ["--set", "Simulation/threads=1"]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)

    def run(folder, extra=(), env_extra=None, resume=False, file_limit=None):
        env = dict(os.environ)
        env.update(env_extra or {})
        if file_limit:
            env.update({"PMIX_MCA_gds": "hash", "OMPI_MCA_ess_base_forward_signals": "none"})
        cmd = [exe, "run", case] + sets + list(extra) + (
            ["--resume", folder] if resume else ["--output-dir", folder])

        def limit():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # EFBIG instead of death by signal
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_limit, file_limit))

        return subprocess.run(cmd, env=env, capture_output=True, text=True,
                              preexec_fn=limit if file_limit else None,
                              restore_signals=file_limit is None)

    def failed_naming(r, path, reason, what):
        lines = r.stderr.strip().splitlines()
        if r.returncode != 1 or len(lines) != 1 or path + ": " not in lines[0] \
                or reason not in lines[0]:
            fail("%s: expected exit 1 and one line naming %s and '%s', got %s: %s%s" %
                 (what, path, reason, r.returncode, r.stdout[-1000:], r.stderr))
        print("  %s: %s" % (what, lines[0]))

    # a full disk: /dev/full in place of a file the resumed run writes
    killed = os.path.join(out, "killed")
    r = run(killed, env_extra={"DEMBRIDGE_TEST_KILL_AFTER_STEP": kill_after})
    if r.returncode != -signal.SIGKILL or not os.path.exists(os.path.join(killed, "checkpoint.h5")):
        fail("the run was not killed after its first checkpoint: %s %s" % (r.returncode, r.stderr))
    for name in [".partial/summary.json.part", ".partial/particle_stress.csv.part",
                 ".partial/particles.pvd", "checkpoint.h5.tmp"]:
        folder = os.path.join(out, "full_" + os.path.basename(name).split(".")[0])
        shutil.copytree(killed, folder, symlinks=True)
        target = os.path.join(folder, name)
        os.symlink("/dev/full", target)
        failed_naming(run(folder, resume=True), target, "No space left on device",
                      "full disk at " + name)

    # a file size limit: the first file to cross it
    folder = os.path.join(out, "limit_vtu")
    failed_naming(run(folder, ["--set", "Output/write vtu=true"], file_limit=FILE_LIMIT),
                  os.path.join(folder, ".partial", "particles_000000.vtu"), "File too large",
                  "%d-byte file limit, ParaView output" % FILE_LIMIT)
    folder = os.path.join(out, "limit_history")
    failed_naming(run(folder, ["--set", "Output/write vtu=false", "--set", "Output/history interval=1"],
                      file_limit=FILE_LIMIT),
                  os.path.join(folder, ".partial", "history.csv.part"), "File too large",
                  "%d-byte file limit, no ParaView output" % FILE_LIMIT)

    # a run that fails after writing a checkpoint keeps its staged files (a fresh run into the
    # folder is refused while the checkpoint is there), and --resume then completes it: a limit
    # above the checkpoint's size that history.csv crosses after the first checkpoints
    folder = os.path.join(out, "limit_after_checkpoint")
    no_vtu = ["--set", "Output/write vtu=false", "--set", "Output/history interval=1"]
    failed_naming(run(folder, no_vtu, file_limit=CHECKPOINT_LIMIT),
                  os.path.join(folder, ".partial", "history.csv.part"), "File too large",
                  "%d-byte file limit after a checkpoint" % CHECKPOINT_LIMIT)
    if not os.path.exists(os.path.join(folder, "checkpoint.h5")) or \
            not os.path.exists(os.path.join(folder, ".partial", "history.csv.part")):
        fail("the run that failed after its checkpoint did not keep its checkpoint and staged "
             "files: %s" % sorted(os.listdir(folder)))
    r = run(folder, no_vtu, resume=True)
    if r.returncode != 0 or not os.path.exists(os.path.join(folder, "summary.json")):
        fail("--resume after the failure did not complete: %s %s" % (r.returncode, r.stderr))
    print("  resumed after the failure: ok")
    print("ok")


if __name__ == "__main__":
    main()
