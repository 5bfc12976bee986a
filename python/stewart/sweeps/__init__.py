"""Sweeps on Dask: load envelopes and workspace/singularity maps (scripts/sweep.py runs them;
docs/sweeps.md describes the spec). Needs the `sweeps` extras: dask, distributed, pyarrow, tqdm,
matplotlib."""
from .run import merge, run
from .spec import Chunk, SpecError, chunks, load, resolve
from .volume import WorkspaceVolume, workspace_volume

__all__ = ["run", "merge", "load", "resolve", "chunks", "Chunk", "SpecError", "workspace_volume",
           "WorkspaceVolume"]
