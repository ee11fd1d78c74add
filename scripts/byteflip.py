#!/usr/bin/env python3
"""Byte-flip robustness harness: runs a command on many randomly corrupted copies of one file (standard library only).

Each case copies the file (or, with --dir, the whole directory holding it) into a fresh temporary directory, changes
1 to --max-flips bytes at random offsets of the copy (anywhere, or within --range) to other random values, runs the
command with a timeout and records how it ended: an exit code, a signal or a timeout. A reader that never crashes
ends every case with 0 (the flip hit a byte that does not matter) or a documented error code; a signal, a timeout or
an exit code listed in --bad-exit (default 1, rfrecon's "internal error: a bug") is a bug.

  byteflip.py --file T.h5 [--cases 400] [--seed 1] -- build/rfrecon dual {} -o {out}.tif
  byteflip.py --dir CAPTURE --file manifest.json -- build/rfrecon transport {} -o {out}.h5

In the command's arguments `{}` is replaced by the corrupted copy (the copied directory with --dir, else the copied
file) and `{out}` by a path that does not exist yet inside the case's temporary directory. The unmodified copy runs
first (the baseline); it must exit 0. Case k draws its flips from a generator seeded with (seed, k) alone, so
`--seed S --only k` reruns one case of a run; --keep DIR keeps the copies of the cases that are bugs.

Prints a table of outcomes (and every bug with its flips and the last line of its stderr); --json FILE also writes
every case. Exit status 0 when no case is a bug, 1 when some are, 2 on bad usage or a failing baseline.
"""
import argparse
import collections
import concurrent.futures
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--file", required=True, help="the file to corrupt (relative to --dir when given)")
    parser.add_argument("--dir", help="copy this whole directory per case and corrupt --file inside it")
    parser.add_argument("--cases", type=int, default=400, help="number of corrupted copies (default 400)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the flips (default 1)")
    parser.add_argument("--only", type=int, action="append", help="run only this case number (repeatable)")
    parser.add_argument("--max-flips", type=int, default=3, help="bytes changed per case: 1 to this (default 3)")
    parser.add_argument("--range", default=":", help="flip only offsets START:END (END exclusive; default all)")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per run before it counts as hung")
    parser.add_argument("--jobs", type=int, default=1, help="cases run at once (default 1)")
    parser.add_argument("--bad-exit", type=int, action="append", help="exit codes that are bugs (default: 1)")
    parser.add_argument("--json", help="write every case and the summary to this JSON file")
    parser.add_argument("--keep", help="copy the corrupted inputs of the bug cases into this directory")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND ARGS... ({} and {out} replaced)")
    args = parser.parse_args(argv)
    if args.command[:1] == ["--"]:
        args.command = args.command[1:]
    if not args.command:
        parser.error("no command given (put it after --)")
    if not any("{}" in word for word in args.command):
        parser.error("the command does not name the corrupted copy ({})")
    if args.cases < 1 or args.max_flips < 1 or args.jobs < 1 or args.timeout <= 0:
        parser.error("--cases, --max-flips and --jobs must be at least 1, --timeout positive")
    args.source = os.path.join(args.dir, args.file) if args.dir else args.file
    if not os.path.isfile(args.source) or os.path.getsize(args.source) == 0:
        parser.error(f"{args.source} is not a non-empty file")
    if args.dir and os.path.isabs(args.file):
        parser.error("with --dir, --file is a path relative to the directory")
    args.bad_exit = set(args.bad_exit or [1])
    try:
        start, end = (int(part) if part else default for part, default in zip(args.range.split(":"), (0, None)))
    except ValueError:
        parser.error("--range is START:END, byte offsets")
    args.offsets = range(os.path.getsize(args.source))[start:end]
    if not args.offsets:
        parser.error(f"--range {args.range} holds no byte of {args.source}")
    return args


def draw_flips(offsets, seed, case, max_flips):
    """The (offset, XOR mask) pairs of one case: distinct offsets drawn from the range `offsets`."""
    rng = random.Random(f"{seed}:{case}")
    offsets = rng.sample(offsets, min(len(offsets), rng.randint(1, max_flips)))
    return [(offset, rng.randrange(1, 256)) for offset in sorted(offsets)]  # XOR mask: never the same byte


def prepare(args, work):
    """Copies the input into `work`; returns (the path that {} stands for, the path of the file to corrupt)."""
    if args.dir:
        target = os.path.join(work, os.path.basename(os.path.normpath(args.dir)))
        shutil.copytree(args.dir, target, symlinks=True)
        return target, os.path.join(target, args.file)
    target = os.path.join(work, os.path.basename(args.file))
    shutil.copyfile(args.file, target)
    return target, target


def describe(returncode):
    if returncode < 0:
        try:
            return "signal " + signal.Signals(-returncode).name
        except ValueError:
            return f"signal {-returncode}"
    return f"exit {returncode}"


def run_case(args, case, flips):
    """Runs one case (flips None: the baseline); returns its record."""
    with tempfile.TemporaryDirectory(prefix="byteflip-") as work:
        target, victim = prepare(args, work)
        changes = []
        with open(victim, "r+b") as f:
            for offset, mask in flips or []:
                f.seek(offset)
                old = f.read(1)[0]
                f.seek(offset)
                f.write(bytes([old ^ mask]))
                changes.append({"offset": offset, "old": old, "new": old ^ mask})
        out = os.path.join(work, "out")
        command = [word.replace("{out}", out).replace("{}", target) for word in args.command]
        start = time.monotonic()
        try:
            done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=args.timeout)
            outcome, stderr = describe(done.returncode), done.stderr
        except subprocess.TimeoutExpired as expired:
            outcome, stderr = "timeout", expired.stderr or b""
        except OSError as error:  # e.g. the program is being rebuilt
            outcome, stderr = "cannot start", str(error).encode()
        lines = stderr.decode(errors="replace").strip().splitlines()
        record = {"case": case, "flips": changes, "outcome": outcome, "seconds": round(time.monotonic() - start, 3),
                  "stderr_last_line": lines[-1] if lines else ""}
        if args.keep and flips is not None and is_bug(args, outcome):
            os.makedirs(args.keep, exist_ok=True)
            kept = os.path.join(args.keep, f"case-{case:04d}-{os.path.basename(target)}")
            shutil.rmtree(kept, ignore_errors=True)
            (shutil.copytree if os.path.isdir(target) else shutil.copyfile)(target, kept)
        return record


def is_bug(args, outcome):
    return not outcome.startswith("exit ") or int(outcome.split()[1]) in args.bad_exit


def main(argv):
    args = parse_args(argv)
    size = os.path.getsize(args.source)
    baseline = run_case(args, None, None)
    if baseline["outcome"] != "exit 0":
        print(f"baseline (no flips) ended with {baseline['outcome']}: {baseline['stderr_last_line']}", file=sys.stderr)
        return 2
    cases = args.only or range(args.cases)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_case, args, case, draw_flips(args.offsets, args.seed, case, args.max_flips))
                   for case in cases]
        records = [future.result() for future in futures]
    counts = collections.Counter(record["outcome"] for record in records)
    bugs = [record for record in records if is_bug(args, record["outcome"])]

    where = f"offsets [{args.offsets.start}, {args.offsets.stop}) of" if len(args.offsets) < size else "all of"
    print(f"{len(records)} cases, 1 to {args.max_flips} bytes changed in {where} {args.source} ({size} bytes),"
          f" seed {args.seed}")
    print(f"command: {' '.join(args.command)}")
    print(f"baseline: {baseline['outcome']} in {baseline['seconds']} s")
    print(f"{'outcome':<16} {'cases':>6}")
    for outcome, count in sorted(counts.items(), key=lambda item: (not item[0].startswith("exit "), item[0])):
        print(f"{outcome:<16} {count:>6}{'   <- bug' if is_bug(args, outcome) else ''}")
    for record in bugs:
        flips = ", ".join(f"@{flip['offset']}: {flip['old']:#04x}->{flip['new']:#04x}" for flip in record["flips"])
        print(f"case {record['case']}: {record['outcome']} ({flips}): {record['stderr_last_line']}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"file": args.source, "size": size, "seed": args.seed, "range": args.range,
                       "command": args.command, "baseline": baseline, "counts": dict(counts), "bugs": len(bugs),
                       "cases": records}, f, indent=1)
    return 1 if bugs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
