#!/usr/bin/env python3
"""blverify --generated DIR verifies a tree it was not built against (no rebuild): here the tree
rulegen emitted from tests/blverify_tree/catalog.json (tests/add_atomic's pulse train, plus fract
and inv, which the emitted bivariate rules call). Passes when blverify exits 0, its table lists
the test-only atomic's entries (bl::gaussian::bump, ...), and no project entry (it verified DIR's
registry, not the compiled-in one).
Usage: blverify_generated.py BLVERIFY DIR"""
import subprocess, sys

blverify, tree = sys.argv[1], sys.argv[2]
r = subprocess.run([blverify, "--generated", tree, "--threads", "2"], capture_output=True, text=True, timeout=1500)
out = r.stdout
problems = []
if r.returncode != 0:
    problems.append(f"exit {r.returncode}")
for name in ["bl::gaussian::bump", "bl::box::bump_sq", "bl::tent::bump"]:
    if name not in out:
        problems.append(f"{name} not verified")
if "bl::gaussian::sin " in out or "bl::box::tanh" in out:
    problems.append("verified the project's entries, not the tree's")
print(out[-3000:])
print(r.stderr[-3000:], file=sys.stderr)
if problems:
    print("FAILED: " + "; ".join(problems))
    sys.exit(1)
