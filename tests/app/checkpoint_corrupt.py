#!/usr/bin/env python3
"""A damaged checkpoint is refused, never resumed into another result (docs/checkpoint.md).

usage: checkpoint_corrupt.py DEMBRIDGE LAYOUT CASE OUT [--set KEY=VALUE]...

Runs the case (one thread, with Output/checkpoint interval among the --set) uninterrupted into
OUT/reference and once killed (SIGKILL) a few steps after its first checkpoint. Then, for 256
seeded random bytes written at 10 %, 30 %, 50 %, 70 % and 90 % of a copy of that checkpoint,
resumes the copy. The resume must be refused with exit code 1 and one line naming the checkpoint
by its full path (and the dataset, when the damaged bytes lie inside the data of one: LAYOUT,
checkpoint_layout.cc, says where each dataset's data lie), leaving every file of the folder
(the staged ones in .partial too) as it was; or, where the bytes hit nothing a resume reads, the
resumed run must end with the reference's files. Never a silent other result.
Plain python3 (no numpy, no h5py).
"""
import json
import os
import random
import shutil
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checkpoint_resume import compare_folders, fail, folder_state  # noqa: E402

DAMAGE_AT = [(0.1, 1), (0.3, 2), (0.5, 3), (0.7, 4), (0.9, 5)]  # (fraction of the file, seed)
DAMAGE_BYTES = 256


def main():
    args = sys.argv[1:]
    if len(args) < 4:
        fail(__doc__)
    exe, layout, case, out = args[0], args[1], args[2], os.path.abspath(args[3])
    sets = args[4:] + ["--set", "Simulation/threads=1"]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)

    def run(folder, env_extra=None, resume=False):
        env = dict(os.environ)
        env.update(env_extra or {})
        cmd = [exe, "run", case] + sets + (["--resume", folder] if resume
                                           else ["--output-dir", folder])
        return subprocess.run(cmd, env=env, capture_output=True, text=True)

    ref = os.path.join(out, "reference")
    r = run(ref)
    if r.returncode != 0:
        fail("reference run failed: " + r.stdout[-2000:] + r.stderr)
    with open(os.path.join(ref, "summary.json")) as f:
        summary = json.load(f)
    interval = float(summary["parameters"]["Output"]["checkpoint interval"])
    first_checkpoint = int(round(interval / summary["time_step"]))
    killed = os.path.join(out, "killed")
    r = run(killed, {"DEMBRIDGE_TEST_KILL_AFTER_STEP": str(first_checkpoint + 3)})
    checkpoint = os.path.join(killed, "checkpoint.h5")
    if r.returncode != -signal.SIGKILL or not os.path.exists(checkpoint):
        fail("the run was not killed after its first checkpoint: %s %s" % (r.returncode, r.stderr))
    size = os.path.getsize(checkpoint)
    extents = []  # (first byte, length, dataset) of each dataset's data
    for line in subprocess.run([layout, checkpoint], capture_output=True, text=True,
                               check=True).stdout.splitlines():
        offset, length, path = line.split(" ", 2)
        extents.append((int(offset), int(length), path))
    covered = sum(length for _, length, _ in extents)
    print("checkpoint of step %d: %d bytes, %d datasets with data (%.0f %% of the file)" %
          (first_checkpoint, size, len(extents), 100.0 * covered / size))

    refusals = harmless = 0
    for fraction, seed in DAMAGE_AT:
        name = "damaged_%02d" % int(100 * fraction)
        folder = os.path.join(out, name)
        shutil.copytree(killed, folder)
        damaged = os.path.join(folder, "checkpoint.h5")
        offset = int(fraction * size)
        damage = random.Random(seed).randbytes(DAMAGE_BYTES)
        with open(damaged, "r+b") as f:
            f.seek(offset)
            f.write(damage[:size - offset])
        end = min(offset + DAMAGE_BYTES, size)
        inside = [path for first, length, path in extents
                  if first <= offset and end <= first + length]
        before = folder_state(folder)
        r = run(folder, resume=True)
        lines = r.stderr.strip().splitlines()
        where = "%s (bytes %d-%d%s)" % (name, offset, end - 1,
                                       ", inside " + inside[0] if inside else "")
        if r.returncode == 0:
            harmless += 1
            print("  %s: resumed; the bytes hit nothing a resume reads" % where)
            compare_folders(ref, folder)
            continue
        if r.returncode != 1 or len(lines) != 1:
            fail("%s: expected a refusal (exit 1, one line) or a resume, got %s: %s%s" %
                 (where, r.returncode, r.stdout[-1000:], r.stderr))
        if damaged + ": " not in lines[0]:
            fail("%s: the refusal does not name %s: %s" % (where, damaged, lines[0]))
        if inside and damaged + ": " + inside[0] + ": damaged" not in lines[0]:
            fail("%s: the refusal does not name the dataset %s: %s" % (where, inside[0], lines[0]))
        if folder_state(folder) != before:
            fail("%s: the refused resume changed the files of its folder" % where)
        refusals += 1
        print("  %s: refused: %s" % (where, lines[0]))
    print("%d refused, %d harmless" % (refusals, harmless))
    print("ok")


if __name__ == "__main__":
    main()
