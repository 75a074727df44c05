#!/usr/bin/python3
"""Where a coupled run's particle region stepped (docs/parallel.md, "Coupled runs on N ranks"):
summary.json's particle_region_steps_on and mpi_ranks as expected, and a reason named exactly
when the particles stayed on rank 0 under mpirun.

    check_particle_layout.py SUMMARY LAYOUT RANKS    (LAYOUT: ranks, "rank 0", "one process")
"""
import json
import sys


def main(argv):
    summary, layout, ranks = argv[1], argv[2], int(argv[3])
    s = json.load(open(summary))
    failures = []
    if s.get("particle_region_steps_on") != layout:
        failures.append("particle_region_steps_on: %r, expected %r"
                        % (s.get("particle_region_steps_on"), layout))
    if s.get("mpi_ranks") != ranks:
        failures.append("mpi_ranks: %r, expected %d" % (s.get("mpi_ranks"), ranks))
    reason = s.get("particle_region_on_rank0_because", "")
    if (layout == "rank 0") != bool(reason):
        failures.append("particle_region_on_rank0_because: %r with the particles on %r"
                        % (reason, layout))
    for f in failures:
        print("FAILED: " + f)
    if not failures:
        print("ok: %s: the particle region stepped on %s (%d ranks)%s"
              % (summary, layout, ranks, "; " + reason if reason else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
