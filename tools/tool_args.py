"""What the tools/ scripts share about their command lines, so that they meet
bad input as octrace itself does: one line naming the flag or file and what
is wrong, exit status 2, and no output file begun.

  import tool_args                       (a script in tools/)
  sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   (in tools/peer/)

  parser = tool_args.Parser(description=...)          argparse, one-line errors
  parser.add_argument("--octrace", type=tool_args.executable, ...)
  parser.add_argument("--rounds", type=tool_args.positive_int, ...)
  parser.add_argument("--out", type=tool_args.output_file, ...)
  tool_args.fail("ab_render.py", "--variant 'x': ...")   a check of its own
  tool_args.print_table(lines, a.out)                   a table to stdout and --out
  out = tool_args.run([octrace, "render", ...])         stdout, or the tool ends
  tool_args.last_line(p.stderr, "no message")           where a program said what is wrong
"""
import argparse
import os
import re
import shutil
import subprocess
import sys


class Parser(argparse.ArgumentParser):
    """argparse with its errors on one line ("TOOL: --rounds: must be a whole
    number >= 1, got '0' (see --help)") instead of the usage and the error."""

    def error(self, message):
        print(f"{self.prog}: {message} (see --help)", file=sys.stderr)
        sys.exit(2)


def fail(tool, message):
    """Ends the tool with "TOOL: MESSAGE" on stderr and exit status 2 (bad input)."""
    print(f"{tool}: {message}", file=sys.stderr)
    sys.exit(2)


def executable(text):
    """A program to run: a path to an executable file, or a name on PATH."""
    if not text:
        raise argparse.ArgumentTypeError("expected a program, got an empty string")
    if os.sep in text:
        if not os.path.isfile(text):
            raise argparse.ArgumentTypeError(f"{text}: no such file (build it first: tools/build.sh)")
        if not os.access(text, os.X_OK):
            raise argparse.ArgumentTypeError(f"{text}: not executable")
        return text
    found = shutil.which(text)
    if not found:
        raise argparse.ArgumentTypeError(f"{text}: not found on PATH")
    return found


def positive_int(text):
    """A whole number >= 1 (rounds, runs, repeats)."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 1, got {text!r}")
    return int(text)


def output_file(text):
    """A file to write: its folder must exist and not be a file, and the path
    must not be a folder; checked before any work."""
    if not text:
        raise argparse.ArgumentTypeError("expected a file name, got an empty string")
    folder = os.path.dirname(text) or "."
    if not os.path.isdir(folder):
        raise argparse.ArgumentTypeError(f"{text}: folder {folder} does not exist")
    if os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"{text}: is a folder, not a file")
    return text


def input_file(text):
    """A file to read, which must exist."""
    if not os.path.isfile(text):
        raise argparse.ArgumentTypeError(f"{text}: no such file")
    return text


def size(text):
    """WIDTHxHEIGHT, as octrace takes it (each side 1 to 9 digits)."""
    if not re.fullmatch(r"[1-9][0-9]{0,8}x[1-9][0-9]{0,8}", text):
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT (e.g. 1200x800), got {text!r}")
    return text


def print_table(lines, out=None):
    """Prints a markdown table's lines (a header line first) and, with `out`,
    writes the same text to that file."""
    text = "\n".join(lines) + "\n"
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text)


def last_line(text, default=""):
    """The last non-empty line of a program's output (where octrace, perf or
    nvdisasm says what is wrong), or `default` where it printed nothing."""
    lines = (text or "").strip().splitlines()
    return lines[-1].strip() if lines else default


def run(cmd, echo_stderr=False):
    """Runs a program and returns its stdout; if it fails, ends the tool with
    "TOOL: PROGRAM ARG failed: " and the program's last line of stderr (where
    octrace says what is wrong), and the program's exit status. With
    `echo_stderr`, a program that succeeds has its stderr (its warnings)
    passed on to the tool's."""
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        why = last_line(out.stderr, f"exit {out.returncode}")
        print(f"{os.path.basename(sys.argv[0])}: {os.path.basename(cmd[0])} {cmd[1]} failed: {why}", file=sys.stderr)
        sys.exit(out.returncode if out.returncode > 0 else 1)
    if echo_stderr:
        sys.stderr.write(out.stderr)
    return out.stdout
