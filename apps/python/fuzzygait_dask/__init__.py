# fuzzygait_dask: fuzzygait's training and walks on a Dask cluster. MIT License (see LICENSE).
"""Trains sets on many clips, and walks a set at many bodies and paces, on Dask workers.

Every worker needs `import fuzzygait` (the module built into build/python, on its PYTHONPATH) and
this package; nothing else is shared: clips, leg mappings and sets travel as bytes. A clip trained
on a worker gives the same set files, byte for byte, as `fuzzygait.train` in-process with the same
options (tested).

    from distributed import Client
    import fuzzygait_dask as fgd
    with Client("tcp://scheduler:8786") as client:
        for r in fgd.train_clips(["a.bvh", "b.bvh"], client, generations=200):
            print(r.clip, r.cost_after if r.ok else r.error)
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import pathlib
import tempfile
import threading
import time
import uuid
from typing import Any, Callable, Iterable, Optional

__all__ = ["ClipFailed", "ClipResult", "train_clips", "walk_many", "grid", "set_files"]

# Set files as {relative path: bytes}: what a set folder holds, sent to and from workers.
Files = dict


class Blob(bytes):
    """A file's bytes that print as their length (in a worker's log of a failed task)."""

    def __repr__(self) -> str:
        return f"<{len(self)} bytes>"


class ClipFailed(Exception):
    """A clip's training failed on a worker: args are (the clip's path, "Type: message")."""

    def __str__(self) -> str:
        return f"{self.args[0]}: {self.args[1]}"


@dataclasses.dataclass
class ClipResult:
    """One clip's training: the set's files and train()'s figures, or why it failed.

    `before` and `after` are train()'s per-clip scores with `report` as a dict (GaitReport's JSON);
    `seconds` is the training's time, `wall` the task's on its worker (reading the clip included).
    """

    clip: str                    # the clip's name (its file's stem), as train() names it
    path: str                    # the file as given
    ok: bool
    error: Optional[str] = None  # "Type: message" when not ok
    files: Files = dataclasses.field(default_factory=dict)
    cost_before: float = float("nan")
    cost_after: float = float("nan")
    before: list = dataclasses.field(default_factory=list)
    after: list = dataclasses.field(default_factory=list)
    stages: list = dataclasses.field(default_factory=list)
    added: list = dataclasses.field(default_factory=list)
    seconds: float = 0.0
    wall: float = 0.0
    stopped: bool = False
    worker: str = ""

    def save(self, folder) -> pathlib.Path:
        """Writes the set (manifest.json and FLL files) into `folder`; returns it."""
        folder = pathlib.Path(folder)
        write_files(folder, self.files)
        return folder

    def load(self):
        """The trained set, a fuzzygait.ControllerSet."""
        import fuzzygait as fg

        with tempfile.TemporaryDirectory(prefix="fuzzygait-set-") as tmp:
            return fg.ControllerSet.load(self.save(tmp))

    def summary(self) -> dict:
        """Everything but the set's files, as JSON-ready data."""
        d = dataclasses.asdict(self)
        del d["files"]
        return d


def set_files(controller_set) -> Files:
    """A set's files: a ControllerSet's (saved) or a folder's; {} for a built-in name."""
    if isinstance(controller_set, str) and not pathlib.Path(controller_set).is_dir():
        return {}
    if isinstance(controller_set, (str, pathlib.Path)):
        return read_files(pathlib.Path(controller_set))
    with tempfile.TemporaryDirectory(prefix="fuzzygait-set-") as tmp:
        controller_set.save(tmp)
        return read_files(pathlib.Path(tmp))


def read_files(folder: pathlib.Path) -> Files:
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def write_files(folder: pathlib.Path, files: Files) -> None:
    for name, data in files.items():
        target = folder / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)


def _base_argument(base) -> Any:
    """What a worker gets for train()'s base: a built-in name, or the set's files."""
    if isinstance(base, str) and not pathlib.Path(base).is_dir():
        return base
    return set_files(base)


def _load_base(base, tmp: pathlib.Path):
    import fuzzygait as fg

    if isinstance(base, str):
        return base
    write_files(tmp / "base", base)
    return fg.ControllerSet.load(tmp / "base")


def _send_progress(topic: Optional[str], clip: str, every: float) -> Optional[Callable]:
    """train()'s progress callback on a worker: at most one event every `every` seconds."""
    if topic is None:
        return None
    from distributed import get_worker

    worker = get_worker()
    last = [0.0]

    def progress(p: dict) -> None:
        now = time.monotonic()
        if now - last[0] >= every:
            last[0] = now
            worker.log_event(topic, dict(p, clip=clip, event="iteration"))

    return progress


def train_one(name: str, path: str, bvh: bytes, mapping: Optional[tuple], base, options: dict,
              topic: Optional[str] = None, every: float = 2.0) -> ClipResult:
    """Trains a set on one clip given as bytes (the task each worker runs; in-process too).

    `mapping` is a leg mapping file's (name, bytes), `base` a built-in name or a set's files.
    Raises ClipFailed naming the clip when reading or training fails.
    """
    import fuzzygait as fg

    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="fuzzygait-train-") as tmp_text:
        tmp = pathlib.Path(tmp_text)
        clip_file = tmp / f"{name}.bvh"  # train() names a clip after its file's stem
        clip_file.write_bytes(bvh)
        options = dict(options)
        if mapping is not None:
            options["map"] = tmp / mapping[0]  # errors name the file as its owner named it
            options["map"].write_bytes(mapping[1])
        try:
            t = fg.train([clip_file], _load_base(base, tmp),
                         progress=_send_progress(topic, name, every), **options)
            trained = tmp / "set"
            t.set.save(trained)
            files = read_files(trained)
        except Exception as e:  # reported with the clip's own file name, not the worker's copy
            message = str(e).replace(str(clip_file), path).replace(str(tmp) + "/", "")
            raise ClipFailed(path, f"{type(e).__name__}: {message}") from None

    def scores(per_clip):
        return [dict(s, report=json.loads(s["report"].to_json())) for s in per_clip]

    try:
        from distributed import get_worker
        worker = get_worker().address
    except (ImportError, ValueError):
        worker = "in-process"
    return ClipResult(clip=name, path=path, ok=True, files=files, cost_before=t.cost_before,
                      cost_after=t.cost_after, before=scores(t.before), after=scores(t.after),
                      stages=list(t.stages), added=list(t.added), seconds=t.seconds,
                      wall=time.perf_counter() - started, stopped=t.stopped, worker=worker)


def train_clips(clips: Iterable, client=None, *, progress: Optional[Callable[[dict], None]] = None,
                retries: int = 0, every: float = 2.0, **train_options) -> list:
    """Trains one set per clip (BVH paths), each by fuzzygait.train on a Dask worker.

    `client` is a distributed.Client (None: the current default client). `train_options` are
    fuzzygait.train's (base, generations, polish, threads, seed, map, up, unit, skip, ...); `base`
    may be a built-in name, a set folder or a ControllerSet, `map` a leg mapping file: both are
    sent as bytes. Returns a ClipResult per clip, in the clips' order; a clip that fails (after
    `retries` more attempts, each failed one logged by its worker) has ok False and
    `error`, and the others still train. `progress(dict)` is called on the client: an "iteration"
    event from a training at most every `every` seconds (stage, iteration, cost, rmse), then
    "done" or "failed" as each clip ends (clip, done, total, seconds, worker, error).
    """
    from distributed import as_completed, default_client

    client = client or default_client()
    paths = [str(c) for c in clips]
    names = [pathlib.Path(p).stem for p in paths]
    options = dict(train_options)
    for forbidden in ("progress", "clips"):
        if forbidden in options:
            raise TypeError(f"train_clips: {forbidden} is not a train option here")
    base = _base_argument(options.pop("base", "default"))
    mapping = options.pop("map", None)
    if mapping is not None:
        mapping = (pathlib.Path(mapping).name, Blob(pathlib.Path(mapping).read_bytes()))

    run = uuid.uuid4().hex[:8]
    topic = f"fuzzygait-train-{run}" if progress else None
    lock = threading.Lock()  # events arrive on the client's loop thread, results on this one

    def report(event: dict) -> None:
        if progress:
            with lock:
                progress(event)

    if topic:
        client.subscribe_topic(topic, lambda event: report(event[1]))
    try:
        results: list = [None] * len(paths)

        def finish(i: int, r: ClipResult) -> None:
            results[i] = r
            done = sum(x is not None for x in results)
            report({"event": "done" if r.ok else "failed", "clip": r.clip, "path": r.path,
                    "done": done, "total": len(paths), "seconds": r.wall, "worker": r.worker,
                    "error": r.error})

        futures = {}
        for i, (name, path) in enumerate(zip(names, paths)):
            try:
                data = Blob(pathlib.Path(path).read_bytes())
            except OSError as e:  # a clip that cannot be read here fails alone
                finish(i, ClipResult(name, path, ok=False, error=f"{type(e).__name__}: {e}"))
                continue
            future = client.submit(train_one, name, path, data, mapping, base, options, topic,
                                   every, key=f"fuzzygait-train-{name}-{run}-{i}",
                                   retries=retries, pure=False)
            futures[future] = i
        for future in as_completed(futures):
            i = futures[future]
            try:
                r = future.result()
            except Exception as e:  # the worker's ClipFailed, or a lost worker's error
                text = e.args[1] if isinstance(e, ClipFailed) else f"{type(e).__name__}: {e}"
                r = ClipResult(names[i], paths[i], ok=False, error=text)
            finish(i, r)
        return results
    finally:
        if topic:
            client.unsubscribe_topic(topic)


# The set of each content hash a worker process has loaded (walk_many's tasks share it).
_loaded_sets: dict = {}


def _walk_one(files: Files, digest: str, walk: dict, cycles: int, reference) -> dict:
    """Walks one body and pace with a set given as files; its evaluation as a dict."""
    import fuzzygait as fg

    controller_set = _loaded_sets.get(digest)
    if controller_set is None:
        with tempfile.TemporaryDirectory(prefix="fuzzygait-set-") as tmp:
            write_files(pathlib.Path(tmp), files)
            controller_set = fg.ControllerSet.load(pathlib.Path(tmp))
        _loaded_sets[digest] = controller_set
    result = dict(walk)
    try:
        motion = fg.Walker(controller_set, **walk).record_cycles(cycles)
        report = fg.evaluate(motion, reference=reference)
        result.update(ok=True, report=json.loads(report.to_json()),
                      missed=report.missed_contact_bounds())
    except (ValueError, RuntimeError) as e:  # bad options; a walk that stalls before its cycles
        result.update(ok=False, error=f"{type(e).__name__}: {e}")
    return result


def grid(speeds: Iterable[float], statures: Iterable[float]) -> list:
    """Walker options of every speed (m/s) at every stature (m)."""
    return [{"speed": v, "stature": h} for h in statures for v in speeds]


def walk_many(controller_set, walks: Iterable[dict], client=None, *, cycles: int = 10,
              reference: Optional[str] = "schwartz2008_free") -> list:
    """Walks a set with each dict of Walker options (e.g. grid(speeds, statures)) on the workers.

    The set (a ControllerSet, a folder or a built-in name) is scattered once to every worker.
    Returns per walk its options plus ok, and report (GaitReport's JSON as a dict) and missed
    (missed_contact_bounds()) or error: what fuzzygait.evaluate says of record_cycles(cycles).
    """
    import fuzzygait as fg
    from distributed import default_client

    client = client or default_client()
    if isinstance(controller_set, str) and not pathlib.Path(controller_set).is_dir():
        controller_set = fg.ControllerSet.builtin(controller_set)
    files = set_files(controller_set)
    digest = hashlib.sha256()
    for name, data in sorted(files.items()):
        digest.update(name.encode() + b"\0" + data + b"\0")
    [scattered] = client.scatter([files], broadcast=True, hash=False)
    walks = [dict(w) for w in walks]
    key = digest.hexdigest()
    futures = [client.submit(_walk_one, scattered, key, w, cycles, reference, pure=False)
               for w in walks]
    return client.gather(futures)
