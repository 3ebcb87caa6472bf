"""The route of one parameter, a propeller's f_theta, through ``propwhirl analyse MODEL.toml``:
the call stacks, module by module, at the moments the value is read into the model, enters the
generated blocks inside the engine's sweep, the modes are named, a crossing is converged and
the critical speed is described for printing; a "climb back up" is a call from a lower layer
(generated < model < engine < analysis < studies < io < app) into a higher one.

    python benchmarks/route.py examples/wingtip.toml      (the report on stderr)

Nothing is timed; run it in two checkouts to compare their routes (issue 21).
"""
import sys
LAYER = {"generated": 0, "model": 1, "engine": 2, "analysis": 3, "studies": 4, "io": 5, "app": 6}
def mod(frame):
    f = frame.f_code.co_filename
    if "/generated/" in f and "site-packages" not in f: return "generated/" + f.split("/generated/")[-1][:-3]
    if "/src/propwhirl/" in f: return f.split("/src/propwhirl/")[-1][:-3]
    return None
def layer(m):
    return LAYER.get(m.split("/")[0])
stacks = {}
def stack_of(frame):
    out = []
    while frame is not None:
        m = mod(frame)
        if m and (not out or out[-1] != m): out.append(m)
        frame = frame.f_back
    return out[::-1]
PROBES = {"read f_theta": lambda m, n: m == "model/propeller" and n in ("__post_init__", "__init__"),
          "mount stiffness into the generated blocks": lambda m, n: m.startswith("generated/prop_flexwing"),
          "mode names tracked": lambda m, n: n == "follow" or (n == "_track_nodes" and m == "analysis/campbell"),
          "crossing converged": lambda m, n: m == "engine/correction",
          "critical speed described": lambda m, n: n in ("describe_critical", "critical_summary", "format_critical")}
def prof(frame, event, arg):
    if event != "call": return
    m = mod(frame)
    if m is None: return
    for k, test in PROBES.items():
        if k not in stacks and test(m, frame.f_code.co_name):
            st = stack_of(frame)
            if k.startswith("mount") and not any(x.startswith("engine/") for x in st):
                continue
            if k.startswith("mode names") and "analysis/naming" not in st:
                continue
            stacks[k] = st
from propwhirl.app import cli
sys.setprofile(prof)
try: cli.main(["analyse", sys.argv[1]])
finally: sys.setprofile(None)
allmods = []
for k, st in stacks.items():
    climbs = sum(1 for a, b in zip(st, st[1:]) if layer(a) is not None and layer(b) is not None and layer(b) > layer(a))
    print(f"{k}: {len(st)} modules, {climbs} climbs back up:\n   " + " -> ".join(st), file=sys.stderr)
    allmods += [m for m in st if m not in allmods]
pk = sorted({m.split('/')[0] if '/' in m else '(top)' for m in allmods})
print(f"together: {len(allmods)} modules in {len(pk)} packages {pk}", file=sys.stderr)
