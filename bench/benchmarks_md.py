"""BENCHMARKS.md is written by several studies, each owning a section between its own markers."""
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parent.parent / "BENCHMARKS.md"


def replace_section(text, begin, end):
    """Put `text` (which starts with `begin` and ends with `end`) in place of the section between
    those markers in BENCHMARKS.md, or append it when the file has none yet."""
    old = BENCHMARKS.read_text()
    if begin in old:
        new = old[:old.index(begin)] + text.rstrip("\n") + old[old.index(end) + len(end):]
    else:
        new = old.rstrip("\n") + "\n\n" + text
    BENCHMARKS.write_text(new)
    print("updated BENCHMARKS.md")
