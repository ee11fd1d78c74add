"""Many scans on a Dask cluster: each scan's transport and reconstruction as tasks keyed by their output files.

Every stage is idempotent: it writes one output (T.h5, a reconstruction directory) atomically, and a stage whose
output exists is skipped, so a batch that was interrupted or resubmitted redoes only what is missing. The tasks'
keys are derived from the output paths, so submitting the same scan twice to one scheduler runs it once. Results
come back as files under ``out_dir`` and a summary table (``summary.csv``, one row per scan). docs/python.md shows
the same code on a LocalCluster, on Slurm through dask-jobqueue, and on any scheduler address.
"""
from __future__ import annotations

import csv
import hashlib
import json
import os
import tempfile
import threading
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from . import _rfrecon

__all__ = ["Scan", "ScanResult", "reconstruct_scans", "run_scan"]

SUMMARY_COLUMNS = ["name", "capture", "transport", "reconstruction", "method", "status", "reconstructed_pixels",
                   "transport_seconds", "reconstruct_seconds", "warnings"]


@dataclass(frozen=True)
class Scan:
    """One scan: its capture directory (manifest.json or OpenCV's Gray-code layout) and its name under out_dir."""

    capture: str
    name: str = ""
    layout: str = ""
    projector_size: tuple[int, int] | None = None

    def label(self) -> str:
        return self.name or Path(self.capture).name


@dataclass
class ScanResult:
    """What one scan left in out_dir/NAME and what each stage did ("made" or "kept": its output existed)."""

    name: str
    capture: str
    transport: str
    reconstruction: str
    method: str
    status: str
    reconstructed_pixels: int = 0
    transport_seconds: float = 0.0
    reconstruct_seconds: float = 0.0
    warnings: list[str] = field(default_factory=list)


# One Session per worker process, shared by its threads one call at a time: opening devices and building programs
# is paid once per worker, not per scan.
_session_lock = threading.Lock()
_sessions: dict[str, _rfrecon.Session] = {}


def _session(devices: str) -> _rfrecon.Session:
    if devices not in _sessions:
        _sessions[devices] = _rfrecon.Session(devices)
    return _sessions[devices]


def run_scan(scan: Scan, rig_file: str, out_dir: str, method: str = "fused", devices: str = "",
             entries_per_pixel: int = 8) -> ScanResult:
    """Transport and reconstruction of one scan into out_dir/NAME/{T.h5, reconstruction/}, each skipped if present.

    Runs where it is called: in a Dask worker through reconstruct_scans, or directly for a serial loop.
    """
    scan_dir = Path(out_dir) / scan.label()
    transport_file = scan_dir / "T.h5"
    reconstruction_dir = scan_dir / "reconstruction"
    result = ScanResult(scan.label(), str(scan.capture), str(transport_file), str(reconstruction_dir), method, "")
    scan_dir.mkdir(parents=True, exist_ok=True)
    stages = []
    with _session_lock:
        session = _session(devices)
        transport = None
        if transport_file.exists():
            stages.append("transport kept")
        else:
            start = time.perf_counter()
            capture = _rfrecon.Capture.from_directory(scan.capture, scan.layout, scan.projector_size)
            transport, result.warnings = session.transport(capture, entries_per_pixel)
            _rfrecon.write_transport(transport, transport_file)
            result.transport_seconds = time.perf_counter() - start
            stages.append("transport made")
        if (reconstruction_dir / "summary.json").exists():
            stages.append("reconstruction kept")
        else:
            start = time.perf_counter()
            if transport is None:
                transport = _rfrecon.read_transport(transport_file)
            maps = session.reconstruct(transport, _rfrecon.read_rig(rig_file), method)
            maps["summary"]["transport_file"] = str(transport_file)
            maps["summary"]["calibration_file"] = str(rig_file)
            _rfrecon.write_reconstruction(maps, reconstruction_dir)
            result.reconstruct_seconds = time.perf_counter() - start
            stages.append("reconstruction made")
    summary = json.loads((reconstruction_dir / "summary.json").read_text())
    result.reconstructed_pixels = int(summary.get("reconstructed_pixels", 0))
    result.status = ", ".join(stages)
    return result


def _key(stage: str, *paths: str) -> str:
    digest = hashlib.sha1("\0".join(os.path.abspath(p) for p in paths).encode()).hexdigest()[:16]
    return f"rfrecon-{stage}-{digest}"


def write_summary(results: list[ScanResult], file: str | os.PathLike) -> None:
    """The summary table as CSV, written atomically (a temporary file renamed into place)."""
    file = Path(file)
    with tempfile.NamedTemporaryFile("w", newline="", dir=file.parent, prefix=f".{file.name}.", delete=False) as out:
        writer = csv.DictWriter(out, SUMMARY_COLUMNS)
        writer.writeheader()
        for result in results:
            row = asdict(result)
            row["warnings"] = " | ".join(row["warnings"])
            writer.writerow(row)
    os.replace(out.name, file)


def _failed(scan: Scan, out_dir: str, method: str, error: BaseException) -> ScanResult:
    scan_dir = Path(out_dir) / scan.label()
    return ScanResult(scan.label(), str(scan.capture), str(scan_dir / "T.h5"), str(scan_dir / "reconstruction"),
                      method, f"failed: {type(error).__name__}: {error}")


def reconstruct_scans(client, scans: list[Scan | str], rig_file: str, out_dir: str, method: str = "fused",
                      devices: str = "", entries_per_pixel: int = 8) -> list[ScanResult]:
    """Reconstructs every scan with one rig on a dask.distributed Client (None: here, one after another).

    Each scan is one task keyed by its output directory. Results come back in the order of `scans` and go to
    out_dir/summary.csv; a scan that fails with an rfrecon error (its capture unreadable, nothing decoded) is a row
    whose status starts with "failed:" and the message, and a rerun redoes only the scans without their outputs.
    Scan names must be unique.
    """
    scans = [Scan(str(s)) if isinstance(s, (str, os.PathLike)) else s for s in scans]
    names = [scan.label() for scan in scans]
    repeated = sorted({name for name in names if names.count(name) > 1})
    if repeated:
        raise _rfrecon.UsageError(f"reconstruct_scans: scan names repeat: {repeated}")
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    arguments = (rig_file, out_dir, method, devices, entries_per_pixel)
    results = []
    if client is None:
        for scan in scans:
            try:
                results.append(run_scan(scan, *arguments))
            except _rfrecon.Error as error:
                results.append(_failed(scan, out_dir, method, error))
    else:
        from distributed import wait

        futures = [client.submit(run_scan, scan, *arguments, key=_key("scan", str(Path(out_dir) / scan.label())))
                   for scan in scans]
        wait(futures)
        for scan, future in zip(scans, futures):
            error = future.exception() if future.status == "error" else None
            if error is not None and not isinstance(error, _rfrecon.Error):
                raise error
            results.append(future.result() if error is None else _failed(scan, out_dir, method, error))
    write_summary(results, Path(out_dir) / "summary.csv")
    return results
