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
Where a precision has its own bound, its cells show it after the value.
Without --update the table goes to stdout; with it, the text between the
markers <!-- hardcases-table:begin --> and <!-- hardcases-table:end --> in
docs/hardcases.md (the one copy of the table; or the file named after
--update) is replaced; each marker must occur exactly once there. Python
standard library only.
"""
import argparse
import pathlib
import sys

BEGIN = "<!-- hardcases-table:begin -->"
END = "<!-- hardcases-table:end -->"
DEFAULT_DOC = pathlib.Path(__file__).resolve().parent.parent / "docs" / "hardcases.md"


def read_rows(path):
    rows = {}  # (case, quantity) -> {(precision, accel): (value, bound, passed)}
    precisions, accels = [], []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line:
                continue
            fields = line.split("\t")
            if len(fields) != 7 or fields[6] not in ("pass", "FAIL"):
                sys.exit(f"{path}:{number}: expected 7 tab-separated fields ending in pass|FAIL")
            case, quantity, bound, accel, precision, value, verdict = fields
            precisions += [precision] if precision not in precisions else []
            accels += [accel] if accel not in accels else []
            rows.setdefault((case, quantity), {})[(precision, accel)] = (value, bound, verdict == "pass")
    seen = {v for results in rows.values() for v in results}
    # Columns grouped by precision, in the order the suite ran them.
    variants = [(p, a) for p in precisions for a in accels if (p, a) in seen]
    return rows, variants


def cell(text):
    return text.replace("|", "\\|")


def table(rows, variants):
    head = ["case", "criterion"] + [f"{p} {a}" for p, a in variants] + ["result"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    failed = 0
    for (case, quantity), results in rows.items():
        bounds = [bound for _, bound, _ in results.values()]
        common = max(set(bounds), key=bounds.count)  # the bound most variants share
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
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("rows", help="file written by OCTRACE_HARDCASES_TABLE=FILE build/tests/hardcases_test")
    parser.add_argument("--update", metavar="MARKDOWN", nargs="?", const=str(DEFAULT_DOC),
                        help="replace the table between the markers in this file (default: docs/hardcases.md)")
    args = parser.parse_args()
    rows, variants = read_rows(args.rows)
    if not rows:
        sys.exit(f"{args.rows}: no rows")
    text = table(rows, variants)
    if not args.update:
        sys.stdout.write(text)
        return
    with open(args.update, encoding="utf-8") as f:
        doc = f.read()
    if doc.count(BEGIN) != 1 or doc.count(END) != 1 or doc.index(BEGIN) > doc.index(END):
        sys.exit(f"{args.update}: expected {BEGIN} and then {END}, once each")
    before, rest = doc.split(BEGIN, 1)
    _, after = rest.split(END, 1)
    with open(args.update, "w", encoding="utf-8") as f:
        f.write(before + BEGIN + "\n" + text + END + after)


if __name__ == "__main__":
    main()
