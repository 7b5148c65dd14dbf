"""What the studies in bench/ share: the environment they launch pmpm under, and BENCHMARKS.md,
which several studies write, each owning a section between its own markers."""
import os
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parent.parent / "BENCHMARKS.md"

# mpiexec as root, and more ranks than cores (the 4-rank layouts on a 2-core machine)
MPI_ENV = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1")
if os.geteuid() == 0:
    MPI_ENV.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


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


def publish(text, path, begin, end, update):
    """A study's result: written to its own file `path`, printed, and put in its BENCHMARKS.md
    section when `update` (a full run, not a quick or partial one)."""
    Path(path).write_text(text)
    print(text)
    if update:
        replace_section(text, begin, end)
