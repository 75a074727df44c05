#!/usr/bin/env python3
"""Kill -9 and resume (issue 11; docs/checkpoint.md).

usage: checkpoint_resume.py DEMBRIDGE CASE OUT [--expect-cracks] [--set KEY=VALUE]...

Runs the case (one thread, with Output/checkpoint interval among the --set) uninterrupted into
OUT/reference, then four runs that die by SIGKILL at different moments and are resumed with
`dembridge run CASE --resume DIR`:
  after_first   the process kills itself a few steps after the first checkpoint
  late          ... at 80 % of the run, long after the last checkpoint (with --expect-cracks:
                after bonds have broken and contacts are active)
  in_write      ... in the middle of writing the second checkpoint (the first one is resumed)
  external      a real `kill -9` from this script once the first checkpoint exists
Every resumed run must end with the reference's files, byte for byte (summary.json without its
timing and provenance keys). Then the refusals, each one line and exit code 1: a checkpoint of
another case, a fresh run into a folder that holds a checkpoint, --resume without one. Without
--expect-cracks also: a resume on two threads completes with the same bonds and E within 1e-6.
Plain python3 (no numpy).
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

# keys that legitimately differ between two runs of the same case
VOLATILE = {"wall_seconds", "solver_seconds", "bond_updates_per_second", "peak_memory_bytes",
            "started_at", "command_line", "host", "resumed_from", "output_files",
            "search_seconds", "contact_seconds", "neighbour_search_seconds",
            "contact_updates_per_second"}


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    args = sys.argv[1:]
    if len(args) < 3:
        fail(__doc__)
    exe, case, out = args[0], args[1], args[2]
    sets, expect_cracks = [], False
    rest = args[3:]
    i = 0
    while i < len(rest):
        if rest[i] == "--set":
            sets += ["--set", rest[i + 1]]
            i += 2
        elif rest[i] == "--expect-cracks":
            expect_cracks = True
            i += 1
        else:
            fail("unknown argument " + rest[i])
    sets += ["--set", "Simulation/threads=1"]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)

    def run(folder, extra=(), env_extra=None, resume=False, threads=None):
        env = dict(os.environ)
        env.update(env_extra or {})
        cmd = [exe, "run", case] + sets + list(extra)
        if threads:
            cmd += ["--set", "Simulation/threads=%d" % threads]
        cmd += ["--resume", folder] if resume else ["--output-dir", folder]
        return subprocess.run(cmd, env=env, capture_output=True, text=True)

    ref = os.path.join(out, "reference")
    r = run(ref)
    if r.returncode != 0:
        fail("reference run failed: " + r.stdout[-2000:] + r.stderr)
    with open(os.path.join(ref, "summary.json")) as f:
        summary = json.load(f)
    if os.path.exists(os.path.join(ref, "checkpoint.h5")):
        fail("a completed run left its checkpoint")
    steps, dt = summary["steps"], summary["time_step"]
    interval = float(summary["parameters"]["Output"]["checkpoint interval"])
    first_checkpoint = int(round(interval / dt))
    if not 0 < first_checkpoint < steps // 3:
        fail("choose a checkpoint interval of at most a third of the run (%d steps, first "
             "checkpoint at step %d)" % (steps, first_checkpoint))
    late = int(0.8 * steps)
    if late % first_checkpoint < first_checkpoint // 4:  # well after a checkpoint, not at one
        late += first_checkpoint // 2
    if expect_cracks:
        if summary.get("n_broken_bonds", 0) < 1 or summary.get("n_contacts", 0) < 1:
            fail("the reference run has no broken bonds or no contacts: %s, %s" %
                 (summary.get("n_broken_bonds"), summary.get("n_contacts")))
        # the last checkpoint before `late` must already hold broken bonds and contacts
        with open(os.path.join(ref, "history.csv")) as f:
            header = f.readline().strip().split(",")
            rows = [dict(zip(header, line.strip().split(","))) for line in f]
        started = [float(row["time"]) for row in rows
                   if float(row["n_broken_bonds"]) > 0 and float(row["n_contacts"]) > 0]
        if not started:
            fail("no history row with broken bonds and active contacts")
        last_checkpoint_time = int(late * dt / interval) * interval
        if last_checkpoint_time <= started[0]:
            fail("the checkpoint before step %d (t = %g s) precedes the first break with contacts "
                 "(t = %g s): lengthen the run" % (late, last_checkpoint_time, started[0]))
        print("bonds break with contacts from t = %g s; resumed from t = %g s" %
              (started[0], last_checkpoint_time))
    print("reference: %d steps, checkpoints every %d steps" % (steps, first_checkpoint))

    def compare(folder):
        names = sorted(os.listdir(ref))
        got = sorted(os.listdir(folder))
        if names != got:
            fail("%s holds %s, the reference %s" % (folder, got, names))
        for name in names:
            a, b = os.path.join(ref, name), os.path.join(folder, name)
            if name == "summary.json":
                with open(a) as f:
                    ja = json.load(f)
                with open(b) as f:
                    jb = json.load(f)
                if "resumed_from" not in jb:
                    fail(folder + "/summary.json does not say it was resumed")
                for k in VOLATILE:
                    ja.pop(k, None)
                    jb.pop(k, None)
                for j in (ja, jb):  # the machine's free memory at the start
                    j.get("memory_estimate", {}).pop("available_bytes", None)
                if ja != jb:
                    diff = [k for k in set(ja) | set(jb) if ja.get(k) != jb.get(k)]
                    fail("%s/summary.json differs from the reference in %s" % (folder, diff))
            else:
                with open(a, "rb") as f:
                    da = f.read()
                with open(b, "rb") as f:
                    db = f.read()
                if da != db:
                    fail("%s/%s differs from the reference (%d vs %d bytes)" %
                         (folder, name, len(db), len(da)))
        print("  %s: %d files identical to the reference" % (os.path.basename(folder), len(names)))

    def killed_then_resumed(name, env_extra=None, external=False):
        folder = os.path.join(out, name)
        if external:
            env = dict(os.environ)
            cmd = [exe, "run", case] + sets + ["--output-dir", folder]
            p = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            checkpoint = os.path.join(folder, "checkpoint.h5")
            while p.poll() is None and not os.path.exists(checkpoint):
                time.sleep(0.001)
            if p.poll() is not None:
                fail("the run ended before its first checkpoint could be killed")
            os.kill(p.pid, signal.SIGKILL)
            p.wait()
            rc = p.returncode
        else:
            rc = run(folder, env_extra=env_extra).returncode
        if rc != -signal.SIGKILL:
            fail("%s: expected death by SIGKILL, got exit status %s" % (name, rc))
        if os.path.exists(os.path.join(folder, "summary.json")):
            fail(name + ": a killed run left a summary.json")
        if not os.path.exists(os.path.join(folder, "checkpoint.h5")):
            fail(name + ": no checkpoint after the kill")
        r = run(folder, resume=True)
        if r.returncode != 0:
            fail("%s: resume failed: %s%s" % (name, r.stdout[-2000:], r.stderr))
        line = [l for l in r.stdout.splitlines() if l.startswith("resumed from")]
        print("  %s: %s" % (name, line[0] if line else "(no 'resumed from' line)"))
        compare(folder)

    killed_then_resumed("after_first", {"DEMBRIDGE_TEST_KILL_AFTER_STEP": str(first_checkpoint + 3)})
    killed_then_resumed("late", {"DEMBRIDGE_TEST_KILL_AFTER_STEP": str(late)})
    killed_then_resumed("in_write", {"DEMBRIDGE_TEST_KILL_IN_CHECKPOINT": "2"})
    killed_then_resumed("external", external=True)

    # refusals: one line, exit code 1
    folder = os.path.join(out, "refusals")

    def refused(r, expected, what):
        lines = r.stderr.strip().splitlines()
        if r.returncode != 1 or len(lines) != 1 or expected not in lines[0]:
            fail("%s: expected exit 1 and one line with '%s', got %s: %s" %
                 (what, expected, r.returncode, r.stderr))
        print("  refused (%s): %s" % (what, lines[0]))

    if run(folder, env_extra={"DEMBRIDGE_TEST_KILL_AFTER_STEP": str(first_checkpoint + 3)}).returncode \
            != -signal.SIGKILL:
        fail("refusals: the run was not killed")
    end_time = summary["parameters"]["Simulation"]["end time"]
    refused(run(folder, ["--set", "Simulation/end time=%s1" % end_time], resume=True),
            "the checkpoint is of another case (%s): Simulation/end time is" %
            os.path.basename(case), "another case")
    refused(run(folder), "holds the checkpoint of an interrupted run (step ",
            "fresh run into a folder with a checkpoint")
    refused(run(os.path.join(out, "empty"), resume=True), "no checkpoint there", "no checkpoint")
    if not expect_cracks:
        refused(run(os.path.join(out, "static"), ["--set", "Simulation/solver=static"]),
                "Output/checkpoint interval: the static solver has no time steps",
                "static solver")
        # another thread count: the bonds are matched by their pairs; not bit for bit
        r = run(folder, resume=True, threads=2)
        if r.returncode != 0:
            fail("resume on two threads failed: " + r.stderr)
        with open(os.path.join(folder, "summary.json")) as f:
            two = json.load(f)
        e_ref, e_two = summary["youngs_modulus"], two["youngs_modulus"]
        if two["n_bonds"] != summary["n_bonds"] or abs(e_two - e_ref) > 1e-6 * abs(e_ref):
            fail("two threads: E %r vs %r" % (e_two, e_ref))
        print("  two threads after resume: E %.12g vs %.12g" % (e_two, e_ref))
    print("ok")


if __name__ == "__main__":
    main()
