#!/usr/bin/env python3
"""Turns the rows hardcases_test writes into the markdown table of docs/hardcases.md.

    rm -f /tmp/hardcases.tsv
    OCTRACE_HARDCASES_TABLE=/tmp/hardcases.tsv build/tests/hardcases_test
    tools/hardcases_table.py /tmp/hardcases.tsv --update

Input: one row per criterion and variant, tab-separated:
    case, quantity, bound, accel, precision, measured value, pass|FAIL
(a later row for the same case, quantity and variant replaces an earlier one,
so a file appended to by several runs gives the latest). Output: one table row
per (case, quantity) in the order the suite ran them, one column per
precision x accel with the measured value, and the verdict over all variants.
Where a precision has its own bound, its cells show it after the value
(the criterion column shows the bound most variants share; of a tie, the
first in the file's order).
Without --update the table goes to stdout; with it, the text between the
markers <!-- hardcases-table:begin --> and <!-- hardcases-table:end --> in
docs/hardcases.md (the one copy of the table; or the file named after
--update) is replaced; each marker must occur exactly once there. Bad input
exits with 2. Python standard library only.
"""
import pathlib
import sys

import tool_args

BEGIN = "<!-- hardcases-table:begin -->"
END = "<!-- hardcases-table:end -->"
DEFAULT_DOC = pathlib.Path(__file__).resolve().parent.parent / "docs" / "hardcases.md"


def read_rows(path):
    rows = {}  # (case, quantity) -> {(precision, accel): (value, bound, passed)}
    precisions, accels = [], []
    for number, line in enumerate(read_text(path).split("\n"), 1):
        if not line:
            continue
        fields = line.split("\t")
        if len(fields) != 7 or fields[6] not in ("pass", "FAIL"):
            tool_args.fail("hardcases_table.py",
                           f"{path}:{number}: expected 7 tab-separated fields ending in pass|FAIL")
        case, quantity, bound, accel, precision, value, verdict = fields
        precisions += [precision] if precision not in precisions else []
        accels += [accel] if accel not in accels else []
        rows.setdefault((case, quantity), {})[(precision, accel)] = (value, bound, verdict == "pass")
    seen = {v for results in rows.values() for v in results}
    # Columns grouped by precision, in the order the suite ran them.
    variants = [(p, a) for p in precisions for a in accels if (p, a) in seen]
    return rows, variants


def read_text(path):
    """The file's text; a file that is not UTF-8 text ends the tool (exit 2)."""
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except UnicodeDecodeError:
        tool_args.fail("hardcases_table.py", f"{path}: not UTF-8 text")


def cell(text):
    return text.replace("|", "\\|")


def table(rows, variants):
    head = ["case", "criterion"] + [f"{p} {a}" for p, a in variants] + ["result"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    failed = 0
    for (case, quantity), results in rows.items():
        bounds = [bound for _, bound, _ in results.values()]
        # The bound most variants share; of a tie, the first in row order
        # (max keeps the first of equals; a set's order would vary by run).
        common = max(dict.fromkeys(bounds), key=bounds.count)
        values = []
        for v in variants:
            if v not in results:
                values.append("–")
                continue
            value, bound, passed = results[v]
            text = value if bound == common else f"{value} ({bound})"
            values.append(text if passed else f"**{text}**")
        criterion = f"{quantity} {common}"
        ok = all(passed for _, _, passed in results.values()) and len(results) == len(variants)
        failed += not ok
        lines.append("| " + " | ".join([f"`{case}`", cell(criterion)] + values + ["pass" if ok else "**FAIL**"]) + " |")
    lines.append("")
    lines.append(f"{len(rows)} criteria, {len(rows) - failed} pass in every variant, {failed} fail or are missing "
                 "(a failing value is in bold; – = not run).")
    return "\n".join(lines) + "\n"


def main():
    parser = tool_args.Parser(description=__doc__.split("\n")[0])
    parser.add_argument("rows", type=tool_args.input_file,
                        help="file written by OCTRACE_HARDCASES_TABLE=FILE build/tests/hardcases_test")
    parser.add_argument("--update", metavar="MARKDOWN", nargs="?", const=str(DEFAULT_DOC), type=tool_args.input_file,
                        help="replace the table between the markers in this file (default: docs/hardcases.md)")
    args = parser.parse_args()
    rows, variants = read_rows(args.rows)
    if not rows:
        tool_args.fail("hardcases_table.py", f"{args.rows}: no rows")
    text = table(rows, variants)
    if not args.update:
        sys.stdout.write(text)
        return
    doc = read_text(args.update)
    if doc.count(BEGIN) != 1 or doc.count(END) != 1 or doc.index(BEGIN) > doc.index(END):
        tool_args.fail("hardcases_table.py", f"{args.update}: expected {BEGIN} and then {END}, once each")
    before, rest = doc.split(BEGIN, 1)
    _, after = rest.split(END, 1)
    with open(args.update, "w", encoding="utf-8") as f:
        f.write(before + BEGIN + "\n" + text + END + after)


if __name__ == "__main__":
    main()
