#!/usr/bin/env python3
"""Regenerates generated/ into a temporary directory and fails when it differs from the
committed files (the manifest is compared without the verification records, which
`blverify --record` adds and the verify_all test checks), or when a committed entry lacks its
passing verification record (generated/ committed from `rulegen emit` alone; the compact
kernels' half-width helpers are not verified entries)."""
import json, pathlib, subprocess, sys, tempfile

rulegen, root = sys.argv[1], pathlib.Path(sys.argv[2])
committed = root / "generated"
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([rulegen, "emit", "--quiet", "--out", tmp,
                    "--catalog", str(root / "symbolic/catalog.json")], check=True)
    fresh = pathlib.Path(tmp)
    names = sorted({p.relative_to(fresh) for p in fresh.rglob("*") if p.is_file()} |
                   {p.relative_to(committed) for p in committed.rglob("*") if p.is_file()})
    bad = []
    for n in names:
        a, b = committed / n, fresh / n
        if not a.exists() or not b.exists():
            bad.append(f"{n}: {'missing in generated/' if not a.exists() else 'no longer generated'}")
            continue
        if n.name == "manifest.json":
            strip = lambda m: {**m, "entries": [{k: v for k, v in e.items() if k != "verification"}
                                                for e in m["entries"]]}
            if strip(json.loads(a.read_text())) != strip(json.loads(b.read_text())):
                bad.append(f"{n}: entries differ")
        elif a.read_bytes() != b.read_bytes():
            bad.append(f"{n}: differs")
    unverified = [e.get("cpp", "?") for e in json.loads((committed / "manifest.json").read_text())["entries"]
                  if not e.get("cpp", "").startswith("bl::compact::")
                  and e.get("verification", {}).get("status") != "pass"]
    if unverified:
        bad.append(f"manifest.json: {len(unverified)} entries without a passing verification record "
                   f"(first: {', '.join(unverified[:3])}): run blverify --record")
    if bad:
        print("generated/ is out of date with the catalog/engine; run tools/main.sh and commit:")
        print("\n".join("  " + b for b in bad))
        sys.exit(1)
    print(f"generated/ matches a fresh generation ({len(names)} files)")
