#!/usr/bin/env python3
"""The link checker must find a broken link and a broken image: runs
tools/check_links.py on tests/docs/broken/ and passes only when it exits 1
and reports exactly the two broken targets of that fixture, nothing else.

    tests/docs/check_links_fixture.py [SOURCE_DIR]     (default: this file's repository)
"""
import pathlib
import subprocess
import sys

source = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
run = subprocess.run([sys.executable, str(source / "tools" / "check_links.py"), str(source / "tests" / "docs" / "broken")],
                     capture_output=True, text=True)
reported = sorted(run.stdout.splitlines())
expected = sorted([
    "README.md:11: link 'missing-page.md' points at nothing",
    "README.md:13: image 'images/missing-picture.png' points at nothing",
])
if run.returncode != 1 or reported != expected:
    print(f"exit code {run.returncode} (expected 1)")
    print("reported:\n  " + "\n  ".join(reported or ["(nothing)"]))
    print("expected:\n  " + "\n  ".join(expected))
    print(run.stderr, end="")
    sys.exit(1)
print("check_links.py reports the fixture's broken link and image, and only those")
