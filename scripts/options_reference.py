#!/usr/bin/python3
"""Generate docs/options.md, the options reference, from `pmpm -help` (issue 25).

    /usr/bin/python3 scripts/options_reference.py                    # rewrite docs/options.md
    /usr/bin/python3 scripts/options_reference.py --pmpm build/pmpm --out FILE
    /usr/bin/python3 scripts/options_reference.py --check [--out F]  # exit 1 if docs/options.md
                                                                     # differs from what -help says

For every options file in options/ it runs `pmpm -options_file FILE -help` on one rank (pmpm
lists every option it would read, with its default, and runs nothing) and keeps pmpm's own option
blocks: those whose entries carry no PETSc manual page (they end in "(None)"); PETSc's own blocks
(-snes_*, -ksp_*, -pc_*, -dm_*, ...) are PETSc's documentation. The blocks every options file
shows are the common options; the others are listed per scene (the union over that scene's
options files). The CTest `docs_options` runs this script with --out into the build tree and
compares (drift: an option added, removed or reworded without regenerating the reference).
"""
import argparse
import os
import re
import subprocess
import sys
from collections import OrderedDict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SEP = "-" * 40
# an entry: "  -name <...>: text (man)", "  -name <...> text (man)", "  -name: <...> text (man)"
ENTRY = re.compile(r"^  -(?P<name>[A-Za-z0-9_]+)(?P<colon1>:?) <(?P<val>[^>]*)>:? ?(?P<text>.*) "
                   r"\((?P<man>[^()]*)\)$")


def help_text(exe, opts):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    p = subprocess.run([str(exe), "-options_file", str(opts), "-help"], cwd=ROOT, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    if p.returncode != 0:
        sys.exit(f"options_reference: {exe} -options_file {opts} -help failed "
                 f"(exit {p.returncode}):\n{p.stdout[-2000:]}")
    return p.stdout


def help_tables(exe):
    """The scene and material law tables (name -> one-line description) `pmpm -help` prints
    without a scene."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([str(exe), "-help"], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=600)
    if p.returncode != 0:
        sys.exit(f"options_reference: {exe} -help failed (exit {p.returncode}):\n{p.stdout[-2000:]}")
    lines = p.stdout.split("\n")

    def table_after(head):
        out = OrderedDict()
        start = next((i for i, ln in enumerate(lines) if ln.startswith(head)), len(lines))
        for ln in lines[start + 1:]:
            m = re.match(r"^  ([a-z_0-9]+)\s+(.*)$", ln)
            if not m:
                break
            out[m.group(1)] = m.group(2).strip()
        return out
    return table_after("Scenes ("), table_after("Material laws (")


def default_of(m):
    """The default an entry shows: enums and integers print <now X : formerly DEFAULT>, reals
    <X : DEFAULT>, booleans -name: <DEFAULT : X>; arrays and strings only their value."""
    val = m.group("val")
    if m.group("colon1"):  # a boolean
        return val.split(" : ")[0].lower()
    mm = re.match(r"now (.*) : formerly (.*)$", val)
    if mm:
        return mm.group(2).strip() or "(none)"
    if " : " in val:
        return val.split(" : ")[1]
    return None  # an array or a string list: no default printed


def blocks(text):
    """pmpm's option blocks of a -help output: OrderedDict title -> OrderedDict name ->
    (default, description)."""
    out = OrderedDict()
    for chunk in text.split(SEP)[1:]:
        lines = [ln for ln in chunk.strip("\n").split("\n") if ln.strip()]
        if not lines:
            continue
        title = lines[0].rstrip(":").strip()
        entries = OrderedDict()
        ours = True
        for ln in lines[1:]:
            m = ENTRY.match(ln)
            if not m:
                continue
            if m.group("man") != "None":
                ours = False
                break
            name, text = m.group("name"), m.group("text").strip()
            if name in entries and text not in entries[name][1]:  # read by two material laws
                text = entries[name][1] + "; " + text
            entries[name] = (default_of(m), text)
        if ours and entries:
            out.setdefault(title, OrderedDict()).update(entries)
    return out


def cell(s):
    """Text for a markdown table cell."""
    return (s.replace("|", "\\|").replace("<", "&lt;").replace(">", "&gt;").replace("*", "\\*"))


def table(entries, common=False):
    """A block as a markdown table. In the common blocks an option whose default differs between
    scenes (-scene itself) says so; in a scene's blocks the defaults of its files are listed."""
    rows = ["| option | default | meaning |", "|---|---|---|"]
    for name, (defaults, text) in entries.items():
        if common and len(defaults) > 1:
            d = "set by the scene"
        else:
            d = " / ".join(f"`{x}`" for x in defaults) if defaults else ""
        rows.append(f"| `-{name}` | {d} | {cell(text)} |")
    return rows


def merge(dst, src):
    """Merge block dicts; an option's defaults kept in order of first appearance."""
    for title, entries in src.items():
        d = dst.setdefault(title, OrderedDict())
        for name, (default, text) in entries.items():
            defaults, _ = d.get(name, ([], text))
            if default is not None and default not in defaults:
                defaults = defaults + [default]
            d[name] = (defaults, text)


def generate(exe):
    table_of_scenes, table_of_laws = help_tables(exe)
    files = sorted((ROOT / "options").glob("*.opts"))
    per_file = OrderedDict()
    scene_of = {}
    for f in files:
        rel = f.relative_to(ROOT)
        per_file[rel] = blocks(help_text(exe, rel))
        m = re.search(r"^-scene\s+(\S+)", f.read_text(), re.M)
        scene_of[rel] = m.group(1) if m else "?"
    common_titles = [t for t in next(iter(per_file.values()))
                     if all(t in b for b in per_file.values())]
    common = OrderedDict()
    for b in per_file.values():
        merge(common, OrderedDict((t, b[t]) for t in common_titles))
    scenes = OrderedDict()
    for rel, b in per_file.items():
        merge(scenes.setdefault(scene_of[rel], OrderedDict()),
              OrderedDict((t, e) for t, e in b.items() if t not in common_titles))

    md = ["# Options reference",
          "",
          "<!-- Generated by scripts/options_reference.py from `pmpm -help` for every options file "
          "in options/. Do not edit by hand: rerun the script (the CTest docs_options fails when "
          "this file and -help differ). -->",
          "",
          "Every option pmpm reads, as `pmpm -options_file FILE -help` lists it: its default and "
          "its meaning with the allowed range. An option a run does not read is an error naming "
          "it, so this list is also the contract of what each scene accepts. Several defaults "
          "separated by `/` are those the scene's options files start from. PETSc's own options "
          "(`-snes_*`, `-ksp_*`, `-pc_*`, `-mat_mumps_*`, `-da_processors_x`, `-log_view`, ...) "
          "are documented by PETSc. How the options work together: "
          "[user-guide.md](user-guide.md) and [cover.md](cover.md).",
          "",
          "## Contents",
          "",
          "- [Scenes](#scenes)",
          "- [Material laws](#material-laws)",
          "- [Options of every run](#options-of-every-run)"]
    for scene in scenes:
        md.append(f"- [Scene `{scene}`](#scene-{scene})")
    md += ["", "## Scenes", "",
           "The scene table of `src/scenes/registry.cpp`, as `pmpm -help` lists it; "
           "`pmpm -scene NAME -help` lists a scene's options without an options file.", "",
           "| scene | what it is |", "|---|---|"]
    md += [f"| `{s}` | {cell(d)} |" for s, d in table_of_scenes.items()]
    md += ["", "## Material laws", "",
           "The law table of `src/materials/registry.cpp`: the values of `-mat_<name>_model` "
           "(the first is the default). Each material's block lists every law's own options "
           "(`-help` reads them all); a run reads its law's only.", "",
           "| law | what it is |", "|---|---|"]
    md += [f"| `{s}` | {cell(d)} |" for s, d in table_of_laws.items()]
    md += ["", "## Options of every run", ""]
    for title, entries in common.items():
        md += [f"### {cell(title)}", ""] + table(entries, common=True) + [""]
    for scene, bl in scenes.items():
        used = [rel for rel in per_file if scene_of[rel] == scene]
        md += [f"## Scene {scene}", "",
               (cell(table_of_scenes[scene][:1].upper() + table_of_scenes[scene][1:]) + ". " if scene in table_of_scenes
                else "") + "Options files: " + ", ".join(f"[`{r}`](../{r.as_posix()})" for r in used) +
               ". Material and layer blocks are named after the materials these files define.",
               ""]
        for title, entries in bl.items():
            md += [f"### {cell(title)}", ""] + table(entries) + [""]
    return "\n".join(md).rstrip("\n") + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--pmpm", default=str(ROOT / "build" / "pmpm"), help="the pmpm binary")
    ap.add_argument("--out", default=None,
                    help="where to write (default docs/options.md; with --check, nowhere)")
    ap.add_argument("--check", action="store_true",
                    help="compare with docs/options.md instead of replacing it (exit 1 on drift)")
    a = ap.parse_args()
    text = generate(Path(a.pmpm).resolve())
    out = a.out or (None if a.check else str(ROOT / "docs" / "options.md"))
    if out:
        Path(out).write_text(text)
        print(f"options_reference: wrote {out} ({len(text.splitlines())} lines)")
    if a.check:
        ref = (ROOT / "docs" / "options.md").read_text()
        if ref == text:
            print("options_reference: docs/options.md matches pmpm -help")
            return 0
        got, want = ref.splitlines(), text.splitlines()
        n = next((i for i in range(min(len(got), len(want))) if got[i] != want[i]),
                 min(len(got), len(want)))
        print("options_reference: docs/options.md differs from pmpm -help (regenerate it: "
              "/usr/bin/python3 scripts/options_reference.py)")
        print(f"  first difference at line {n + 1}:")
        print(f"  docs/options.md: {got[n] if n < len(got) else '(end of file)'}")
        print(f"  pmpm -help:      {want[n] if n < len(want) else '(end of file)'}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
