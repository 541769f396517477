#!/usr/bin/env python3
"""A mutation fuzzer of the `tpi` command line (issue 14's acceptance): mutates the sample
surface and pattern files and generator specs, runs `tpi discretise` with JSON, OBJ and SVG
outputs (and `tpi info`), and counts panics, hangs, exit-0 runs whose outputs hold a
non-finite number or an OBJ face with fewer than 3 distinct vertices, files left behind by
failing runs, and messages over 1 kB.

    python3 fuzz/cli_mutate.py target/release/tpi 900      # binary, seconds
"""
import json, math, os, random, shutil, subprocess, sys, tempfile, time

def mutate_number(x, rng):
    return rng.choice([0, -0.0, 1e308, -1e308, 5e-324, 1e-300, 1e300, 1e15, 1e16, x * 1e10,
                       x * -1, x + 1e-9, float(int(x)) if abs(x) < 1e18 else x, 1e-7, 2.0])

def mutate(value, rng, depth=0):
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, (int, float)):
        return mutate_number(float(value), rng) if rng.random() < 0.3 else value
    if isinstance(value, list):
        v = [mutate(x, rng, depth + 1) for x in value]
        r = rng.random()
        if r < 0.05 and v:
            v.pop(rng.randrange(len(v)))
        elif r < 0.1 and v:
            v.append(v[rng.randrange(len(v))])
        elif r < 0.12 and v:
            rng.shuffle(v)
        return v
    if isinstance(value, dict):
        v = {k: mutate(x, rng, depth + 1) for k, x in value.items()}
        r = rng.random()
        if r < 0.05 and v:
            v.pop(rng.choice(list(v)))
        elif r < 0.08:
            v[rng.choice(["type", "weights", "zz", "radius"])] = rng.choice(["nurbs", 3, [1.0] * 42, "x" * rng.randrange(1, 5000)])
        return v
    if isinstance(value, str):
        return value if rng.random() < 0.9 else value + "x" * rng.randrange(1, 3000)
    return value

def non_finite_in(obj):
    if isinstance(obj, float):
        return not math.isfinite(obj)
    if obj is None:
        return False
    if isinstance(obj, list):
        return any(non_finite_in(x) for x in obj)
    if isinstance(obj, dict):
        return any(non_finite_in(x) for x in obj.values())
    return False

def main():
    tpi, seconds = sys.argv[1], float(sys.argv[2])
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples")
    surfaces = [json.load(open(os.path.join(root, f))) for f in sorted(os.listdir(root))
                if f.endswith(".json") and not f.startswith(("hex-", "poisson-", "random-"))]
    patterns = [json.load(open(os.path.join(root, f))) for f in ("hex-24x20.json",)]
    specs = ["hex:8x8", "grid:12x9", "random:60:seed=3", "poisson:0.1:seed=2", "jitter:7x7:amount=0.9",
             "grid:1x10000000", "hex:0x3", "random:2", "poisson:0.0001", "grid:spacing=1e-300"]
    rng = random.Random(14)
    counts = dict(runs=0, panics=0, hangs=0, bad_exit0=0, left_behind=0, long_messages=0, exit0=0)
    work = tempfile.mkdtemp(prefix="tpi-mutate-")
    end = time.time() + seconds
    while time.time() < end:
        counts["runs"] += 1
        d = tempfile.mkdtemp(dir=work)
        s = mutate(rng.choice(surfaces), rng)
        with open(os.path.join(d, "s.json"), "w") as f:
            f.write(json.dumps(s))
        if rng.random() < 0.5:
            p = mutate(rng.choice(patterns), rng)
            with open(os.path.join(d, "p.json"), "w") as f:
                f.write(json.dumps(p))
            pattern = os.path.join(d, "p.json")
        else:
            pattern = rng.choice(specs)
        outs = [os.path.join(d, "r.json"), os.path.join(d, "r.obj"), os.path.join(d, "r.svg")]
        args = [tpi, "discretise", "--surface", os.path.join(d, "s.json"), "--pattern", pattern]
        for o in outs:
            args += ["--out", o]
        try:
            r = subprocess.run(args, capture_output=True, timeout=60)
        except subprocess.TimeoutExpired:
            counts["hangs"] += 1
            print("HANG", d)
            continue
        err = r.stderr.decode("utf-8", "replace")
        if r.returncode == 101 or "panicked" in err:
            counts["panics"] += 1
            print("PANIC", d, err[:300])
        if any(len(line) > 1024 for line in err.splitlines()):
            counts["long_messages"] += 1
            print("LONG MESSAGE", d)
        before = {"s.json", "p.json"}
        left = set(os.listdir(d)) - before
        if r.returncode == 0:
            counts["exit0"] += 1
            bad = False
            try:
                bad = non_finite_in(json.load(open(outs[0])))
            except Exception as e:
                bad = True
            for line in open(outs[1]):
                if line.startswith("v ") and any(not math.isfinite(float(t)) for t in line.split()[1:]):
                    bad = True
                if line.startswith("f ") and len(set(line.split()[1:])) < 3:
                    bad = True
            if bad:
                counts["bad_exit0"] += 1
                print("BAD EXIT 0", d)
            else:
                shutil.rmtree(d)
        else:
            if left:
                counts["left_behind"] += 1
                print("LEFT BEHIND", d, left)
            else:
                shutil.rmtree(d)
    print(json.dumps(counts))

if __name__ == "__main__":
    main()
