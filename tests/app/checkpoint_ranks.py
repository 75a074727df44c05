#!/usr/bin/env python3
"""A coupled or FE checkpoint is resumed on the number of MPI ranks that wrote it, no other
(docs/checkpoint.md): each rank sums its own share of the continuum's works.

usage: checkpoint_ranks.py DEMBRIDGE MPIEXEC CASE OUT [--ranks W:R]... [--kill-after-step N]
                           [--refusal REGEX] [--kept FILE]... [--set KEY=VALUE]...

Runs the coupled case (with Output/checkpoint interval among the --set) under `MPIEXEC -np 2`,
killed (SIGKILL) a few steps after its first checkpoint (after step N, default 80: the first
checkpoint of tests/coupling/coupled_pull.prm is at step 78), and resumes it on one rank; then the
reverse (written on one rank, resumed on two). Each resume must be refused with exit code 1 and
one line on rank 0's stderr naming both rank counts (the other ranks print nothing: app/mpi_job.h),
before any step, leaving the checkpoint.
--ranks W:R: written on W ranks, resumed on R, instead (repeated: each pair).
--refusal REGEX: rank 0's line matches REGEX instead of naming the rank counts (a refusal for
another reason, such as a one-rank DEM checkpoint resumed on several ranks).
--kept FILE: FILE (in the run's folder) is still there and not empty after the refusal.
Plain python3.
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    if len(sys.argv) < 5:
        fail(__doc__)
    exe, mpiexec, case, out = sys.argv[1:5]
    rest = sys.argv[5:]
    kill_after, pairs, refusal, kept = "80", [], None, []
    while rest[:1] and rest[0] in ("--kill-after-step", "--ranks", "--refusal", "--kept"):
        option, value, rest = rest[0], rest[1], rest[2:]
        if option == "--kill-after-step":
            kill_after = value
        elif option == "--ranks":
            pairs.append(tuple(int(n) for n in value.split(":")))
        elif option == "--refusal":
            refusal = value
        else:
            kept.append(value)
    pairs = pairs or [(2, 1), (1, 2)]
    sets = rest + ["--set", "Simulation/threads=1"]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)

    def run(np, folder, resume=False, env_extra=None):
        """Runs on np ranks; returns the exit code and each rank's stderr (kept apart)."""
        env = dict(os.environ)
        env.update(env_extra or {})
        where = ["--resume", folder] if resume else ["--output-dir", folder]
        errdir = tempfile.mkdtemp()
        try:
            rank_err = '2>"%s/rank.${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}"' % errdir
            cmd = [mpiexec, "-np", str(np), "--oversubscribe", "sh", "-c",
                   'exec "$0" "$@" ' + rank_err, exe, "run", case] + sets + where
            rc = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL).returncode
            errs = []
            for r in range(np):
                path = os.path.join(errdir, "rank.%d" % r)
                errs.append(open(path).read() if os.path.exists(path) else None)
            return rc, errs
        finally:
            shutil.rmtree(errdir, ignore_errors=True)

    for written, resumed in pairs:
        folder = os.path.join(out, "np%d_resumed_on_%d" % (written, resumed))
        rc, _ = run(written, folder, env_extra={"DEMBRIDGE_TEST_KILL_AFTER_STEP": kill_after})
        if rc in (0, 1) or not os.path.exists(os.path.join(folder, "checkpoint.h5")):
            fail("np %d: the run was not killed after a checkpoint (exit code %d)" % (written, rc))
        rc, errs = run(resumed, folder, resume=True)
        expected = ("checkpoint.h5: the checkpoint was written by a run on %d MPI rank(s), this "
                    "run has %d (resume it with mpirun -np %d)" % (written, resumed, written))
        pattern = refusal or re.escape(expected)
        for r, err in enumerate(errs):
            if r == 0 and (err is None or err.count("\n") != 1 or not err.endswith("\n")
                           or not re.search(pattern, err)):
                fail("np %d resumed on %d: rank 0: expected one line matching /%s/, got %r" %
                     (written, resumed, pattern, err))
            if r > 0 and err != "":
                fail("np %d resumed on %d: rank %d printed %r (rank 0 alone prints)" %
                     (written, resumed, r, err))
            print("  np %d resumed on %d, rank %d: %r" % (written, resumed, r, err))
        if rc != 1:
            fail("np %d resumed on %d: exit code %d, expected 1" % (written, resumed, rc))
        if os.path.exists(os.path.join(folder, "summary.json")):
            fail("a refused resume wrote summary.json")
        if not glob.glob(os.path.join(folder, "checkpoint.h5")):
            fail("a refused resume removed the checkpoint")
        for name in kept:
            path = os.path.join(folder, name)
            if not os.path.isfile(path) or os.path.getsize(path) == 0:
                fail("a refused resume removed or emptied %s" % name)
    print("ok")


if __name__ == "__main__":
    main()
