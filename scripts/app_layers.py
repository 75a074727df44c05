#!/usr/bin/env python3
"""Checks that app/'s folders depend downwards only: a file in a folder includes app headers from
its own folder or from folders above it in app/CMakeLists.txt's list (job, input, checkpoint,
output, runs, studies, cli; main.cc may include any). Prints each include that points upwards and
exits 1 when there is one.

    scripts/app_layers.py [APP_DIR]
"""
import pathlib
import re
import sys

ORDER = ["input", "job", "checkpoint", "output", "runs", "studies", "cli"]


def main():
    app = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent / "app")
    upward = []
    for f in sorted(app.glob("*/*")):
        if f.suffix not in (".h", ".cc"):
            continue
        folder = f.parent.name
        if folder not in ORDER:
            upward.append(f"{f}: folder '{folder}' is not in the layer list")
            continue
        for n, line in enumerate(f.read_text().splitlines(), 1):
            m = re.match(r'#include "app/(\w+)/', line)
            if m and (m.group(1) not in ORDER or ORDER.index(m.group(1)) > ORDER.index(folder)):
                upward.append(f"{f}:{n}: {folder}/ includes {m.group(1)}/")
    for u in upward:
        print(u)
    return 1 if upward else 0


if __name__ == "__main__":
    sys.exit(main())
