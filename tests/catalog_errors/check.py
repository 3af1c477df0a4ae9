#!/usr/bin/env python3
"""Each catalog snippet here reproduces a defect of issue 15: `rulegen derive` must exit 2 with a
message naming the file, the entry and the field (never accept it, never exit 3).
Usage: check.py RULEGEN [DIR]"""
import pathlib, subprocess, sys

EXPECT = {  # snippet -> (entry, field, words of the reason)
    "log_oscillating_F": ("log", "F", "differs from the integrand"),
    "tanh_jumping_F": ("tanh", "F", "jumps by 2 at x = 0"),
    "fract_narrow_range": ("fract", "range", "takes the value 1"),
    "of_not_string": ("floor", "of", "expected a string"),
    "comment_not_string": ("pow2", "comment", "expected a string"),
    "flat_not_number": ("tanh", "flat", "'beyond' must be a finite number"),
    "abs_in_antiderivative_f": ("absx", "f", "not smooth at x = 0"),
    "laplace_sgn_f": ("laplace", "f", "not smooth at x = 0"),
    # zeros of a polynomial break argument are isolated exactly, not sampled (0.47 apart, |x| <= 4243)
    "tanh_close_jumps_F": ("tanh", "F", "jumps by -2 at x = 0.01"),
    "tanh_far_jump_F": ("tanh", "F", "at x = 10000"),
    # monotone proved where f' = q e^{ax}: q's real roots, not samples
    "cubic_not_monotone": ("cubic", "monotone", "f' = 0 at x = 0.6"),
    "trunc_unknown_builtin": ("trunc", "builtin", "not a built-in of both C++ and GLSL"),
    "atan_negative_scale": ("atan", "scale", "must be positive, is -1000000"),
}

rulegen = sys.argv[1]
here = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path(__file__).parent
bad = []
files = sorted(here.glob("*.json"))
if {f.stem for f in files} != set(EXPECT):
    bad.append(f"snippets {sorted(f.stem for f in files)} do not match the table {sorted(EXPECT)}")
for f in files:
    entry, field, reason = EXPECT.get(f.stem, ("?", "?", "?"))
    r = subprocess.run([rulegen, "derive", "--quiet", "--catalog", str(f)], capture_output=True, text=True, timeout=120)
    want = [str(f), f"catalog entry '{entry}'", f"field '{field}'", reason]
    missing = [w for w in want if w not in r.stderr]
    if r.returncode != 2 or missing:
        bad.append(f"{f.name}: exit {r.returncode}, missing {missing} in: {r.stderr.strip()}")
    else:
        print(f"{f.name}: exit 2: {r.stderr.strip()}")
if bad:
    print("\n".join(bad))
    sys.exit(1)
