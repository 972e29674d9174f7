#!/usr/bin/env python3
"""Fails when a link or image in README.md or docs/**/*.md points at nothing.

    tools/check_links.py [ROOT]        (ROOT: the repository, default: the current folder)

Checked in ROOT/README.md and every ROOT/docs/**/*.md, outside fenced code
blocks and inline code:
  - markdown links and images, [text](target) and ![alt](target), and
    <img src="target"> / <a href="target">: the target, percent-decoded
    (%20 is a space) and relative to the file's folder, or to ROOT where it
    starts with / (as GitHub resolves it), a trailing #anchor dropped, must
    exist; where it is a markdown file, its #anchor must be one of the
    file's headings, as GitHub names them.
    http(s):, mailto: and pure #anchor targets are not checked.
  - inline code that is a bare repository path, such as `docs/results/h100/bench.md`
    or `tools/accuracy.py`: one word that starts with a top-level folder of the
    repository (app, renderer, shaders, tests, tools, docs, .ci) and names a
    file (has an extension) or a folder (ends in /); it must exist relative to
    ROOT. Words with wildcards or placeholders (* < > { } [ ] $ |) are skipped.
Prints one line per missing target, FILE:LINE: kind 'target' (and one per
file that is not UTF-8 text), and exits 1 if there is any; exit 0 and a
one-line count otherwise. Python standard library only.
"""
import argparse
import pathlib
import re
import sys
import urllib.parse

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^()\s>]+(?:\([^()\s]*\)[^()\s>]*)*)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML = re.compile(r"<(img|a)\b[^>]*?\b(src|href)\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")
REPO_DIRS = ("app", "renderer", "shaders", "tests", "tools", "docs", ".ci")
PLACEHOLDER = re.compile(r"[*<>{}\[\]$|\s]")


def anchors(path, cache={}):
    """The anchors GitHub gives the headings of a markdown file."""
    if path not in cache:
        names, seen, in_fence = set(), {}, None
        for line in path.read_text(encoding="utf-8").splitlines():
            fence = FENCE.match(line)
            if fence:
                in_fence = fence.group(1) if in_fence is None else (None if fence.group(1) == in_fence else in_fence)
                continue
            heading = re.match(r"^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
            if in_fence or not heading:
                continue
            text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading.group(1))  # a link's text only
            slug = re.sub(r"[^\w\- ]", "", text.lower()).replace(" ", "-")
            n = seen.get(slug, 0)
            seen[slug] = n + 1
            names.add(slug if n == 0 else f"{slug}-{n}")
        cache[path] = names
    return cache[path]


def markdown_files(root):
    files = [root / "README.md"] if (root / "README.md").is_file() else []
    docs = root / "docs"
    if docs.is_dir():
        files += sorted(p for p in docs.rglob("*.md") if p.is_file())
    return files


def external(target):
    return re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) is not None  # http:, https:, mailto:, ...


def looks_like_repo_path(word):
    if PLACEHOLDER.search(word) or "/" not in word:
        return False
    if word.split("/", 1)[0] not in REPO_DIRS:
        return False
    last = word.rstrip("/").rsplit("/", 1)[-1]
    return word.endswith("/") or ("." in last and not last.endswith("."))


def check_file(root, path):
    """Yields (line number, kind, target) for every target in `path` that does not exist."""
    in_fence = None
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        fence = FENCE.match(line)
        if fence:
            if in_fence is None:
                in_fence = fence.group(1)
            elif fence.group(1) == in_fence:
                in_fence = None
            continue
        if in_fence:
            continue
        spans = [m.group(2).strip() for m in CODE_SPAN.finditer(line)]
        text = CODE_SPAN.sub("", line)
        targets = [("image" if m.group(0).startswith("!") else "link", m.group(1)) for m in LINK.finditer(text)]
        targets += [("image" if m.group(1).lower() == "img" else "link", m.group(3)) for m in HTML.finditer(text)]
        for kind, target in targets:
            if external(target) or target.startswith("#"):
                continue
            file_part, _, anchor = target.partition("#")
            file_part = urllib.parse.unquote(file_part)
            resolved = root / file_part.lstrip("/") if file_part.startswith("/") else path.parent / file_part
            if not resolved.exists():
                yield number, kind, target
            elif anchor and resolved.is_file() and resolved.suffix == ".md" and anchor not in anchors(resolved):
                yield number, "anchor", target
        for word in spans:
            if looks_like_repo_path(word) and not (root / word).exists():
                yield number, "path", word


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root", nargs="?", default=".", help="repository root (default: the current folder)")
    args = ap.parse_args()
    root = pathlib.Path(args.root).resolve()
    files = markdown_files(root)
    if not files:
        sys.exit(f"{root}: no README.md and no docs/*.md")
    missing = 0
    for path in files:
        try:
            path.read_text(encoding="utf-8")
        except UnicodeDecodeError as e:
            print(f"{path.relative_to(root)}: not UTF-8 text (byte {e.start})")
            missing += 1
            continue
        for number, kind, target in check_file(root, path):
            print(f"{path.relative_to(root)}:{number}: {kind} '{target}' points at nothing")
            missing += 1
    if missing:
        print(f"{missing} broken in {len(files)} files", file=sys.stderr)
        sys.exit(1)
    print(f"links: {len(files)} files, nothing broken")


if __name__ == "__main__":
    main()
