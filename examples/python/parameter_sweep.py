"""Impact speed against crater depth: the tube impact of the paper run at several speeds.

The scene is examples/tube_impact_solid.toml read into a dict (flexdem.scene_dict), with the
impactor's velocity changed for each run; the crater depth is the largest downward
displacement of a tube node during the run. The curve goes to parameter_sweep.png (next to
this script, or --png PATH); without matplotlib the table is all you get.

    pip install ./crates/python matplotlib
    python examples/python/parameter_sweep.py [--speeds 0.5 1 2 3 4] [--duration 0.3]

Six speeds of 0.3 s each take some 10 s of wall time (a release build: pip install).
"""

import argparse
import pathlib
import time

import flexdem

HERE = pathlib.Path(__file__).resolve().parent
SCENE = HERE.parent / "tube_impact_solid.toml"


def crater_depth(speed, duration=0.3, every=10, scene=SCENE):
    """Runs the tube impact with the impactor falling at `speed` (m/s) for `duration` s of
    simulated time; returns (the largest downward displacement of a tube node in m, the
    relative energy balance error at the end). The tube nodes are watched every `every`
    steps."""
    d = flexdem.scene_dict(scene)
    d["spheres"][0]["velocity"] = [0.0, 0.0, -float(speed)]
    d.pop("output", None)  # nothing written
    sim = flexdem.Simulation.from_dict(d, base_dir=scene.parent)
    tube = sim.structures == 0  # the tube's nodes (structure 0)
    z0 = sim.positions[tube, 2]
    deepest = 0.0

    def watch(s):
        nonlocal deepest
        deepest = max(deepest, float((z0 - s.positions[tube, 2]).max()))

    sim.run(duration=duration, callback=watch, every=every)
    return deepest, sim.energy()["relative_balance_error"]


def sweep(speeds, duration, every=10):
    """crater_depth at each speed: a list of (speed, depth, balance error)."""
    return [(v, *crater_depth(v, duration, every)) for v in speeds]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[0.5, 1, 1.5, 2, 3, 4],
                        help="impact speeds (m/s)")
    parser.add_argument("--duration", type=float, default=0.3,
                        help="simulated seconds per run (the crater is deepest near 0.1 s)")
    parser.add_argument("--png", default=str(HERE / "parameter_sweep.png"))
    args = parser.parse_args()

    start = time.perf_counter()
    rows = sweep(args.speeds, args.duration)
    print(f"{len(rows)} runs of {args.duration} s in {time.perf_counter() - start:.1f} s")
    print(" speed (m/s)   crater depth (m)   depth / tube radius   energy balance error")
    for v, depth, error in rows:
        print(f"{v:12.3f}   {depth:16.5f}   {depth / 0.1:19.3f}   {error:20.2e}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (pip install matplotlib): no plot")
        return

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([r[0] for r in rows], [r[1] for r in rows], "o-")
    ax.set_xlabel("impact speed (m/s)")
    ax.set_ylabel("crater depth (m)")
    ax.set_title("Solid sphere on a PFacet tube: crater depth")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print(f"plot written to {args.png}")


if __name__ == "__main__":
    main()
