"""What the studies in bench/ share: the environment they launch pmpm under, and the study files in
docs/benchmarks/, one per study, each written by its script between its own markers
(`<!-- chains.py begin -->` ... `<!-- chains.py end -->` goes to docs/benchmarks/chains.md)."""
import json
import os
import shutil
import subprocess
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BENCH_DOCS = ROOT / "docs" / "benchmarks"  # one file per study; README.md there is the index

# mpiexec as root, and more ranks than cores (the 4-rank layouts on a 2-core machine)
MPI_ENV = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1")
if os.geteuid() == 0:
    MPI_ENV.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def study_file(begin):
    """The file in docs/benchmarks/ a study's section lives in, from its begin marker:
    "<!-- chains.py begin -->" -> docs/benchmarks/chains.md, "<!-- memory begin -->" -> memory.md."""
    name = begin.strip().removeprefix("<!--").removesuffix("-->").strip().removesuffix(" begin")
    return BENCH_DOCS / (name.removesuffix(".py") + ".md")


def replace_section(text, begin, end):
    """Put `text` (which starts with `begin` and ends with `end`) in place of the section between
    those markers in the study's own file docs/benchmarks/<study>.md (study_file), or start that
    file when it does not exist or has no such section yet. The study's image links (written
    relative to the repository root, `](bench/x.png)`) are made relative to docs/benchmarks/."""
    text = text.replace("](bench/", "](../../bench/")
    path = study_file(begin)
    old = path.read_text() if path.exists() else ""
    if begin in old and end in old:
        new = old[:old.index(begin)] + text.rstrip("\n") + old[old.index(end) + len(end):]
    elif old.strip():
        new = old.rstrip("\n") + "\n\n" + text
    else:
        new = text
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(new.rstrip("\n") + "\n")
    print(f"updated {path.relative_to(ROOT)}")


def publish(text, path, begin, end, update):
    """A study's result: written to its own file `path`, printed, and put in its section of
    docs/benchmarks/<study>.md when `update` (a full run, not a quick or partial one)."""
    Path(path).write_text(text)
    print(text)
    if update:
        replace_section(text, begin, end)


def launch(exe, np_, args, out, timeout=3600):
    """Run pmpm from the repository root into `out` (emptied first). Return (its summary.json with
    the launch's wall seconds as "elapsed" and the exit code as "exit_code", the output) or (None,
    the output) if it failed. Exit 3 (a stage stopped at its step cap) and 4 (INCONCLUSIVE) wrote
    their answers: they are results, not failures."""
    out = Path(out)
    if out.is_dir():
        shutil.rmtree(out)
    cmd = ["mpiexec", "-n", str(np_), str(exe)] + [str(a) for a in args] + \
          ["-output_dir", str(out), "-quiet"]
    t0 = time.time()
    p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=timeout)
    if p.returncode not in (0, 3, 4):
        return None, f"{' '.join(cmd)}\n{p.stdout}"
    with open(out / "summary.json") as f:
        s = json.load(f)
    s["elapsed"] = time.time() - t0
    s["exit_code"] = p.returncode
    return s, p.stdout


def build_revision(rev, tag):
    """Build git revision `rev` once into bench/out/<tag>-<rev>/ (a detached worktree and a
    Release build of the pmpm target); its pmpm path. A half-built directory is started again."""
    d = ROOT / "bench" / "out" / f"{tag}-{rev}"
    exe = d / "build" / "pmpm"
    if exe.exists():
        return exe
    if d.exists():
        subprocess.run(["git", "worktree", "remove", "--force", str(d)], cwd=ROOT)
        shutil.rmtree(d, ignore_errors=True)
    subprocess.run(["git", "worktree", "add", "--detach", str(d), rev], cwd=ROOT, check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "-S", str(d), "-B", str(d / "build"), "-DCMAKE_BUILD_TYPE=Release"],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(d / "build"), "-j", str(os.cpu_count()), "--target",
                    "pmpm"], check=True, stdout=subprocess.DEVNULL)
    return exe


def error_line(output, tail=300):
    """pmpm's one error line in a failed launch's output, or the output's tail."""
    return next((ln for ln in output.splitlines() if ln.startswith("pmpm: error")), output[-tail:])


def run_pmpm(exe, np_, args, out, timeout=3600):
    """launch(), printing the command and its output's tail when it fails (then None)."""
    s, output = launch(exe, np_, args, out, timeout)
    if s is None:
        print(f"  failed: {output[-2000:]}")
    return s
