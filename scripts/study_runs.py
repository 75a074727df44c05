#!/usr/bin/python3
"""The runs of the specimen study (scripts/study.py): the dembridge Python module of the build
that --dembridge names, each specimen generated once and stored, each run of the matrix as
dembridge.run on an example case with overrides, and their execution one specimen at a time or
in spawned worker processes. study.py holds the matrix, the results table and the command line;
the names below are also study.py's (study.Runner, study.run_name: bench/study_bench.py)."""
import concurrent.futures
import contextlib
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




def rtag(radius_mm):
    return f"{radius_mm:g}".replace(".", "p")


def specimen_name(packing, radius_mm, seed):
    return f"{packing}_r{rtag(radius_mm)}mm" + (f"_s{seed}" if packing == "random" else "")




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
