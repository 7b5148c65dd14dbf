#!/usr/bin/python3
"""docs_links: a clone must not point at documents its reader cannot open (issue 25).

Fails (exit 1, one line per finding) when
  1. any tracked file mentions one of the briefing notes that were never part of the repository
     (their names are assembled below, so this file does not name them itself); cite the paper or
     a docs/method.md section instead;
  2. a relative markdown link in README.md or docs/ (`[text](path)`, `[text](path#anchor)`)
     points to a file or directory that does not exist (links into fenced code blocks and inline
     code are not links; http(s) and mailto links are not checked: no network in CI);
  3. a markdown file under docs/ is linked from no other markdown file (it could not be found
     from the README).
Before checking the repository it checks itself on a small synthetic tree with one error of each
kind, so it cannot pass by finding nothing.

    /usr/bin/python3 tests/test_docs_links.py [REPO_ROOT]
"""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

# the notes' stems; the ".md" is added here so that this file never names a note itself
GONE = ["FIELD", "REFERENCE", "PETSC_NOTES", "STYLE"]
GONE_RE = re.compile(r"\b(" + "|".join(GONE) + r")\.md\b")
LINK_RE = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE_RE = re.compile(r"^\s*(```|~~~).*?^\s*\1", re.S | re.M)
CODE_RE = re.compile(r"`[^`\n]*`")


def tracked_files(root):
    """The files git tracks under root, or every file outside build trees and .git if root is not
    a git checkout (a source tarball)."""
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True, check=True)
        names = [n for n in out.stdout.decode().split("\0") if n]
        if names:
            return [root / n for n in names]
    except (OSError, subprocess.CalledProcessError):
        pass
    skip = {".git", "build", "out", "output"}
    return [p for p in root.rglob("*") if p.is_file() and not skip & set(p.relative_to(root).parts)]


def markdown_docs(root):
    docs = [root / "README.md"] if (root / "README.md").is_file() else []
    return docs + sorted((root / "docs").rglob("*.md")) if (root / "docs").is_dir() else docs


def links(text):
    """Relative link targets of a markdown text, outside code."""
    text = CODE_RE.sub("", FENCE_RE.sub("", text))
    for target in LINK_RE.findall(text):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I) or target.startswith("#"):
            continue  # http:, https:, mailto:, or an anchor in the same file
        yield target


def check(root):
    problems = []
    for p in tracked_files(root):
        try:
            text = p.read_text(encoding="utf-8")
        except (UnicodeDecodeError, OSError):
            continue  # binary (pictures)
        for n, line in enumerate(text.splitlines(), 1):
            m = GONE_RE.search(line)
            if m:
                problems.append(f"{p.relative_to(root)}:{n}: cites {m.group(0)}, which is not in "
                                "the repository (cite the paper or a docs/method.md section)")
    linked = set()
    for doc in markdown_docs(root):
        for target in links(doc.read_text(encoding="utf-8")):
            path = target.split("#", 1)[0]
            if not path:
                continue
            dest = (doc.parent / path).resolve()
            linked.add(dest)
            if not dest.exists():
                problems.append(f"{doc.relative_to(root)}: link to {target}: no such file")
    for doc in markdown_docs(root):
        if doc.parent != root and doc.resolve() not in linked:
            problems.append(f"{doc.relative_to(root)}: linked from no other document")
    return problems


def self_test():
    """One error of each kind in a synthetic tree must be found, and nothing in a clean one."""
    with tempfile.TemporaryDirectory() as d:
        root = Path(d)
        (root / "docs").mkdir()
        (root / "README.md").write_text("[guide](docs/guide.md) `[code](nowhere.md)`\n"
                                        "```\n[fenced](missing_too.md)\n```\n"
                                        "[web](https://example.org/x.md) [here](#top)\n")
        (root / "docs" / "guide.md").write_text("[back](../README.md#two-commands)\n")
        assert check(root) == [], check(root)
        (root / "src.cpp").write_text("// see " + GONE[0] + ".md 3.4\n")
        (root / "docs" / "guide.md").write_text("[back](../README.md) [gone](method.md#x)\n")
        (root / "docs" / "orphan.md").write_text("nothing links here\n")
        found = check(root)
        want = ["src.cpp:1: cites", "docs/guide.md: link to method.md#x", "docs/orphan.md: linked"]
        for w in want:
            assert any(f.startswith(w) for f in found), (w, found)
        assert len(found) == 3, found


def main():
    self_test()
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
    problems = check(root.resolve())
    for p in problems:
        print(p)
    n_docs = len(markdown_docs(root.resolve()))
    print(f"docs_links: {len(problems)} problem(s) in {len(tracked_files(root.resolve()))} tracked "
          f"files and {n_docs} markdown documents")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
