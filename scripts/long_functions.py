#!/usr/bin/env python3
"""Lists the C++ functions longer than N lines (default 80) in the given files or folders.

    scripts/long_functions.py [-n 80] app coupling

A brace-matching scan, not a parser: comments, string and character literals are blanked out,
then every top-level-of-its-scope block opened by `) {`, `) const {`, `) noexcept {`, `-> T {`
or a constructor's initialiser list is a function body; namespaces, classes, structs, enums and
lambdas inside a body are not counted separately (a lambda belongs to its function). The
length is counted from the line of the function's name to its closing brace, as a reader sees
it. Exit code 1 when a function is over the limit, so that CI can run it.
"""
import argparse
import pathlib
import re
import sys

SOURCE_SUFFIXES = {".cc", ".h", ".cpp", ".hpp"}


def blank_comments_and_literals(text):
    """The text with comments, strings and character literals replaced by spaces (newlines
    kept), so that braces inside them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def collapse_parentheses(header):
    """@p header with the contents of every (...) removed: "f(int a = 1) const" -> "f() const"."""
    out, depth = [], 0
    for c in header:
        if c == "(":
            if depth == 0:
                out.append(c)
            depth += 1
        elif c == ")":
            depth = max(depth - 1, 0)
            if depth == 0:
                out.append(c)
        elif depth == 0:
            out.append(c)
    return "".join(out)


FUNCTION_HEADER = re.compile(
    r"\)\s*((const|noexcept|override|final|mutable|try|&|&&)\s*)*(->\s*[^{;]+)?$")
CONSTRUCTOR_INITIALISERS = re.compile(r"\)\s*(noexcept\s*)?:(?!:)")


def functions(text):
    """(name line, end line, header) of every function body in @p text (1-based lines)."""
    clean = blank_comments_and_literals(text)
    clean = re.sub(r"(?m)^[ \t]*#.*$", lambda m: " " * len(m.group(0)), clean)
    stack = []  # per open brace: "function", "scope" (namespace, class, ...), "block", "init"
    starts = []
    results = []
    last_stop = 0  # after the last ';', '{' or '}' that ended a declaration
    for pos, c in enumerate(clean):
        if c == "{":
            header = clean[last_stop:pos]
            hc = collapse_parentheses(header).strip()
            kind = "block" if "function" in stack else "scope"
            if kind == "scope":
                if CONSTRUCTOR_INITIALISERS.search(hc) and re.search(r"[\w>]$", hc):
                    kind = "init"  # a member's brace initialiser: a_{1}
                elif FUNCTION_HEADER.search(hc) or (CONSTRUCTOR_INITIALISERS.search(hc)
                                                    and hc.endswith("}")):
                    kind = "function"
            stack.append(kind)
            if kind == "function":
                paren = header.find("(")
                first = last_stop + (paren if paren >= 0 else 0)
                starts.append(clean.count("\n", 0, first) + 1)
                results.append(None)
                starts[-1] = (starts[-1], header)
            else:
                starts.append(None)
            if kind != "init":
                last_stop = pos + 1
        elif c == "}":
            if stack:
                kind = stack.pop()
                start = starts.pop()
                if kind == "function":
                    results.append((start[0], clean.count("\n", 0, pos) + 1, start[1]))
                if kind == "init":
                    continue
            last_stop = pos + 1
        elif c == ";":
            last_stop = pos + 1
    return [r for r in results if r]


def function_name(header):
    """The name before the header's first '(' (operator() kept whole)."""
    h = " ".join(header.split())
    m = re.search(r"([~\w:]+(\s*<[^()]*>)?|operator\s*\S+?)\s*\(", h)
    return m.group(1) if m else h[-60:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", "--max-lines", type=int, default=80)
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    files = []
    for p in map(pathlib.Path, args.paths):
        files += sorted(f for f in p.rglob("*") if f.suffix in SOURCE_SUFFIXES) if p.is_dir() else [p]
    long = []
    for f in files:
        for start, end, header in functions(f.read_text(errors="replace")):
            length = end - start + 1
            if length > args.max_lines:
                long.append((length, f"{f}:{start}", function_name(header)))
    for length, where, name in sorted(long, reverse=True):
        print(f"{length:5d}  {where}  {name}")
    return 1 if long else 0


if __name__ == "__main__":
    sys.exit(main())
