#!/usr/bin/env python3
"""A static run on several MPI ranks solved its systems on all of them.

usage: check_static_ranks.py RUN_DIR N

summary.json's solver.method names PETSc's CG on N ranks and the rows of the parallel matrix
(mpiaij) each rank held: N counts, each a positive multiple of 6 (whole particles), adding up to
6 DOFs per particle. A solve left on one rank, or a matrix held whole by each rank, fails.
Prints one line per check; exit code 1 when one fails.
"""
import json
import re
import sys


def main(argv):
    run_dir, n_ranks = argv[1], int(argv[2])
    summary = json.load(open(run_dir + "/summary.json"))
    method = summary["solver"]["method"]
    failed = 0

    def check(ok, text):
        nonlocal failed
        print(("ok: " if ok else "FAILED: ") + text)
        failed += 0 if ok else 1

    m = re.fullmatch(r"PETSc CG\+(GAMG|Jacobi) on (\d+) ranks \(mpiaij rows ([\d +]+)\)", method)
    check(m is not None and int(m.group(2)) == n_ranks,
          "solver.method '%s': PETSc's CG on %d ranks, an mpiaij matrix" % (method, n_ranks))
    if m:
        rows = [int(r) for r in m.group(3).split("+")]
        dofs = 6 * summary["n_particles"]
        check(len(rows) == n_ranks and all(r > 0 and r % 6 == 0 for r in rows),
              "each of the %d ranks holds whole particles' rows: %s" % (n_ranks, rows))
        check(sum(rows) == dofs, "the rows add up to the %d DOFs (%d)" % (dofs, sum(rows)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
