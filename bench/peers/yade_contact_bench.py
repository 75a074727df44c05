# YADE peer benchmark for dembridge: contact-update throughput on the packing of the compression
# benchmark (bench/damage_bench.py), the same set-up as bench/contacts_box.prm.
#
# Run headless (thread count from YADE's -j option):
#   yade -j1 -n -x bench/peers/yade_contact_bench.py --packing PACKING.csv --dt DT --density RHO
#        [--steps 300] [--kn 3.14e7] [--friction 0.5] [--damping 0.7] [--velocity 0.05]
#        [--timing-steps 30] [--json-out FILE]
#
# The spheres of PACKING.csv (dembridge's particle file: x, y, z, r, '#' comments) sit in a box of
# six rigid walls laid onto them (utils.wall at the packing's extent, as dembridge's
# 'touch = true'); the x+ wall moves in at --velocity, the others stay. Contacts: FrictMat /
# Ip2_FrictMat_FrictMat_FrictPhys / Law2_ScGeom_FrictPhys_CundallStrack (linear normal spring,
# incremental tangential spring with Coulomb friction, no viscous damping), found by
# InsertionSortCollider with YADE's default verletDist (-0.5: half the smallest radius);
# NewtonIntegrator with local damping --damping (Cundall's, as dembridge's particle damping) and
# no gravity; the time step is dembridge's (--dt), not YADE's own estimate.
# Stiffness: FrictPhys gives k_n = 2 E R1 R2 / (R1 + R2) (= E R for equal spheres), so
# young = k_n / R reproduces dembridge's k_n between equal spheres; k_t / k_n is YADE's `poisson`
# (2/7, dembridge's default). Ig2_Wall_Sphere_ScGeom gives the wall the sphere's radius, so a
# sphere-wall contact has the same k_n = E R, as in dembridge.
#
# Timed: O.run(steps, True) after two warm-up steps, wall (perf_counter) and CPU time (process).
# Contacts: the real interactions (O.interactions.countReal()) sampled every 10 steps by a
# PyRunner; contact_updates = their mean x steps, as dembridge counts the touching pairs and
# sphere-wall contacts it evaluates each step. A separate window (--timing-steps) with
# O.timingEnabled gives each engine's share of the step; the collider's is the neighbour search.
import argparse
import json
import math
import os
import sys
import time

import yade
from yade import O, utils
from yade.wrapper import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat,
                          Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom, InsertionSortCollider,
                          InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                          Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, PyRunner)

ap = argparse.ArgumentParser()
ap.add_argument("--packing", required=True)
ap.add_argument("--dt", type=float, required=True, help="time step (s): dembridge's")
ap.add_argument("--density", type=float, required=True, help="particle density (kg/m^3)")
ap.add_argument("--steps", type=int, default=300)
ap.add_argument("--kn", type=float, default=3.14e7, help="normal stiffness between equal spheres")
ap.add_argument("--kt-ratio", type=float, default=2.0 / 7.0)
ap.add_argument("--friction", type=float, default=0.5)
ap.add_argument("--damping", type=float, default=0.7)
ap.add_argument("--velocity", type=float, default=0.05, help="x+ platen speed (m/s)")
ap.add_argument("--timing-steps", type=int, default=30)
ap.add_argument("--json-out", default=None)
args = ap.parse_args(sys.argv[1:])

load_start = os.getloadavg()[0]
t_setup0 = time.perf_counter()
spheres = []
with open(args.packing) as f:
    for line in f:
        line = line.strip()
        if line and not line.startswith("#"):
            spheres.append(tuple(float(v) for v in line.split(",")))
radius = min(s[3] for s in spheres)
lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]

mat = O.materials.append(FrictMat(young=args.kn / radius, poisson=args.kt_ratio,
                                  frictionAngle=math.atan(args.friction), density=args.density))
O.bodies.append([utils.sphere(s[:3], s[3], material=mat) for s in spheres])
walls = {}
for axis in range(3):
    walls[(axis, 1)] = O.bodies.append(utils.wall(lo[axis], axis=axis, sense=1, material=mat))
    walls[(axis, -1)] = O.bodies.append(utils.wall(hi[axis], axis=axis, sense=-1, material=mat))
platen = O.bodies[walls[(0, -1)]]
platen.state.vel = (-args.velocity, 0, 0)  # a fixed body moves at its prescribed velocity

collider = InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()])
O.engines = [
    ForceResetter(),
    collider,
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=args.damping, gravity=(0, 0, 0)),
    PyRunner(iterPeriod=10, command="sample()"),
]
O.dt = args.dt
samples = []


def sample():
    samples.append(O.interactions.countReal())


O.run(2, True)  # warm-up: the collider's first sort, the interactions' first geometry
n_particles = len(spheres)
t_setup = time.perf_counter() - t_setup0

samples.clear()
collider_runs0 = collider.numAction
O.timingEnabled = False
t0, c0 = time.perf_counter(), time.process_time()
O.run(args.steps, True)
wall = time.perf_counter() - t0
cpu = time.process_time() - c0
collider_runs = collider.numAction - collider_runs0
mean_contacts = sum(samples) / max(len(samples), 1)
contact_updates = mean_contacts * args.steps

breakdown = None
if args.timing_steps > 0:
    O.timingEnabled = True
    for e in O.engines:
        e.execTime = 0
        e.execCount = 0
    O.run(args.timing_steps, True)
    total = sum(e.execTime for e in O.engines) or 1
    breakdown = {e.__class__.__name__: round(100.0 * e.execTime / total, 1) for e in O.engines}
    O.timingEnabled = False

platen_force = O.forces.f(platen.id)
result = {
    "tool": "yade",
    "case": "contacts_box",
    "command": "yade -j%d -n -x %s" % (O.numThreads, " ".join([sys.argv[0]] + sys.argv[1:])),
    "yade_version": yade.config.version,
    "threads": O.numThreads,
    "n_particles": n_particles,
    "steps": args.steps,
    "dt_s": O.dt,
    "wall_seconds": round(wall, 4),
    "cpu_seconds": round(cpu, 4),
    "mean_contacts": mean_contacts,
    "contacts_first_last": [samples[0], samples[-1]] if samples else None,
    "contact_updates": contact_updates,
    "contact_updates_per_second": contact_updates / wall,
    "contact_updates_per_cpu_second": contact_updates / cpu if cpu > 0 else None,
    "particle_steps_per_second": n_particles * args.steps / wall,
    "ms_per_step": 1e3 * wall / args.steps,
    "collider": "InsertionSortCollider verletDist=%g" % collider.verletDist,
    "collider_runs_in_timed_window": collider_runs,
    "neighbour_search_share": (breakdown or {}).get("InsertionSortCollider", 0) / 100.0
    if breakdown else None,
    "timing_breakdown_percent": breakdown,
    "platen_force_N": list(platen_force),
    "setup_seconds": round(t_setup, 2),
    "nproc": os.cpu_count(),
    "loadavg_1min_at_start": load_start,
    "loadavg_1min_at_end": os.getloadavg()[0],
}
print(json.dumps(result), flush=True)
if args.json_out:
    with open(args.json_out, "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
