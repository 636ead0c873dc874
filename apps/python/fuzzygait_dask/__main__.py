# fuzzygait_dask's command line. MIT License (see LICENSE).
"""python3 -m fuzzygait_dask train [--scheduler ADDR | --local-workers N] --out DIR CLIP.bvh...

Trains a set per clip on a Dask cluster, writes each into DIR/CLIP/ (the set and training.json),
prints progress and a table; exits 1 naming the clips that failed.
"""
import argparse
import json
import pathlib
import sys

from . import train_clips


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m fuzzygait_dask",
                                description="fuzzygait's training on a Dask cluster")
    commands = p.add_subparsers(dest="command", required=True)
    t = commands.add_parser("train", help="train a set per clip, each on a worker")
    where = t.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDR",
                       help="a running scheduler, e.g. tcp://host:8786")
    where.add_argument("--local-workers", type=int, metavar="N", default=2,
                       help="else a local cluster of N one-thread worker processes (default 2)")
    t.add_argument("--out", "-o", required=True, type=pathlib.Path,
                   help="folder receiving a folder per clip")
    t.add_argument("--retries", type=int, default=0, help="more attempts of a failing clip")
    t.add_argument("--quiet", action="store_true", help="no progress lines, the table alone")
    # fuzzygait train's options, as fuzzygait.train takes them
    t.add_argument("--base", default="default", help="built-in set or set folder to start from")
    t.add_argument("--name", help="name of each trained set (default 'trained')")
    t.add_argument("--description")
    t.add_argument("--generations", type=int)
    t.add_argument("--polish", type=int)
    t.add_argument("--threads", type=int, help="walks evaluated in parallel in each training")
    t.add_argument("--seed", type=int)
    t.add_argument("--steps-around", type=float, nargs="+")
    t.add_argument("--grid", action="store_true", default=None)
    t.add_argument("--recovery", type=int)
    t.add_argument("--fit-iterations", type=int)
    t.add_argument("--no-fits", dest="fits", action="store_false", default=None)
    t.add_argument("--base-structure", action="store_true", default=None)
    t.add_argument("--map", type=pathlib.Path, help="leg mapping file")
    t.add_argument("--up", choices=["y", "z"])
    t.add_argument("--unit", type=float)
    t.add_argument("--skip", type=int)
    t.add_argument("clips", nargs="+", type=pathlib.Path, help="BVH files of walks")
    return p


TRAIN_OPTIONS = ["base", "name", "description", "generations", "polish", "threads", "seed",
                 "steps_around", "grid", "recovery", "fit_iterations", "fits", "base_structure",
                 "map", "up", "unit", "skip"]


def train(args) -> int:
    names = [c.stem for c in args.clips]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        print(f"fuzzygait_dask: clips named alike: {', '.join(twice)}", file=sys.stderr)
        return 2
    options = {k: getattr(args, k) for k in TRAIN_OPTIONS if getattr(args, k) is not None}

    def progress(e: dict) -> None:
        if args.quiet:
            return
        if e["event"] == "iteration":
            print(f"  {e['clip']}: {e['stage']} {e['iteration']}, cost {e['cost']:.1f}",
                  flush=True)
        elif e["event"] == "done":
            print(f"[{e['done']}/{e['total']}] {e['clip']} trained in {e['seconds']:.1f} s "
                  f"on {e['worker']}", flush=True)
        else:
            print(f"[{e['done']}/{e['total']}] {e['path']} FAILED: {e['error']}", flush=True)

    from distributed import Client

    if args.scheduler:
        client = Client(args.scheduler)
    else:  # the client's own cluster, closed with it
        client = Client(n_workers=args.local_workers, threads_per_worker=1, processes=True,
                        dashboard_address=None)
    with client:
        if not args.quiet:
            clips, workers = len(args.clips), len(client.scheduler_info()["workers"])
            print(f"fuzzygait_dask: {clips} clip{'s' * (clips != 1)} on {workers} "
                  f"worker{'s' * (workers != 1)}", flush=True)
        results = train_clips(args.clips, client, progress=progress, retries=args.retries,
                              **options)

    args.out.mkdir(parents=True, exist_ok=True)
    print(f"{'clip':<12} {'status':<7} {'cost before':>11} {'after':>8} {'knee':>6} "
          f"{'s':>6}  worker")
    for r in results:
        if r.ok:
            r.save(args.out / r.clip)
            (args.out / r.clip / "training.json").write_text(json.dumps(r.summary(), indent=2))
            knee = r.after[0]["knee"] if r.after else float("nan")
            print(f"{r.clip:<12} {'ok':<7} {r.cost_before:>11.1f} {r.cost_after:>8.1f} "
                  f"{knee:>6.2f} {r.wall:>6.1f}  {r.worker}")
        else:
            print(f"{r.clip:<12} {'FAILED':<7} {r.error}")
    failed = [r.path for r in results if not r.ok]
    if failed:
        print(f"fuzzygait_dask: {len(failed)} of {len(results)} clips failed: "
              f"{', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    return train(args)


if __name__ == "__main__":
    sys.exit(main())
