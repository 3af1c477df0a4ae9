#!/usr/bin/env python3
"""blverify --generated DIR verifies a tree it was not built against (no rebuild): here the tree
rulegen emitted from tests/blverify_tree/catalog.json (tests/add_atomic's pulse train alone, so
without the bivariate div and mod, which call inv and fract). Passes when blverify exits 0, its
table lists the test-only atomic's entries (bl::gaussian::bump, ...), and no project entry (it
verified DIR's registry, not the compiled-in one), every bivariate rule of DIR's manifest passed
its check, and every one the manifest lists as not emitted is reported absent, not checked; and
when a copy of DIR whose manifest claims those rules is checked (--rules-only, the same cached
plugin), blverify fails naming each, rather than passing it unchecked.
Usage: blverify_generated.py BLVERIFY DIR"""
import json, pathlib, re, shutil, subprocess, sys, tempfile

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
manifest = json.load(open(f"{tree}/manifest.json"))
for e in manifest["entries"]:
    if e.get("rule") == "bivariate" and not re.search(re.escape(e["cpp"]) + r" .* pass$", out, re.M):
        problems.append(f"{e['cpp']} not checked or not passed")
for n in manifest["not_derived"]:
    if n.get("rule") == "bivariate":
        cpp = "bl::bivariate::" + n["op"]
        if not re.search(re.escape(cpp) + r" .* absent$", out, re.M) or f"{cpp}: not checked:" not in out:
            problems.append(f"{cpp} (not emitted) is not reported absent")
absent = ["bl::bivariate::" + n["op"] for n in manifest["not_derived"] if n.get("rule") == "bivariate"]
if absent:
    with tempfile.TemporaryDirectory() as tmp:
        liar = pathlib.Path(tmp) / "tree"
        shutil.copytree(tree, liar)
        m = json.loads((liar / "manifest.json").read_text())
        m["entries"] += [{"rule": "bivariate", "cpp": cpp} for cpp in absent]
        (liar / "manifest.json").write_text(json.dumps(m, indent=2))
        l = subprocess.run([blverify, "--generated", str(liar), "--rules-only"], capture_output=True, text=True,
                           timeout=600)
        if l.returncode == 0:
            problems.append("a manifest listing rules the tree lacks passed")
        for cpp in absent:
            if f"FAILED: {cpp} (absent from the compiled tree, but" not in l.stderr:
                problems.append(f"{cpp} listed in the manifest but absent from the tree: not reported")
print(out[-3000:])
print(r.stderr[-3000:], file=sys.stderr)
if problems:
    print("FAILED: " + "; ".join(problems))
    sys.exit(1)
