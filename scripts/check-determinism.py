#!/usr/bin/env python3
"""Run every command that prints formulas several times and report outputs that differ.

Each command (solve, formulas, explain in every format and level, codegen, exercises with a
fixed seed) is run RUNS times over every named class and every problem file under examples/
and tests/ (files that neither `solve` nor `formulas` accepts are left out). The processes run
with the machine's ordinary address randomisation, which is what made GiNaC's term order
change from run to run; IMPACTGEN_NO_REEXEC=1 is set so that the CLI's re-exec guard (see
docs/architecture.md) does not hide it: what is measured is the library's own determinism.

usage: scripts/check-determinism.py IMPACTGEN [--runs 5] [--exercise-runs 3] [--jobs 2]
                                    [--only SUBSTRING] [--verb SUBCOMMAND] [--allow-reexec]
Exit status 1 when some output differs. Run it niced on a shared machine.
"""
import argparse
import concurrent.futures
import glob
import hashlib
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cmd, env, cwd=None):
    out = subprocess.run(cmd, capture_output=True, env=env, cwd=cwd, timeout=600)
    return out.returncode, out.stdout + b"\0" + out.stderr


def run_exercises(cmd, env):
    with tempfile.TemporaryDirectory(prefix="det-ex-") as tmp:
        # run inside the folder so that the messages name the same path in every run
        rc, text = run(cmd + ["--out", "sheet"], env, cwd=tmp)
        tmp = os.path.join(tmp, "sheet")
        digest = hashlib.sha256(text)
        for path in sorted(glob.glob(os.path.join(tmp, "**", "*"), recursive=True)):
            if os.path.isfile(path):
                digest.update(os.path.relpath(path, tmp).encode() + b"\0")
                with open(path, "rb") as f:
                    digest.update(f.read())
        return rc, digest.hexdigest().encode()


def problem_files():
    files = []
    for pattern in ("examples/**/*.json", "tests/**/*.json"):
        files += glob.glob(os.path.join(ROOT, pattern), recursive=True)
    return sorted(os.path.relpath(f, ROOT) for f in files
                  if "/golden/" not in f or "/problems/" in f)


def named_classes(exe, env):
    _, text = run([exe, "list"], env)
    names = []
    for line in text.split(b"\0")[0].decode().splitlines():
        # rows are "NAME  description"; the group headings end with a colon
        if line.strip() and not line.rstrip().endswith(":"):
            names.append(line.split()[0])
    return names


def commands(exe, source, is_file):
    base = [[exe, "formulas", source, "--format", f] for f in ("text", "latex", "json")]
    if is_file:
        base += [[exe, "solve", source], [exe, "solve", "--json", source]]
    for level in ("full", "summary"):
        for f in ("text", "markdown", "latex", "html"):
            base.append([exe, "explain", source, "--format", f, "--level", level])
    base.append([exe, "codegen", source])
    return base


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("impactgen")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--exercise-runs", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="", help="only the sources whose name contains this")
    ap.add_argument("--verb", default="", help="only this subcommand (solve, formulas, explain, codegen, exercises)")
    ap.add_argument("--allow-reexec", action="store_true",
                    help="let the CLI re-exec itself without address randomisation")
    args = ap.parse_args()
    exe = os.path.abspath(args.impactgen)
    env = dict(os.environ)
    if not args.allow_reexec:
        env["IMPACTGEN_NO_REEXEC"] = "1"
    os.chdir(ROOT)

    sources = [(c, False) for c in named_classes(exe, env)]
    for f in problem_files():
        ok = any(run([exe, verb, f], env)[0] == 0 for verb in ("formulas", "solve"))
        if ok:
            sources.append((f, True))
    sources = [s for s in sources if args.only in s[0]]

    jobs = []
    for source, is_file in sources:
        for cmd in commands(exe, source, is_file):
            jobs += [(tuple(cmd), run)] * args.runs
        where = os.path.join(ROOT, source) if is_file else source
        ex = [exe, "--time-limit", "0", "exercises", where, "--count", "2", "--seed", "1"]
        jobs += [(tuple(ex), run_exercises)] * args.exercise_runs

    if args.verb:
        jobs = [j for j in jobs if args.verb in j[0]]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(fn, list(cmd), env): cmd for cmd, fn in jobs}
        for fut in concurrent.futures.as_completed(futures):
            rc, text = fut.result()
            results.setdefault(futures[fut], []).append(hashlib.sha256(
                str(rc).encode() + b"\0" + text).hexdigest())

    differing = 0
    for cmd in sorted(results):
        distinct = len(set(results[cmd]))
        if distinct > 1:
            differing += 1
            shown = " ".join(c if c != exe else "impactgen" for c in cmd)
            print(f"DIFFERS ({distinct} outputs in {len(results[cmd])} runs): {shown}")
    print(f"{differing} of {len(results)} commands differ "
          f"({len(sources)} sources, {len(jobs)} runs)")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
