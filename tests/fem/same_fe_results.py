#!/usr/bin/python3
"""same_fe_results.py A/summary.json B/summary.json: the FE results of two runs are the same bits
(strain energy, reactions, point-group displacements, stress slabs, DoFs). Used to show that the
case file `dembridge verify` writes (fem/case.prm) is the model it ran: rerun, same results."""
import json
import sys

KEYS = ("n_dofs", "strain_energy", "reactions", "mean_displacements", "stress_layers",
        "reaction_force", "youngs_modulus", "elongation")
a, b = (json.load(open(f)) for f in sys.argv[1:3])
checked = [k for k in KEYS if k in a or k in b]
bad = [k for k in checked if a.get(k) != b.get(k)]
for k in bad:
    print(f"FAIL {k}: {a.get(k)!r} vs {b.get(k)!r}")
print(f"{len(checked) - len(bad)} of {len(checked)} results equal: {', '.join(checked)}")
sys.exit(1 if bad or len(checked) < 3 else 0)
