#!/usr/bin/env python3
"""What a command prints and the files it leaves, checked line by line (grep's way).

usage: check_output.py [options] [-- COMMAND ARGS...]

Runs COMMAND (under `MPIEXEC -np N --oversubscribe` with --mpi), prints what it printed and
passes when it exits with --exit's code (0 by default) and every check holds:
  --has REGEX            a line of its stdout matches REGEX (re.search; '(?i)' for any case)
  --lacks REGEX          no line of its stdout matches REGEX
  --stdout FILE          its stdout is kept in FILE
  --same-on-one-rank     (with --mpi) its stdout equals that of COMMAND run alone, byte for byte
  --startup-cpu-below S  its CPU time (user + system) exceeds that of `COMMAND[0] --version`,
                         the start-up every command pays, by less than S seconds
  --exists FILE          FILE exists and is not empty
  --absent FILE          FILE does not exist
  --file-has FILE REGEX, --file-lacks FILE REGEX: as --has and --lacks, on FILE's lines
Without COMMAND only the file checks run. Plain python3.
"""
import argparse
import os
import re
import resource
import subprocess
import sys

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def any_line(lines, regex):
    return any(re.search(regex, line) for line in lines)


def file_lines(path):
    if not os.path.isfile(path):
        return []
    with open(path, errors="replace") as f:
        return f.read().splitlines()


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(command):
    """Runs command; returns its exit code, stdout (text) and CPU seconds."""
    before = children_cpu()
    done = subprocess.run(command, stdout=subprocess.PIPE, text=True)
    return done.returncode, done.stdout, children_cpu() - before


def main():
    argv = sys.argv[1:]
    command = []
    if "--" in argv:
        command = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("--mpi", nargs=2, metavar=("MPIEXEC", "NP"))
    parser.add_argument("--exit", type=int, default=0)
    parser.add_argument("--has", action="append", default=[])
    parser.add_argument("--lacks", action="append", default=[])
    parser.add_argument("--stdout")
    parser.add_argument("--same-on-one-rank", action="store_true")
    parser.add_argument("--startup-cpu-below", type=float)
    parser.add_argument("--exists", action="append", default=[])
    parser.add_argument("--absent", action="append", default=[])
    parser.add_argument("--file-has", nargs=2, action="append", default=[])
    parser.add_argument("--file-lacks", nargs=2, action="append", default=[])
    args = parser.parse_args(argv)

    if command:
        launcher = [args.mpi[0], "-np", args.mpi[1], "--oversubscribe"] if args.mpi else []
        code, out, cpu = run(launcher + command)
        lines = out.splitlines()
        if len(lines) <= 100:
            sys.stdout.write(out)
        print("(%d lines on stdout, exit code %d)" % (len(lines), code))
        if args.stdout:
            os.makedirs(os.path.dirname(os.path.abspath(args.stdout)), exist_ok=True)
            with open(args.stdout, "w") as f:
                f.write(out)
        check(code == args.exit, "exit code %d (expected %d)" % (code, args.exit))
        for regex in args.has:
            check(any_line(lines, regex), "a line of stdout matches /%s/" % regex)
        for regex in args.lacks:
            check(not any_line(lines, regex), "no line of stdout matches /%s/" % regex)
        if args.same_on_one_rank:
            alone_code, alone, _ = run(command)
            print("alone: %d lines on stdout, exit code %d" % (len(alone.splitlines()), alone_code))
            check(alone_code == 0 and alone == out, "stdout under mpirun equals stdout alone")
        if args.startup_cpu_below is not None:
            _, _, startup = run([command[0], "--version"])
            print("CPU seconds (user+system): the command %.3f, start-up alone %.3f" %
                  (cpu, startup))
            check(cpu - startup < args.startup_cpu_below,
                  "CPU time beyond the start-up below %g s" % args.startup_cpu_below)
    for path in args.exists:
        check(os.path.isfile(path) and os.path.getsize(path) > 0, "%s is not empty" % path)
    for path in args.absent:
        check(not os.path.lexists(path), "%s does not exist" % path)
    for path, regex in args.file_has:
        check(any_line(file_lines(path), regex), "a line of %s matches /%s/" % (path, regex))
    for path, regex in args.file_lacks:
        check(os.path.isfile(path) and not any_line(file_lines(path), regex),
              "%s exists, no line of it matches /%s/" % (path, regex))
    if failures:
        sys.exit(1)
    print("ok")


if __name__ == "__main__":
    main()
