#!/usr/bin/python3
"""Full-DEM specimen study of the thesis (sections 4-5, Table 1): runs the simulation matrix
packings x radii x bond models x tests (x random seeds) on the example cases through the Python
module (dembridge.run, docs/python.md: the library `dembridge run` is built on, in this process),
collects every run's summary into results.csv and draws the thesis' Figures 29-35.

    /usr/bin/python3 scripts/study.py                         # the whole Table 1 matrix, static
    /usr/bin/python3 scripts/study.py --packings random --radii 5,7.5 --seeds 1-3 \\
        --models pbm --tests compression --solver static,explicit --jobs 2 --out study

Matrix (thesis Table 1): packings cubic (the thesis' "uniform"), hcp, random; radii 2.5, 5,
7.5, 10, 12.5 mm; bond models pbm (parallel bond, thesis calibration k̄_n = E_b/(2 r),
k̄_n/k̄_s = 4.2) and tbbm (Timoshenko beam); tests tension, compression, bending; 5 random
packings (seeds 1-5) per radius. As in the thesis, TBBM bending at r = 2.5 mm is left out
(Table 1: 0 runs) unless --full is given. Any other radius or seed may be asked for.

Runs. Each run is dembridge.run(example, output_dir, set=[...]): the example case with the
overrides below, the same files and figures as `dembridge run EXAMPLE --set ...` (its
summary.json records that command line); what the library prints goes to the run's
dembridge.log. The module is the one of the build that --dembridge names (BUILD/app/dembridge:
BUILD/python). --jobs N runs N specimens at a time in N worker processes (started with
'spawn': each imports the module afresh; a run changes the working directory of its process,
so runs never share one).

Specimens. Each (packing, radius, seed) is generated once by dembridge (the compression example
with `Particles/save file`, end time 0) and stored in OUT/specimens/; every test and bond model
of that specimen reads it back (`Particles/source = file`), as the thesis loaded each packing in
all three tests. Spheres that would not be bonded to the specimen's main bonded cluster (the
rare rattlers of a random packing, which carry no load) are dropped from the stored specimen,
so that the static solver never meets a support or load on a sphere without stiffness.
Porosity (`specimen_porosity`) = 1 - sum of sphere volumes / volume of the specimen's extent
(the bounding box of the spheres, as the thesis' Table 2 reports the HCP dimensions).

Supports. Uniaxial tests: the end groups of the example (spheres within 1.5 r of the end
faces; x- held in x, x+ moved in x), plus exactly three constraints for the rigid-body modes
the ends leave free: the sphere nearest the corner (x-, y-, z-) held in y and z (group
`corner`), the sphere nearest (x-, y+, z-) held in z (group `corner_y`). Statically
determinate: their reactions are zero and the result does not depend on the spheres chosen.
Bending: pin (x-) and roller (x+) are the spheres within 1.5 r of the bottom corner edges, the
1 kN load is shared by the top spheres within 1.5 r of midspan, the deflection averages those
and the bottom midspan spheres (examples/bending_*.prm); the boxes are recomputed from each
specimen's extent. The flexural Poisson's ratio (eq. 67, 69) is the mean of nu_xy and nu_xz
of the same specimen's compression run when there is one.

Resumable: a run whose summary.json exists is skipped; dembridge writes summary.json last, so
an interrupted run has none and is run again. results.csv and the plots are rebuilt from every
run found under OUT/runs at the end (also with --report-only).
Requires numpy and matplotlib (Debian: /usr/bin/python3); nothing else beyond the stdlib.
"""
import argparse
import concurrent.futures
import contextlib
import csv
import ctypes
import importlib
import json
import math
import multiprocessing
import os
import re
import shutil
import sys
import threading
import time
from pathlib import Path

import numpy as np

from study_specimens import bonded_pairs, largest_cluster

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
PACKINGS = ("cubic", "hcp", "random")
RADII_MM = (2.5, 5.0, 7.5, 10.0, 12.5)
MODELS = {"pbm": "parallel_bond", "tbbm": "timoshenko"}
TESTS = ("tension", "compression", "bending")
SEEDS = (1, 2, 3, 4, 5)
BOX = (0.25, 0.1, 0.1)
HCP_IDEAL_POROSITY = 1 - math.pi / (3 * math.sqrt(2))  # 0.25952
RCP_MIN_POROSITY = 0.363  # Torquato et al. (2000), thesis section 5.1


class StudyError(Exception):
    pass


# ----------------------------------------------------------------------------- matrix


def parse_list(text, conv, allowed=None, name=""):
    out = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        if conv is int and re.fullmatch(r"\d+-\d+", part):
            a, b = (int(v) for v in part.split("-"))
            out.extend(range(a, b + 1))
            continue
        try:
            v = conv(part)
        except ValueError:
            raise StudyError(f"--{name}: cannot read '{part}'")
        if allowed is not None and v not in allowed:
            raise StudyError(f"--{name}: unknown '{part}' (expected one of {', '.join(allowed)})")
        out.append(v)
    if not out:
        raise StudyError(f"--{name}: empty list")
    return list(dict.fromkeys(out))


def rtag(radius_mm):
    return f"{radius_mm:g}".replace(".", "p")


def specimen_name(packing, radius_mm, seed):
    return f"{packing}_r{rtag(radius_mm)}mm" + (f"_s{seed}" if packing == "random" else "")


def build_matrix(a):
    runs = []
    for packing in a.packings:
        for radius in a.radii:
            for seed in a.seeds if packing == "random" else [None]:
                for model in a.models:
                    for test in a.tests:
                        if test == "bending" and model == "tbbm" and radius < 3 and not a.full:
                            continue  # thesis Table 1: no TBBM flexural runs at r = 2.5 mm
                        for solver in a.solver:
                            runs.append(dict(packing=packing, radius_mm=radius, seed=seed,
                                             model=model, test=test, solver=solver))
    # compression before tension before bending within a specimen: bending takes its
    # Poisson's ratio from the compression run
    order = {t: i for i, t in enumerate(("compression", "tension", "bending"))}
    runs.sort(key=lambda r: (specimen_name(r["packing"], r["radius_mm"], r["seed"]),
                             order[r["test"]], r["model"], r["solver"]))
    return runs


def run_name(r):
    return (specimen_name(r["packing"], r["radius_mm"], r["seed"]) +
            f"_{r['model']}_{r['test']}_{r['solver']}")


# ----------------------------------------------------------------------------- examples


def example_for(test, packing):
    """The example case a run starts from (overridden on the command line)."""
    kind = "compression" if test in ("compression", "tension") else "bending"
    for name in ([f"{test}_{packing}.prm"] if test == "tension" else []) + \
            [f"{kind}_{packing}.prm", f"{kind}_random.prm", f"{kind}_cubic.prm"]:
        if (EXAMPLES / name).exists():
            return EXAMPLES / name
    raise StudyError(f"no example case for {test} of {packing} in {EXAMPLES}")


def prm_value(path, key):
    """Value of 'set KEY = VALUE' in a .prm file (first occurrence), or None."""
    pat = re.compile(r"^\s*set\s+" + re.escape(key) + r"\s*=\s*(.*?)\s*(#.*)?$")
    for line in Path(path).read_text().splitlines():
        m = pat.match(line)
        if m:
            return m.group(1)
    return None


def load_name(path):
    text = Path(path).read_text()
    m = re.search(r"subsection\s+Loads\s*\n\s*set\s+names\s*=\s*([^\n#]+)", text)
    if not m:
        raise StudyError(f"{path}: no 'subsection Loads' with names")
    return m.group(1).split(",")[0].strip()


def contact_multiplier(packing):
    v = prm_value(example_for("compression", packing), "contact radius multiplier")
    return float(v) if v is not None else 1.0


# ----------------------------------------------------------------------------- specimens


def write_atomic(path, text):
    tmp = Path(str(path) + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def read_packing(path):
    a = np.loadtxt(path, delimiter=",", comments="#", ndmin=2)
    if a.shape[1] != 4 or len(a) == 0:
        raise StudyError(f"{path}: not a particle file 'x, y, z, r'")
    return a[:, :3].copy(), a[:, 3].copy()


def module_folder(exe):
    """The folder holding the Python package of the build that made `exe` (BUILD/app/dembridge:
    BUILD/python)."""
    folder = Path(exe).resolve().parent.parent / "python"
    if not (folder / "dembridge" / "__init__.py").exists():
        raise StudyError(f"the dembridge Python module of {exe} was not found (looked for "
                         f"{folder / 'dembridge'}); build it (the _dembridge target)")
    return folder


def import_dembridge(exe):
    """The dembridge module of `exe`'s build (module_folder), imported once per process."""
    folder = module_folder(exe)
    if str(folder) not in sys.path:
        sys.path.insert(0, str(folder))
    try:
        return importlib.import_module("dembridge")
    except ImportError as e:
        raise StudyError(f"the dembridge Python module does not import: {e}")


@contextlib.contextmanager
def output_into(log):
    """The process' standard output and error (the library's C and C++ streams among them) go
    to the open file `log` while the block runs."""
    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    sys.stderr.flush()
    libc.fflush(None)
    log.flush()
    saved = os.dup(1), os.dup(2)
    try:
        os.dup2(log.fileno(), 1)
        os.dup2(log.fileno(), 2)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        libc.fflush(None)
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])


class Runner:
    def __init__(self, exe, out, verbose=False, extra_sets=()):
        self.exe = exe
        self.module = None  # imported at the first run (a spawned worker imports its own)
        self.out = Path(out).resolve()
        self.verbose = verbose
        self.extra_sets = list(extra_sets)
        self.lock = threading.Lock()
        self.spec_locks = {}
        (self.out / "specimens").mkdir(parents=True, exist_ok=True)
        (self.out / "runs").mkdir(parents=True, exist_ok=True)

    def log(self, msg):
        with self.lock:
            print(msg, flush=True)

    def dembridge(self, case, outdir, sets, logfile):
        """dembridge.run(case, outdir, sets): `dembridge run CASE --output-dir OUTDIR --set ...`
        in this process, its output in `logfile`."""
        if self.module is None:
            self.module = import_dembridge(self.exe)
        sets = list(sets) + self.extra_sets
        with open(logfile, "w") as log:
            log.write(f"dembridge.run({str(case)!r}, output_dir={str(outdir)!r}, set={sets!r})\n")
            try:
                with output_into(log):
                    self.module.run(case, output_dir=outdir, set=sets)
            except self.module.CaseError as e:
                log.write(f"dembridge: error: {e}\n")
                raise StudyError(f"dembridge failed ({logfile}): {e}")

    # -- specimen: generate once, drop spheres outside the main bonded cluster, derive groups
    def specimen(self, packing, radius_mm, seed):
        name = specimen_name(packing, radius_mm, seed)
        with self.lock:
            lock = self.spec_locks.setdefault(name, threading.Lock())
        with lock:
            info_path = self.out / "specimens" / f"{name}.json"
            if info_path.exists():
                return json.loads(info_path.read_text())
            r = radius_mm / 1000.0
            raw = self.out / "specimens" / f"{name}.generated.csv"
            csv_path = self.out / "specimens" / f"{name}.csv"
            gen_dir = self.out / "specimens" / f"{name}.generate"
            t0 = time.time()
            if not raw.exists():
                sets = [f"Particles/radius={r!r}", f"Particles/save file={raw}",
                        "Simulation/solver=explicit", "Simulation/end time=0",
                        "Output/write vtu=false"]
                if packing == "random":
                    sets.append(f"Particles/seed={seed}")
                # the example's corner spheres are right for r = 5 mm only; any valid index
                # will do here (nothing is solved at end time 0)
                sets += ["Group corner/select=index", "Group corner/indices=0",
                         "Group corner_y/select=index", "Group corner_y/indices=-1"]
                self.dembridge(example_for("compression", packing), gen_dir, sets,
                               self.out / "specimens" / f"{name}.generate.log")
                shutil.rmtree(gen_dir, ignore_errors=True)
            x, rad = read_packing(raw)
            eta = contact_multiplier(packing)
            I, J = bonded_pairs(x, rad, eta)
            keep = largest_cluster(len(x), I, J)
            x, rad = x[keep], rad[keep]
            lines = [f"# dembridge specimen {name}: {len(x)} spheres ({int((~keep).sum())} "
                     "outside the main bonded cluster dropped)", "# x, y, z, r"]
            lines += ["%.17g, %.17g, %.17g, %.17g" % (*p, q) for p, q in zip(x, rad)]
            write_atomic(csv_path, "\n".join(lines) + "\n")
            lo = (x - rad[:, None]).min(axis=0)
            hi = (x + rad[:, None]).max(axis=0)
            solid = float((4.0 / 3.0 * math.pi * rad ** 3).sum())
            info = dict(name=name, packing=packing, radius_mm=radius_mm, seed=seed,
                        file=str(csv_path), n_particles=int(len(x)),
                        n_dropped=int((~keep).sum()), contact_radius_multiplier=eta,
                        extent_min=lo.tolist(), extent_max=hi.tolist(),
                        porosity=1.0 - solid / float(np.prod(hi - lo)),
                        porosity_box=1.0 - solid / float(np.prod(BOX)),
                        generate_seconds=round(time.time() - t0, 3))
            # bonds inside the kept cluster (all bonds of kept spheres are inside it)
            kept_bonds = int(np.count_nonzero(keep[I]))
            info["mean_coordination"] = 2.0 * kept_bonds / len(x)
            info["groups"] = self.groups(x, rad, lo, hi)
            write_atomic(info_path, json.dumps(info, indent=1))
            self.log(f"  specimen {name}: {len(x)} spheres, porosity {info['porosity']:.4f}, "
                     f"coordination {info['mean_coordination']:.2f}"
                     + (f", {info['n_dropped']} unbonded dropped" if info["n_dropped"] else "")
                     + f" ({info['generate_seconds']:.1f} s)")
            return info

    @staticmethod
    def groups(x, rad, lo, hi):
        r = float(rad.max())
        tol = 1e-6 * r
        band = 1.5 * r + tol  # "within 1.5 r" of a face, as the face groups select

        def nearest(target):
            return int(np.argmin(((x - np.array(target)) ** 2).sum(axis=1)))

        corner = nearest(lo)
        corner_y = nearest([lo[0], hi[1], lo[2]])
        if abs(x[corner_y, 1] - x[corner, 1]) < 0.25 * (hi[1] - lo[1]):
            raise StudyError("corner spheres too close in y to hold the rotation about x")
        mid = 0.5 * (lo[0] + hi[0])
        # box limits on the centres: face bands at 1.5 r (centre within 1.5 r of the surface)
        xb0, xb1 = lo[0] + band, hi[0] - band
        zb0, zb1 = lo[2] + band, hi[2] - band
        boxes = {
            "pin": ([lo[0] - tol, lo[1] - tol, lo[2] - tol], [xb0, hi[1] + tol, zb0]),
            "roller": ([xb1, lo[1] - tol, lo[2] - tol], [hi[0] + tol, hi[1] + tol, zb0]),
            "loaded": ([mid - band, lo[1] - tol, zb1], [mid + band, hi[1] + tol, hi[2] + tol]),
            "bottom": ([mid - band, lo[1] - tol, lo[2] - tol], [mid + band, hi[1] + tol, zb0]),
        }
        # box min/max of a box group compare centres; the centre of a sphere touching a face
        # is r inside it, so the bands are measured from the extent (surface), as above
        for g, (a, b) in boxes.items():
            inside = np.all((x >= np.array(a)) & (x <= np.array(b)), axis=1)
            if not inside.any():
                raise StudyError(f"bending group {g} would be empty")
        return dict(corner=corner, corner_y=corner_y,
                    boxes={g: [list(map(float, a)), list(map(float, b))]
                           for g, (a, b) in boxes.items()})

    # -- one run
    def run(self, spec, r, poisson=None):
        name = run_name(r)
        rdir = self.out / "runs" / name
        summary = rdir / "summary.json"
        if summary.exists():
            return "skipped", 0.0
        rdir.mkdir(parents=True, exist_ok=True)
        for f in rdir.iterdir():  # leftovers of an interrupted run
            if f.is_file():
                f.unlink()
        case = example_for(r["test"], r["packing"])
        sets = ["Particles/source=file", f"Particles/file={spec['file']}",
                f"Bonds/model={MODELS[r['model']]}",
                f"Bonds/contact radius multiplier={spec['contact_radius_multiplier']!r}",
                f"Simulation/solver={r['solver']}", "Output/write vtu=false"]
        g = spec["groups"]
        if r["test"] in ("compression", "tension"):
            sets += ["Group corner/select=index", f"Group corner/indices={g['corner']}",
                     "Group corner_y/select=index", f"Group corner_y/indices={g['corner_y']}"]
            value = prm_value(case, "value")
            v = abs(float(value.split(",")[0]))
            sign = -1 if r["test"] == "compression" else 1
            sets.append(f"Load {load_name(case)}/value={sign * v!r}, 0, 0")
        else:
            for gname, (a, b) in g["boxes"].items():
                sets += [f"Group {gname}/select=box",
                         f"Group {gname}/box min={a[0]!r}, {a[1]!r}, {a[2]!r}",
                         f"Group {gname}/box max={b[0]!r}, {b[1]!r}, {b[2]!r}"]
            if poisson is not None:
                sets.append(f"Measurements/flexural poisson ratio={poisson!r}")
        meta = dict(r, run=name, specimen=spec["name"], case=str(case.relative_to(ROOT)),
                    specimen_porosity=spec["porosity"],
                    specimen_porosity_box=spec["porosity_box"],
                    specimen_particles=spec["n_particles"],
                    specimen_dropped=spec["n_dropped"],
                    contact_radius_multiplier=spec["contact_radius_multiplier"],
                    flexural_poisson_ratio=poisson)
        write_atomic(rdir / "run.json", json.dumps(meta, indent=1))
        t0 = time.time()
        self.dembridge(case, rdir, sets, rdir / "dembridge.log")
        return "ran", time.time() - t0


def poisson_for_bending(out, r):
    """Mean of nu_xy, nu_xz of the same specimen's compression run (same model, same solver;
    else the other solver), or None (the example's value is used)."""
    for solver in (r["solver"], "static", "explicit"):
        c = dict(r, test="compression", solver=solver)
        s = Path(out) / "runs" / run_name(c) / "summary.json"
        if s.exists():
            j = json.loads(s.read_text())
            if "poisson_ratio_xy" in j and "poisson_ratio_xz" in j:
                return 0.5 * (j["poisson_ratio_xy"] + j["poisson_ratio_xz"])
    return None


def headline(r, summary):
    if r["test"] == "bending":
        v = summary.get("flexural_modulus")
        return f"E_f = {v / 1e9:.4f} GPa" if v is not None else ""
    e = summary.get("youngs_modulus")
    txt = f"E = {e / 1e9:.4f} GPa" if e is not None else ""
    if "poisson_ratio_xy" in summary:
        txt += f", nu_xy = {summary['poisson_ratio_xy']:.3f}, nu_xz = {summary['poisson_ratio_xz']:.3f}"
    return txt


def run_specimen(runner, items, report):
    """The runs of one specimen, in order (bending after compression); report(run name, message
    or None, error or None) after each. Returns the failures [(run name, error)]."""
    r0 = items[0]
    failures = []
    try:
        spec = runner.specimen(r0["packing"], r0["radius_mm"], r0["seed"])
    except (StudyError, OSError) as e:
        runner.log(f"FAILED specimen {specimen_name(r0['packing'], r0['radius_mm'], r0['seed'])}: {e}")
        for r in items:
            failures.append((run_name(r), str(e)))
            report(run_name(r), None, str(e))
        return failures
    for r in items:
        poisson = None
        if r["test"] == "bending":
            poisson = poisson_for_bending(runner.out, r)
            if poisson is None and r["packing"] == "cubic":
                poisson = 0.0
        try:
            status, secs = runner.run(spec, r, poisson)
            if status == "ran":
                s = json.loads((runner.out / "runs" / run_name(r) / "summary.json").read_text())
                report(run_name(r), f"{secs:.1f} s  {headline(r, s)}", None)
            else:
                report(run_name(r), "done before, skipped", None)
        except (StudyError, OSError, ValueError) as e:
            failures.append((run_name(r), str(e)))
            report(run_name(r), None, str(e))
    return failures


WORKER = {}


def start_worker(exe, out, extra_sets):
    """A spawned worker process: its own Runner and module."""
    WORKER["runner"] = Runner(exe, out, extra_sets=extra_sets)
    WORKER["runner"].module = import_dembridge(exe)


def worker_specimen(items):
    """run_specimen in a worker; the reports and failures go back to the study's process."""
    reports = []
    failures = run_specimen(WORKER["runner"], items,
                            lambda *report: reports.append((*report, time.time())))
    return reports, failures


def execute(runner, runs, jobs):
    """Runs grouped by specimen (bending after compression); with jobs > 1 that many specimens
    at a time, each in a worker process started with 'spawn' (a fresh interpreter: the module's
    MPI and working directory are its own, nothing is forked mid-run)."""
    by_spec = {}
    for r in runs:
        by_spec.setdefault(specimen_name(r["packing"], r["radius_mm"], r["seed"]), []).append(r)
    total = len(runs)
    done = [0]
    t_start = time.time()

    def report(name, message, error, when=None):
        done[0] += 1
        el = (when or time.time()) - t_start
        runner.log(f"[{done[0]}/{total}] {name}: {message if error is None else 'FAILED: ' + error}"
                   f"  (elapsed {el:.0f} s)")

    failures = []
    if jobs <= 1 or len(by_spec) == 1:
        for items in by_spec.values():
            failures += run_specimen(runner, items, report)
        return failures
    spawn = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(
            max_workers=jobs, mp_context=spawn, initializer=start_worker,
            initargs=(runner.exe, runner.out, runner.extra_sets)) as pool:
        pending = {pool.submit(worker_specimen, items): items for items in by_spec.values()}
        for future in concurrent.futures.as_completed(pending):
            try:
                reports, failed = future.result()
            except concurrent.futures.process.BrokenProcessPool as e:
                # a worker died (killed, or the library aborted): its runs have no summary.json
                # and run again next time
                reports = [(run_name(r), None, f"worker process died: {e}", None)
                           for r in pending[future]]
                failed = [(name, error) for name, _, error, _ in reports]
            for name, message, error, when in reports:
                report(name, message, error, when)
            failures += failed
    return failures


# ----------------------------------------------------------------------------- results


def flatten(prefix, v, out):
    if isinstance(v, dict):
        for k, w in v.items():
            flatten(f"{prefix}.{k}" if prefix else k, w, out)
    elif isinstance(v, list):
        if len(v) <= 64:
            for i, w in enumerate(v):
                flatten(f"{prefix}[{i}]", w, out)
    elif isinstance(v, (int, float, str, bool)) or v is None:
        out[prefix] = v


PARAM_COLS = ["run", "packing", "radius_mm", "seed", "model", "test", "solver", "specimen",
              "specimen_particles", "specimen_dropped", "specimen_porosity",
              "specimen_porosity_box", "contact_radius_multiplier", "flexural_poisson_ratio",
              "case"]


def collect(out):
    rows = []
    for rdir in sorted((Path(out) / "runs").glob("*")):
        s, m = rdir / "summary.json", rdir / "run.json"
        if not (s.exists() and m.exists()):
            continue
        row = {k: v for k, v in json.loads(m.read_text()).items() if k in PARAM_COLS}
        summary = json.loads(s.read_text())
        flat = {}
        for k, v in summary.items():
            if k == "groups":  # per-group detail stays in the run's summary.json
                continue
            flatten(k, v, flat)
        row.update(flat)
        rows.append(row)
    return rows


def write_csv(path, rows):
    keys = list(PARAM_COLS)
    extra = sorted({k for r in rows for k in r} - set(keys))
    keys += extra
    tmp = Path(str(path) + ".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in keys})
    os.replace(tmp, path)


def wang_mora_E(youngs=4e9, ratio=4.2):
    """Thesis eq. 2 (Wang and Mora 2008) for the thesis' PBM: k_n = k̄_n pi r^2, k̄_n = E_b/(2r),
    k_s = k_n / ratio; E_x is independent of r."""
    r = 1.0
    kn = youngs / (2 * r) * math.pi * r * r
    ks = kn / ratio
    return (3 * math.sqrt(2) * kn * (kn + ks) * (3 * kn ** 2 + 23 * ks ** 2 + 22 * kn * ks) /
            (r * (18 * kn ** 3 + 119 * kn ** 2 * ks + 128 * kn * ks ** 2 + 23 * ks ** 3)))


# ----------------------------------------------------------------------------- main


def find_dembridge(arg):
    cands = [Path(arg)] if arg else []
    if not arg and os.environ.get("DEMBRIDGE"):
        cands.append(Path(os.environ["DEMBRIDGE"]))
    if not cands:
        cands = [ROOT / "build" / "app" / "dembridge"]
    for c in cands:
        if c.is_file() and os.access(c, os.X_OK):
            return c.resolve()
    raise StudyError("the dembridge executable was not found (looked for "
                     + ", ".join(str(c) for c in cands)
                     + "); build it first (bash scripts/setup.sh) or pass --dembridge PATH")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--packings", default=",".join(PACKINGS), help="cubic,hcp,random")
    ap.add_argument("--radii", default=",".join(f"{r:g}" for r in RADII_MM),
                    help="particle radii in mm (default 2.5,5,7.5,10,12.5)")
    ap.add_argument("--models", default="pbm,tbbm", help="pbm,tbbm")
    ap.add_argument("--tests", default=",".join(TESTS), help="tension,compression,bending")
    ap.add_argument("--seeds", default="1-5", help="random packings: seeds, e.g. 1-5 or 1,3")
    ap.add_argument("--solver", default="static", help="static, explicit or static,explicit")
    ap.add_argument("--full", action="store_true",
                    help="also TBBM bending at r < 3 mm (left out in the thesis' Table 1)")
    ap.add_argument("--jobs", type=int, default=1, help="specimens run in parallel (default 1)")
    ap.add_argument("--out", default="study", help="output folder (default ./study)")
    ap.add_argument("--dembridge", default="", help="the build to use, named by its dembridge "
                    "executable: the runs go through that build's Python module (BUILD/python; "
                    "default $DEMBRIDGE, else build/app/dembridge)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="extra override passed to every run (e.g. 'Simulation/threads=2')")
    ap.add_argument("--dry-run", action="store_true", help="list the runs and stop")
    ap.add_argument("--report-only", action="store_true",
                    help="rebuild results.csv and the plots from the runs in --out")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--fresh", action="store_true",
                    help="first delete what an earlier call wrote into --out (runs, specimens, "
                         "results.csv, the plots): nothing is reused")
    a = ap.parse_args(argv)
    try:
        a.packings = parse_list(a.packings, str, PACKINGS, "packings")
        a.radii = parse_list(a.radii, float, None, "radii")
        if any(not (r > 0) for r in a.radii):
            raise StudyError("--radii: radii must be positive (mm)")
        a.models = parse_list(a.models, str, tuple(MODELS), "models")
        a.tests = parse_list(a.tests, str, TESTS, "tests")
        a.seeds = parse_list(a.seeds, int, None, "seeds")
        a.solver = parse_list(a.solver, str, ("static", "explicit"), "solver")
        runs = build_matrix(a)
        if a.dry_run:
            for r in runs:
                print(run_name(r))
            print(f"{len(runs)} runs")
            return 0
        # the plots module reads this module's constants, so it is imported once both exist
        from study_plots import PLOTS, plots

        out = Path(a.out)
        if a.fresh and not a.report_only:
            for d in ("runs", "specimens"):
                shutil.rmtree(out / d, ignore_errors=True)
            for f in ["results.csv", *PLOTS]:
                (out / f).unlink(missing_ok=True)
        failures = []
        if not a.report_only:
            exe = find_dembridge(a.dembridge)
            folder = module_folder(exe)
            runner = Runner(exe, out, extra_sets=a.set)
            print(f"study: {len(runs)} runs into {out.resolve()} with the dembridge module in "
                  f"{folder} ({a.jobs} job(s))", flush=True)
            t0 = time.time()
            failures = execute(runner, runs, a.jobs)
            print(f"study: finished in {time.time() - t0:.1f} s", flush=True)
        rows = collect(out)
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / "results.csv", rows)
        print(f"study: {len(rows)} runs in {out / 'results.csv'}")
        if not a.no_plots and rows:
            for p in plots(out, rows, a.solver[0]):
                print(f"study: wrote {p}")
        if failures:
            print(f"study: {len(failures)} run(s) failed:", file=sys.stderr)
            for n, e in failures:
                print(f"  {n}: {e}", file=sys.stderr)
            return 1
        return 0
    except StudyError as e:
        print(f"study.py: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
