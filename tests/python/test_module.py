#!/usr/bin/python3
"""The Python module against the command line (tests/python/CMakeLists.txt says what and why)."""
import argparse
import os
import shutil
import subprocess
import sys
import unittest

import numpy as np

# the dembridge .vtu reader of the app tests (meshio does not read VTK's String field arrays)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app"))
from static_output import vtu_array  # noqa: E402

ARGS = None


def cli_run(case, out, *sets):
    command = [ARGS.dembridge, "run", case, "--output-dir", out]
    for s in sets:
        command += ["--set", s]
    return subprocess.run(command, capture_output=True, text=True)


def fresh(name):
    path = os.path.join(ARGS.out, name)
    shutil.rmtree(path, ignore_errors=True)
    return path


class RunLikeTheCommandLine(unittest.TestCase):
    """dembridge.run() writes what `dembridge run` writes, figure for figure, file for file."""

    def same_outputs(self, case, sets):
        import dembridge
        cli, py = fresh(case + "_cli"), fresh(case + "_python")
        overrides = dict(s.split("=", 1) for s in sets)
        done = cli_run(os.path.join(ARGS.examples, case + ".prm"), cli, *sets)
        self.assertEqual(done.returncode, 0, done.stderr)
        run = dembridge.run(os.path.join(ARGS.examples, case + ".prm"), output_dir=py, set=overrides)
        compared = subprocess.run([sys.executable, ARGS.compare, cli, py],
                                  capture_output=True, text=True)
        self.assertEqual(compared.returncode, 0, compared.stdout + compared.stderr)
        return run

    def test_cantilever(self):
        run = self.same_outputs("cantilever", [])
        self.assertEqual(run.summary["mode"], "dem")
        # the tip deflection of the thesis' cantilever (tests/app: 8.534242e-3 m)
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.534242e-3, delta=5e-5)
        history = run.history
        self.assertEqual(len(history["time"]), len(history["step"]))
        self.assertGreater(len(history["time"]), 2)
        self.assertTrue(np.all(np.diff(history["time"]) > 0))

    def test_hcp_compression(self):
        run = self.same_outputs("compression_hcp", [])
        self.assertEqual(run.summary["solver"]["type"], "static")

    def test_overrides(self):
        run = self.same_outputs("cantilever", ["Bonds/model=euler_bernoulli"])
        # tests/app: the Euler-Bernoulli beam's tip deflection 8.488264e-3 m
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.488264e-3, delta=5e-5)


class Arrays(unittest.TestCase):
    """The model's arrays are its state: the last ParaView file's displacements, to the bit."""

    def test_displacements_match_the_paraview_file(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        out = fresh("cantilever_arrays")
        done = cli_run(case, out)
        self.assertEqual(done.returncode, 0, done.stderr)
        last = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".vtu"))[-1]
        kind, u_values = vtu_array(os.path.join(out, last), "displacement")
        self.assertEqual(kind, "Float64")  # every bit of the model's doubles
        _, ids_file = vtu_array(os.path.join(out, last), "id")
        model = dembridge.Model(case)
        figures = model.run()
        self.assertEqual(figures["stop_reason"], _summary(out)["stop_reason"])
        self.assertEqual(figures["steps"], _summary(out)["steps"])
        same_figures(self, figures, _summary(out))  # the tip deflection, energies, stresses
        with open(os.path.join(out, "history.csv")) as f:
            self.assertEqual(model.history_text, f.read())  # every record, every digit
        self.assertEqual(len(model.history["time"]), len(model.history_text.splitlines()) - 1)
        u_file = np.array(u_values).reshape(-1, 3)
        row_of_id = np.argsort(model.ids)
        u_model = model.displacements[row_of_id[np.array(ids_file, dtype=int)]]
        self.assertEqual(u_model.shape, u_file.shape)
        self.assertGreater(np.abs(u_file).max(), 1e-3)  # the tip moved (8.5 mm)
        np.testing.assert_array_equal(u_model, u_file)

    def test_views_follow_the_model(self):
        import dembridge
        model = dembridge.Model(os.path.join(ARGS.examples, "cantilever.prm"))
        positions = model.positions
        self.assertEqual(positions.shape, (model.n_particles, 3))
        self.assertFalse(positions.flags.writeable)
        before = positions.copy()
        model.step(200)
        self.assertEqual(model.steps, 200)
        self.assertGreater(np.abs(positions - before).max(), 0.0)  # the same memory, moved
        np.testing.assert_array_equal(positions - model.reference_positions, model.displacements)
        self.assertEqual(model.bond_ends.shape, (model.n_bonds, 2))
        self.assertTrue(np.all(model.bond_states == 0))
        self.assertEqual(model.stresses().shape, (model.n_particles, 3, 3))


VOLATILE = ("seconds", "memory", "started_at", "host", "command_line", "version", "git_commit")


def same_figures(test, figures, summary, where=""):
    """Every figure the Model returns is summary.json's, to the bit (times aside)."""
    for key, value in figures.items():
        if any(v in key for v in VOLATILE):
            continue
        test.assertIn(key, summary, where + key)
        if isinstance(value, dict):
            same_figures(test, value, summary[key], where + key + "/")
        elif key != "warnings":
            test.assertEqual(value, summary[key], where + key)


class StaticModel(unittest.TestCase):
    """Model.run() and Model.solve_static() are the command line's static solver: the HCP
    compression's E and nu to the bit, the cubic lattice's E = pi E_b / 4."""

    cli = {}

    @classmethod
    def cli_summary(cls, case, *sets):
        if (case, sets) not in cls.cli:
            out = fresh(f"{case}_static_cli{len(cls.cli)}")
            done = cli_run(os.path.join(ARGS.examples, case + ".prm"), out, *sets)
            assert done.returncode == 0, done.stderr
            cls.cli[case, sets] = _summary(out)
        return cls.cli[case, sets]

    def test_run_gives_the_command_lines_figures(self):
        import dembridge
        summary = self.cli_summary("compression_hcp")
        model = dembridge.Model(os.path.join(ARGS.examples, "compression_hcp.prm"))
        self.assertTrue(model.static_case)
        figures = model.run()
        for key in ("youngs_modulus", "poisson_ratio_xy", "poisson_ratio_xz"):
            self.assertEqual(figures[key], summary[key], key)  # bit for bit
        self.assertGreater(figures["youngs_modulus"], 1e9)
        same_figures(self, figures, summary)
        self.assertEqual(figures["solver"]["type"], "static")
        self.assertEqual(list(model.history["step"]), [1.0])  # one load step

    def test_solve_static_then_figures(self):
        import dembridge
        sets = ("Bonds/stiffness ratio=3", "Bonds/youngs modulus=5e9")
        summary = self.cli_summary("compression_hcp", *sets)
        model = dembridge.Model(os.path.join(ARGS.examples, "compression_hcp.prm"),
                                set=dict(s.split("=") for s in sets))
        before = model.positions.copy()
        solver = model.solve_static()
        self.assertEqual(solver["n_free_dofs"], summary["solver"]["n_free_dofs"])
        self.assertLess(solver["residual"], 1e-8)
        self.assertGreater(np.abs(model.positions - before).max(), 0.0)  # the view moved
        figures = model.figures()
        for key in ("youngs_modulus", "poisson_ratio_xy", "poisson_ratio_xz"):
            self.assertEqual(figures[key], summary[key], key)
        with self.assertRaises(dembridge.CaseError):
            model.step(1)  # a solved model is not stepped on

    def test_cubic_lattice_modulus(self):
        # thesis section 5.1: the simple cubic lattice of parallel bonds has E = pi E_b / 4
        # (the example's header), exactly in the linear static solve
        import dembridge
        model = dembridge.Model(os.path.join(ARGS.examples, "compression_cubic.prm"))
        model.solve_static()
        e = model.figures()["youngs_modulus"]
        self.assertAlmostEqual(e / (np.pi * 4e9 / 4), 1.0, delta=1e-6)

    def test_explicit_case_solved_statically(self):
        # the cantilever (an explicit case) solved statically: the command line's static run of
        # the same case, tip deflection to the bit
        import dembridge
        summary = self.cli_summary("cantilever", "Simulation/solver=static")
        model = dembridge.Model(os.path.join(ARGS.examples, "cantilever.prm"))
        self.assertFalse(model.static_case)
        model.solve_static()
        self.assertEqual(model.figures()["tip_deflection"], summary["tip_deflection"])


class Study(unittest.TestCase):
    """scripts/study.py runs its cases through the module, two specimens in two 'spawn' worker
    processes: each run's folder is what `dembridge run` writes for the command line its
    summary.json records (compare_outputs.py: every figure and file), and results.csv holds
    the summaries."""

    def test_study_reproduces_the_command_line(self):
        import csv
        out = fresh("study")
        study = os.path.join(os.path.dirname(ARGS.compare), "study.py")
        done = subprocess.run(
            [sys.executable, study, "--dembridge", ARGS.dembridge, "--out", out,
             "--packings", "cubic,hcp", "--radii", "12.5", "--models", "pbm",
             "--tests", "compression", "--solver", "static", "--jobs", "2", "--no-plots"],
            capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        with open(os.path.join(out, "results.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(sorted(r["packing"] for r in rows), ["cubic", "hcp"])
        for row in rows:
            folder = os.path.join(out, "runs", row["run"])
            summary = _summary(folder)
            self.assertEqual(float(row["youngs_modulus"]), summary["youngs_modulus"])
            with open(os.path.join(folder, "dembridge.log")) as log:
                self.assertIn("DEM: ", log.read())  # the library's lines went to the run's log
            words = summary["command_line"]
            self.assertEqual(words[:2], ["dembridge", "run"])
            cli = fresh("study_cli_" + row["run"])
            at = words.index("--output-dir")
            command = [ARGS.dembridge] + words[1:at + 1] + [cli] + words[at + 2:]
            rerun = subprocess.run(command, capture_output=True, text=True)
            self.assertEqual(rerun.returncode, 0, rerun.stderr)
            compared = subprocess.run([sys.executable, ARGS.compare, cli, folder,
                                       "--exclude", "run.json"], capture_output=True, text=True)
            self.assertEqual(compared.returncode, 0, compared.stdout + compared.stderr)
        cubic = next(r for r in rows if r["packing"] == "cubic")
        self.assertAlmostEqual(float(cubic["youngs_modulus"]) / (np.pi * 4e9 / 4), 1, delta=1e-6)


class Errors(unittest.TestCase):
    """A bad key raises CaseError with the command line's one line, naming the key."""

    def test_unknown_key(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        key = "Bonds/stiffnes ratio"
        done = cli_run(case, fresh("bad_key_cli"), key + "=2")
        self.assertEqual(done.returncode, 1)
        cli_line = done.stderr.strip().splitlines()[-1].removeprefix("dembridge: error: ")
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.run(case, output_dir=fresh("bad_key_python"), set={key: 2})
        self.assertIn("stiffnes ratio", str(raised.exception))
        self.assertEqual(str(raised.exception), cli_line)
        self.assertIsInstance(raised.exception, ValueError)
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.Model(case, set={key: 2})
        self.assertEqual(str(raised.exception), cli_line)

    def test_bad_value_names_the_key(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        done = cli_run(case, fresh("bad_value_cli"), "Bonds/model=spaghetti")
        self.assertEqual(done.returncode, 1)
        cli_line = done.stderr.strip().splitlines()[-1].removeprefix("dembridge: error: ")
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.Model(case, set={"Bonds/model": "spaghetti"})
        self.assertIn("Bonds/model", str(raised.exception))
        self.assertEqual(str(raised.exception), cli_line)

    def test_dict_case(self):
        import dembridge
        parameters = dembridge.check(os.path.join(ARGS.examples, "cantilever.prm"))
        self.assertEqual(parameters["Mode"], "dem")
        run = dembridge.run(parameters, output_dir=fresh("dict_case"))
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.534242e-3, delta=5e-5)


def _summary(folder):
    import json
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--dembridge", required=True)
    parser.add_argument("--examples", required=True)
    parser.add_argument("--compare", required=True)
    parser.add_argument("--out", required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.out, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
