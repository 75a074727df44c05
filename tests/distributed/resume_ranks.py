#!/usr/bin/env python3
"""A DEM checkpoint written on several MPI ranks, resumed on as many and on others.

usage: resume_ranks.py DEMBRIDGE MPIEXEC CASE OUT --write N --kill-after-step K
                       --resume-on M[,M...] [--again-after-step K2] [--write-failure]
                       [--set KEY=VALUE]...

Runs `MPIEXEC -np N dembridge run CASE` (with Output/checkpoint interval among the --set) into
OUT/killed, killed by SIGKILL after step K (DEMBRIDGE_TEST_KILL_AFTER_STEP, on every rank, after
a checkpoint before it); the folder must hold the checkpoint. Then, for each M, a copy of that
folder is resumed on M ranks (`dembridge run CASE --resume OUT/resumed_npM`, under MPIEXEC when
M > 1): it must end with exit code 0, say it resumed at the checkpoint's step, and write its
summary (compare_runs.py then compares it with the uninterrupted run). With --again-after-step
K2: the folder resumed on one rank, killed again after step K2 (after its own checkpoint, written
by the run on one rank in the layout of the ranks) and resumed once more on N ranks into
OUT/resumed_again: it must resume from a step after K. With --write-failure, a resume on N ranks
whose next checkpoint cannot be written (a folder in the place of checkpoint.h5.tmp) must stop
every rank within a minute with exit code 1 and one dembridge line naming the file.
Plain python3.
"""
import json
import os
import shutil
import subprocess
import sys


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    args = sys.argv[1:]
    if len(args) < 4:
        fail(__doc__)
    exe, mpiexec, case, out = args[:4]
    rest = args[4:]
    sets, write_np, kill_after, resume_on, again_after, write_failure = [], 2, 0, [], 0, False
    while rest:
        flag = rest.pop(0)
        if flag == "--set":
            sets += ["--set", rest.pop(0)]
        elif flag == "--write":
            write_np = int(rest.pop(0))
        elif flag == "--kill-after-step":
            kill_after = int(rest.pop(0))
        elif flag == "--resume-on":
            resume_on = [int(m) for m in rest.pop(0).split(",")]
        elif flag == "--again-after-step":
            again_after = int(rest.pop(0))
        elif flag == "--write-failure":
            write_failure = True
        else:
            fail("unknown argument " + flag)
    if kill_after <= 0 or not resume_on:
        fail("--kill-after-step and --resume-on are needed")

    def command(np, folder, resume):
        launch = [mpiexec, "-np", str(np), "--oversubscribe"] if np > 1 else []
        where = ["--resume", folder] if resume else ["--output-dir", folder]
        return launch + [exe, "run", case] + sets + where

    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    killed = os.path.join(out, "killed")
    env = dict(os.environ, DEMBRIDGE_TEST_KILL_AFTER_STEP=str(kill_after))
    r = subprocess.run(command(write_np, killed, False), env=env, capture_output=True, text=True,
                       timeout=300)
    if r.returncode in (0, 1):
        fail("the run on %d ranks was to be killed after step %d, exit code %d: %s" %
             (write_np, kill_after, r.returncode, r.stderr))
    if not os.path.isfile(os.path.join(killed, "checkpoint.h5")):
        fail("the killed run left no checkpoint.h5: %s" % os.listdir(killed))
    print("written on %d ranks, killed after step %d" % (write_np, kill_after))

    for np in resume_on:
        folder = os.path.join(out, "resumed_np%d" % np)
        shutil.copytree(killed, folder, symlinks=True)
        r = subprocess.run(command(np, folder, True), capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            fail("the resume on %d rank(s): exit code %d: %s" % (np, r.returncode, r.stderr))
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
        step = summary.get("resumed_from", {}).get("step", 0)
        if not 0 < step <= kill_after < summary["steps"]:
            fail("resumed on %d rank(s) at step %d, killed after %d, ended at %d" %
                 (np, step, kill_after, summary["steps"]))
        print("resumed on %d rank(s) from step %d to step %d" % (np, step, summary["steps"]))

    if again_after:
        folder = os.path.join(out, "resumed_again")
        shutil.copytree(killed, folder, symlinks=True)
        env = dict(os.environ, DEMBRIDGE_TEST_KILL_AFTER_STEP=str(again_after))
        r = subprocess.run(command(1, folder, True), env=env, capture_output=True, text=True,
                           timeout=300)
        if r.returncode != -9:
            fail("the resume on one rank was to be killed after step %d, exit code %d: %s" %
                 (again_after, r.returncode, r.stderr))
        r = subprocess.run(command(write_np, folder, True), capture_output=True, text=True,
                           timeout=300)
        if r.returncode != 0:
            fail("the second resume on %d ranks: exit code %d: %s" %
                 (write_np, r.returncode, r.stderr))
        with open(os.path.join(folder, "summary.json")) as f:
            step = json.load(f).get("resumed_from", {}).get("step", 0)
        if not kill_after < step <= again_after:
            fail("the second resume started at step %d, not after step %d" % (step, kill_after))
        print("resumed on one rank, killed after step %d, resumed on %d ranks from step %d" %
              (again_after, write_np, step))

    if not write_failure:
        return
    # a checkpoint that cannot be written: every rank stops, one line, exit code 1
    folder = os.path.join(out, "write_fails")
    shutil.copytree(killed, folder, symlinks=True)
    os.makedirs(os.path.join(folder, "checkpoint.h5.tmp"))
    r = subprocess.run(command(write_np, folder, True), capture_output=True, text=True,
                       timeout=60)
    lines = [l for l in r.stderr.splitlines() if l.startswith("dembridge")]
    if r.returncode != 1 or len(lines) != 1 or "checkpoint.h5.tmp: cannot create" not in lines[0]:
        fail("a checkpoint that cannot be written: expected exit code 1 and one line naming "
             "checkpoint.h5.tmp, got %d: %s" % (r.returncode, r.stderr))
    print("a failed checkpoint write: %s" % lines[0])


if __name__ == "__main__":
    main()
