#!/usr/bin/env python3
"""What a command prints and the files it leaves, checked line by line (grep's way).

usage: check_output.py [options] [-- COMMAND ARGS... [--then COMMAND ARGS...]...]

Runs COMMAND (under `MPIEXEC -np N --oversubscribe` with --mpi), prints what it printed and
passes when it exits with --exit's code (0 by default) and every check holds. With --then the
commands run in turn, each but the last must exit with 0 (the first that does not fails the
test), and the checks of stdout and stderr are those of the last:
  --remove PATH          PATH (a file or folder) is removed before COMMAND runs
  --has REGEX            a line of its stdout matches REGEX (re.search; '(?i)' for any case)
  --lacks REGEX          no line of its stdout matches REGEX
  --stdout FILE          its stdout is kept in FILE
  --err-has REGEX        a line of its stderr matches REGEX (stderr is then captured, and printed)
  --err-lines N          its stderr is N lines, each ended by a newline
  --same-on-one-rank     (with --mpi) its stdout equals that of COMMAND run alone, byte for byte
  --startup-cpu-below S  its CPU time (user + system) exceeds that of `COMMAND[0] --version`,
                         the start-up every command pays, by less than S seconds
  --exists FILE          FILE exists and is not empty
  --absent FILE          FILE does not exist
  --file-has FILE REGEX, --file-lacks FILE REGEX: as --has and --lacks, on FILE's lines
  --file-count FILE REGEX N    at least N lines of FILE match REGEX
  --same-count FILE REGEX1 REGEX2  as many lines of FILE match REGEX1 as match REGEX2
--mpi applies to the last command. Without COMMAND only the file checks run. Plain python3.
"""
import argparse
import os
import re
import resource
import shutil
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


def run(command, capture_stderr=False):
    """Runs command; returns its exit code, stdout, stderr (None unless captured; text) and CPU
    seconds."""
    before = children_cpu()
    done = subprocess.run(command, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE if capture_stderr else None, text=True,
                          errors="replace")
    return done.returncode, done.stdout, done.stderr, children_cpu() - before


def split_commands(argv):
    """The commands after the first '--', separated by '--then'."""
    commands = [[]]
    for arg in argv:
        if arg == "--then":
            commands.append([])
        else:
            commands[-1].append(arg)
    return [c for c in commands if c]


def count_lines(path, regex):
    return sum(1 for line in file_lines(path) if re.search(regex, line))


def main():
    argv = sys.argv[1:]
    commands = []
    if "--" in argv:
        commands = split_commands(argv[argv.index("--") + 1:])
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("--mpi", nargs=2, metavar=("MPIEXEC", "NP"))
    parser.add_argument("--exit", type=int, default=0)
    parser.add_argument("--remove", action="append", default=[])
    parser.add_argument("--err-has", action="append", default=[])
    parser.add_argument("--err-lines", type=int)
    parser.add_argument("--has", action="append", default=[])
    parser.add_argument("--lacks", action="append", default=[])
    parser.add_argument("--stdout")
    parser.add_argument("--same-on-one-rank", action="store_true")
    parser.add_argument("--startup-cpu-below", type=float)
    parser.add_argument("--exists", action="append", default=[])
    parser.add_argument("--absent", action="append", default=[])
    parser.add_argument("--file-has", nargs=2, action="append", default=[])
    parser.add_argument("--file-lacks", nargs=2, action="append", default=[])
    parser.add_argument("--file-count", nargs=3, action="append", default=[])
    parser.add_argument("--same-count", nargs=3, action="append", default=[])
    args = parser.parse_args(argv)

    for path in args.remove:
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        elif os.path.lexists(path):
            os.remove(path)
    for earlier in commands[:-1]:
        print("$ " + " ".join(earlier), flush=True)
        code = subprocess.run(earlier).returncode
        if code != 0:
            check(False, "exit code %d of %s (expected 0)" % (code, earlier[0]))
            sys.exit(1)
    if commands:
        command = commands[-1]
        launcher = [args.mpi[0], "-np", args.mpi[1], "--oversubscribe"] if args.mpi else []
        capture_stderr = bool(args.err_has) or args.err_lines is not None
        code, out, err, cpu = run(launcher + command, capture_stderr)
        lines = out.splitlines()
        if len(lines) <= 100:
            sys.stdout.write(out)
        print("(%d lines on stdout, exit code %d)" % (len(lines), code))
        if capture_stderr:
            print("stderr: " + err, end="" if err.endswith("\n") else "\n")
        if args.stdout:
            os.makedirs(os.path.dirname(os.path.abspath(args.stdout)), exist_ok=True)
            with open(args.stdout, "w") as f:
                f.write(out)
        check(code == args.exit, "exit code %d (expected %d)" % (code, args.exit))
        for regex in args.has:
            check(any_line(lines, regex), "a line of stdout matches /%s/" % regex)
        for regex in args.lacks:
            check(not any_line(lines, regex), "no line of stdout matches /%s/" % regex)
        for regex in args.err_has:
            check(any_line(err.splitlines(), regex), "a line of stderr matches /%s/" % regex)
        if args.err_lines is not None:
            check(err.count("\n") == args.err_lines and (err == "" or err.endswith("\n")),
                  "stderr is %d line(s), each ended by a newline (expected %d)" %
                  (err.count("\n"), args.err_lines))
        if args.same_on_one_rank:
            alone_code, alone, _, _ = run(command)
            print("alone: %d lines on stdout, exit code %d" % (len(alone.splitlines()), alone_code))
            check(alone_code == 0 and alone == out, "stdout under mpirun equals stdout alone")
        if args.startup_cpu_below is not None:
            _, _, _, startup = run([command[0], "--version"])
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
    for path, regex, least in args.file_count:
        n = count_lines(path, regex)
        check(n >= int(least), "%d lines of %s match /%s/ (at least %s)" % (n, path, regex, least))
    for path, first, second in args.same_count:
        a, b = count_lines(path, first), count_lines(path, second)
        check(a == b, "%d lines of %s match /%s/, %d match /%s/ (as many)" %
              (a, path, first, b, second))
    if failures:
        sys.exit(1)
    print("ok")


if __name__ == "__main__":
    main()
