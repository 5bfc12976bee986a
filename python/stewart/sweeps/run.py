"""Running a sweep: chunks on a Dask cluster (a LocalCluster, or a running scheduler), each
chunk's Parquet file written as it arrives, then the merged results and plots.

OUT_DIR layout: spec.json (the resolved spec), version.json, chunks/*.parquet (one per chunk;
a rerun computes only the missing ones), envelope.parquet or workspace_<slice>.parquet, *.png,
volume.json (a workspace spec's "volume": the constant-orientation workspace volume [m^3]),
run.json (timings and which worker computed each chunk: not results). Workers that see OUT_DIR
write their chunk files themselves; others send their tables to this process, which writes them."""
from __future__ import annotations

import importlib
import json
import os
import pathlib
import platform as host
import sys
import time
import uuid
from typing import Callable, Optional

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from .spec import Chunk, SpecError, chunks, load, slice_size
from .units import LENGTHS, Units
from .work import envelope_chunk, workspace_chunk


def compute_chunk(spec: dict, chunk: Chunk, out_dir: str) -> tuple[Optional[pa.Table], dict]:
    """One chunk's statistics (seconds, poses, cases, worker address) and its table. A worker
    that sees OUT_DIR (same machine, or a shared file system) writes the chunk file itself and
    returns no table, which saves sending the results through the scheduler's connection."""
    out = pathlib.Path(out_dir)
    writes = (out / "chunks").is_dir() and (out / "spec.json").is_file() and \
        json.loads((out / "spec.json").read_text()) == spec
    cpu = time.process_time()
    if spec["kind"] == "envelope":
        table, stats = envelope_chunk(spec, chunk)
    elif writes:
        # Written block by block as the blocks are solved, in this process's arrays of the
        # previous block and chunk: a worker's arrays are block-sized (no chunk-sized memory to
        # fault in, in its first chunk or a slice's shorter last one).
        with ChunkWriter(out, chunk) as writer:
            table, stats = workspace_chunk(spec, chunk, reuse=True, write=writer.write)
            stats["seconds"] -= writer.seconds  # computing apart from writing, as below
        stats["write_seconds"] = writer.seconds
    else:
        # One sent back must own its arrays.
        table, stats = workspace_chunk(spec, chunk)
    try:
        from distributed import get_worker
        stats["worker"] = get_worker().address
    except (ImportError, ValueError):
        stats["worker"] = "local"
    if writes and table is not None:
        started = time.perf_counter()
        write_chunk(table, out, chunk)
        stats["write_seconds"] = time.perf_counter() - started
        table = None
    # CPU time of this (single-threaded) worker process: on a shared machine it tells how much
    # of a core the chunk really got.
    stats["cpu_seconds"] = time.process_time() - cpu
    return table, stats


def write_chunk(table: pa.Table, out: pathlib.Path, chunk: Chunk) -> None:
    """Writes the chunk's file under a unique temporary name, then renames it into place, so a
    chunk file exists only when complete (an interrupted run leaves it missing)."""
    path = out / "chunks" / chunk.file_name
    tmp = path.with_name(f".{chunk.file_name}.{uuid.uuid4().hex}.tmp")
    write_parquet(table, tmp)
    os.replace(tmp, path)


class ChunkWriter:
    """A chunk's file written table by table (one row group each), as write_chunk writes it:
    under a unique temporary name, renamed into place when closed without an error. seconds: the
    time spent writing."""

    def __init__(self, out: pathlib.Path, chunk: Chunk):
        self.path = out / "chunks" / chunk.file_name
        self.tmp = self.path.with_name(f".{chunk.file_name}.{uuid.uuid4().hex}.tmp")
        self.writer = None
        self.seconds = 0.0

    def write(self, table: pa.Table) -> None:
        started = time.perf_counter()
        if self.writer is None:
            self.writer = pq.ParquetWriter(self.tmp, table.schema, **parquet_options(table.schema))
        self.writer.write_table(table)
        self.seconds += time.perf_counter() - started

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        started = time.perf_counter()
        if self.writer is not None:
            self.writer.close()
            if exc_type is None:
                os.replace(self.tmp, self.path)
            else:
                self.tmp.unlink(missing_ok=True)
        self.seconds += time.perf_counter() - started


def parquet_options(schema: pa.Schema) -> dict:
    """Parquet with dictionaries for the text columns only (on float columns they cost as much
    time as a massless solve and save nothing) and lz4 compression."""
    text = [f.name for f in schema if pa.types.is_string(f.type) or pa.types.is_dictionary(f.type)]
    return {"compression": "lz4", "use_dictionary": text}


def write_parquet(table: pa.Table, path: pathlib.Path) -> None:
    """One file, written with parquet_options."""
    pq.write_table(table, path, **parquet_options(table.schema))


def versions() -> dict:
    """The product's version and those of the pieces that computed the results."""
    import dask
    import distributed
    from .. import __version__
    return {"stewart": __version__, "numpy": np.__version__, "pyarrow": pa.__version__,
            "dask": dask.__version__, "distributed": distributed.__version__,
            "python": sys.version.split()[0], "machine": host.machine()}


def prepare(spec_path, out_dir, scene_dir, platform_file=None,
            scale_to_ranges: bool = False) -> tuple[dict, pathlib.Path]:
    """Loads and checks the spec (SpecError before anything is written; platform_file and
    scale_to_ranges as spec.load takes them), then creates OUT_DIR with spec.json and
    version.json; refuses an OUT_DIR that holds another spec's results."""
    spec = load(spec_path, scene_dir, platform_file, scale_to_ranges)
    out = pathlib.Path(out_dir)
    spec_file = out / "spec.json"
    text = json.dumps(spec, indent=1, sort_keys=True)
    try:
        (out / "chunks").mkdir(parents=True, exist_ok=True)
        if spec_file.exists() and spec_file.read_text() != text:
            raise SpecError(f"OUT_DIR = {out} holds the results of a different spec "
                            f"({spec_file}): use another OUT_DIR or delete it")
        spec_file.write_text(text)
        (out / "version.json").write_text(json.dumps(versions(), indent=1, sort_keys=True))
    except OSError as e:
        raise SpecError(f"OUT_DIR = {out}: cannot write the results there: "
                        f"{e.strerror or e} ({e.filename or out})") from None
    return spec, out


def missing_chunks(spec: dict, out: pathlib.Path) -> list[Chunk]:
    """The chunks without a finished file (files are renamed into place only when complete)."""
    return [c for c in chunks(spec) if not (out / "chunks" / c.file_name).exists()]


def run(spec_path, out_dir, scene_dir, workers: Optional[int] = None,
        scheduler: Optional[str] = None, progress: bool = True,
        log: Callable[[str], None] = print, units: Units | str = Units(),
        platform_file=None, scale_to_ranges: bool = False) -> dict:
    """Runs (or finishes) the sweep of spec_path into out_dir; returns the run summary, also in
    run.json. A chunk that raises is reported and left missing (a rerun retries it). units
    ("mm,deg", or a Units): the lengths and angles of the merged results, the CSV, volume.json
    and the plots (the chunks stay SI); ValueError names a unit that is not one.
    platform_file (a path from the working directory) replaces the spec's platform_file;
    scale_to_ranges sets an envelope's (its scenes scaled to the machine's axis ranges)."""
    units = units if isinstance(units, Units) else Units.parse(units)
    spec, out = prepare(spec_path, out_dir, scene_dir, platform_file, scale_to_ranges)
    todo = missing_chunks(spec, out)
    total = len(chunks(spec))
    log(f"sweep: {total} chunks, {total - len(todo)} already done, {len(todo)} to compute")
    summary = {"chunks": total, "computed": [], "failed_chunks": [], "wall_seconds": 0.0}
    if todo:
        started = time.perf_counter()
        with _client(workers, scheduler) as client:
            summary["workers"] = len(client.scheduler_info()["workers"])
            # Workers import the solver and pyarrow now, as part of the start-up, not in the
            # first chunk each computes.
            client.run(importlib.import_module, "stewart.sweeps.work")
            summary["startup_seconds"] = time.perf_counter() - started
            started = time.perf_counter()
            _compute_all(client, spec, todo, out, summary, progress, log)
            summary["wall_seconds"] = time.perf_counter() - started
    merge(spec, out, units)
    if "volume" in spec:
        write_volume(spec, out, units)
    from .plots import plot
    plot(spec, out, units)
    (out / "run.json").write_text(json.dumps(summary, indent=1))
    if summary["failed_chunks"]:
        raise RuntimeError(f"{len(summary['failed_chunks'])} chunks raised (see run.json); "
                           "run again to retry them")
    return summary


class _client:
    """A distributed Client on a running scheduler, or on a LocalCluster it starts and stops."""

    def __init__(self, workers: Optional[int], scheduler: Optional[str]):
        self.workers, self.scheduler = workers, scheduler
        self.cluster = None

    def __enter__(self):
        from distributed import Client, LocalCluster
        if self.scheduler:
            self.client = Client(self.scheduler, timeout="30s")
        else:
            self.cluster = LocalCluster(n_workers=self.workers or os.cpu_count() or 1,
                                        threads_per_worker=1, processes=True,
                                        host="127.0.0.1", dashboard_address=":0")
            self.client = Client(self.cluster)
        return self.client

    def __exit__(self, *exc):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _compute_all(client, spec, todo, out, summary, progress, log):
    from distributed import as_completed
    from tqdm import tqdm
    spec_future = client.scatter(spec, broadcast=True)
    futures = {client.submit(compute_chunk, spec_future, c, str(out.resolve()), pure=False): c
               for c in todo}
    unit = "case" if spec["kind"] == "envelope" else "pose"
    sizes = {c: c.stop - c.start for c in todo}
    with tqdm(total=sum(sizes.values()), unit=unit, disable=not progress, smoothing=0.1) as bar:
        for future in as_completed(futures):
            chunk = futures[future]
            try:
                table, stats = future.result()
            except Exception as e:  # a bug, not a failing case: those are rows with a status
                log(f"sweep: chunk {chunk.file_name} raised {type(e).__name__}: {e}")
                summary["failed_chunks"].append({"chunk": chunk.file_name, "error": str(e)})
                continue
            if table is not None:  # the worker could not write it
                write_chunk(table, out, chunk)
            summary["computed"].append({"chunk": chunk.file_name, **stats})
            bar.update(sizes[chunk])


def merge(spec: dict, out: pathlib.Path, units: Units = Units()) -> list[pathlib.Path]:
    """The chunk files of each part, in chunk order, as one Parquet file per part (workspace
    slices get a `boundary` column), lengths and angles in `units` (each field's unit in its
    metadata), and the envelope also as envelope.csv. Parts with missing chunks are left
    unmerged."""
    parts: dict[str, list[Chunk]] = {}
    for c in chunks(spec):
        parts.setdefault(c.part, []).append(c)
    written = []
    for part, cs in parts.items():
        files = [out / "chunks" / c.file_name for c in cs]
        if not all(f.exists() for f in files):
            continue
        table = pa.concat_tables(pq.read_table(f) for f in files)
        if spec["kind"] == "envelope":
            path = out / "envelope.parquet"
        else:
            s = next(x for x in spec["slices"] if x["name"] == part)
            assert table.num_rows == slice_size(s)
            table = table.append_column("boundary", pa.array(boundary(s, table["reachable"].to_numpy())))
            path = out / f"workspace_{part}.parquet"
        table = in_units(table, units)
        write_parquet(table, path)
        written.append(path)
        if spec["kind"] == "envelope":
            write_csv(table, out / "envelope.csv")
            written.append(out / "envelope.csv")
    return written


def in_units(table: pa.Table, units: Units) -> pa.Table:
    """The table with its lengths and angles in units, each field's unit in its metadata."""
    import pyarrow.compute as pc
    columns, fields = [], []
    for f, column in zip(table.schema, table.columns):
        factor = units.factor(f.name)
        if factor != 1.0:
            column = pc.multiply(column, pa.scalar(factor, pa.float64()))
        unit = units.unit(f.name)
        fields.append(pa.field(f.name, column.type, f.nullable,
                               {"unit": unit} if unit else None))
        columns.append(column)
    return pa.Table.from_arrays(columns, schema=pa.schema(fields))


def write_csv(table: pa.Table, path: pathlib.Path) -> None:
    """The table as CSV (numbers as Python writes them: the same in every locale), the unit of
    each column in its header as `name [unit]`."""
    import csv
    names = [f"{f.name} [{f.metadata[b'unit'].decode()}]" if f.metadata else f.name
             for f in table.schema]
    rows = zip(*(c.to_pylist() for c in table.columns))
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(names)
        writer.writerows(["" if v is None else v for v in r] for r in rows)


def write_volume(spec: dict, out: pathlib.Path, units: Units = Units()) -> None:
    """volume.json: the spec's platform's constant-orientation workspace volume (at the spec's
    orientation, or home's), within every limit (the options' warn_condition for the
    condition), with its error estimate and the box that holds it, in this process."""
    from ..platform import Platform
    from .volume import workspace_volume
    v = spec["volume"]
    started = time.perf_counter()
    result = workspace_volume(Platform(**spec["platform"]), v["orientation"], v["cells"],
                              warn_condition=spec["options"].get("warn_condition"),
                              accuracy=v["accuracy"], details=True)
    (out / "volume.json").write_text(json.dumps(
        {"volume_m3": result.volume, "error_estimate_m3": result.error_estimate,
         "accuracy": v["accuracy"], "orientation": list(result.orientation),
         "box_m": result.box.tolist(), "cells": result.cells,
         "grids": [list(g) for g in result.grids], "note": result.note,
         "volume": result.volume * LENGTHS[units.length] ** 3,
         "error_estimate": result.error_estimate * LENGTHS[units.length] ** 3,
         "volume_unit": f"{units.length}^3",
         "seconds": time.perf_counter() - started}, indent=1))


def boundary(s: dict, reachable: np.ndarray) -> np.ndarray:
    """Reachable grid points with an unreachable grid neighbour along some axis: the boundary of
    the reachable workspace in the slice (the grid's own edge is not marked)."""
    grid = reachable.reshape([len(v) for v in s["axes"].values()])
    edge = np.zeros_like(grid)
    for axis in range(grid.ndim):
        ahead = np.zeros_like(grid)
        behind = np.zeros_like(grid)
        sl = [slice(None)] * grid.ndim
        sl_next = [slice(None)] * grid.ndim
        sl[axis], sl_next[axis] = slice(0, -1), slice(1, None)
        ahead[tuple(sl)] = ~grid[tuple(sl_next)]
        behind[tuple(sl_next)] = ~grid[tuple(sl)]
        edge |= ahead | behind
    return (grid & edge).reshape(-1)
