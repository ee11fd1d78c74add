#!/usr/bin/env python3
"""Lints the OpenCL C kernels as the FPGA flows compile them (standard library and clang only).

Every kernels/**/*.cl is compiled with clang as OpenCL C 1.2 (`-x cl -cl-std=CL1.2 -fsyntax-only`, include path
kernels/) once per target macro: none (PoCL, GPUs), RF_TARGET_INTEL_FPGA (aoc) and RF_TARGET_XILINX_FPGA (v++), with
-Wall -Wextra -pedantic. Any error fails, and so does any warning outside ALLOWED below: the vendor attributes and
pragmas of kernels/common/target.h, which clang does not know, each allowed for its own target only. Then all .cl
files together in one translation unit per target, as the hw/ flows put them into one binary per board (a helper
defined in two files would collide there). Last, each single work-item entry (a kernel whose name ends in `_single`)
must carry RF_SINGLE_TASK, and no other kernel may.

This is what CI can check without vendor tools: it proves the files parse under each macro, not that aoc or v++
accept them or what they schedule (docs/fpga.md).

Exit status 0 when everything holds, 1 with one `path:line: message` line per problem, 2 on bad usage.

  lint_kernels.py [--root DIR] [--kernels DIR] [--include DIR]... [--clang PATH]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

TARGETS = [None, "RF_TARGET_INTEL_FPGA", "RF_TARGET_XILINX_FPGA"]

# (target macro, warning flag, attribute or pragma name): the warnings clang may give for that target, no others.
ALLOWED = {
    # aoc: RF_SINGLE_TASK is max_global_work_dim(0), RF_PARTITION_COMPLETE is register (clang knows neither).
    ("RF_TARGET_INTEL_FPGA", "-Wunknown-attributes", "max_global_work_dim"),
    ("RF_TARGET_INTEL_FPGA", "-Wunknown-attributes", "register"),
    # aoc: RF_PIPELINE_II(n) is `#pragma ii n`, RF_IVDEP_SAFELEN(n) is `#pragma ivdep safelen(n)` (`unroll` is known).
    ("RF_TARGET_INTEL_FPGA", "-Wunknown-pragmas", "ii"),
    ("RF_TARGET_INTEL_FPGA", "-Wunknown-pragmas", "ivdep"),
    # v++: RF_PIPELINE_II(n) is xcl_pipeline_loop(n), RF_PARTITION_COMPLETE is xcl_array_partition(complete, 1)
    # (RF_SINGLE_TASK is reqd_work_group_size and RF_UNROLL opencl_unroll_hint, which clang knows).
    ("RF_TARGET_XILINX_FPGA", "-Wunknown-attributes", "xcl_pipeline_loop"),
    ("RF_TARGET_XILINX_FPGA", "-Wunknown-attributes", "xcl_array_partition"),
}

# Build options every program gets. __OPENCL_VERSION__ is defined by an OpenCL implementation (PoCL, aoc, v++), not
# by clang itself (which defines only __OPENCL_C_VERSION__); the shared headers (kernels/depth/reciprocity.h) test it.
# K and the row interleave come from the generated common/params.h (--include names its directory), as in the flows.
COMMON_OPTIONS = ["-x", "cl", "-cl-std=CL1.2", "-fsyntax-only", "-D__OPENCL_VERSION__=120",
                  "-Wall", "-Wextra", "-pedantic", "-fno-color-diagnostics", "-fmacro-backtrace-limit=0"]

DIAGNOSTIC = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+):(?P<col>\d+): (?P<severity>warning|error|fatal error): "
                        r"(?P<message>.*?)(?: \[(?P<flag>-W[^\],]+)[^\]]*\])?$")
ATTRIBUTE = re.compile(r"unknown attribute '(\w+)' ignored")
PRAGMA_IN_SOURCE = re.compile(r"(?:#\s*pragma\s+|_Pragma\s*\(\s*\")(\w+)")
KERNEL = re.compile(r"__kernel\s+void\s+(\w+)\s*\(")


def diagnostics(output):
    """Splits clang's output into (header match, following lines) per warning or error."""
    found = []
    for line in output.splitlines():
        match = DIAGNOSTIC.match(line)
        if match:
            found.append((match, []))
        elif found:
            found[-1][1].append(line)
    return found


def pragma_name(match, lines):
    """The name of the pragma an unknown-pragma warning is about: from the macro expansion or the source line."""
    for i, line in enumerate(lines):
        if "<scratch space>" in line and "expanded from here" in line and i + 1 < len(lines):
            words = lines[i + 1].split()
            return words[0] if words else None
    try:
        with open(match["file"], encoding="utf-8") as f:
            source = f.read().splitlines()[int(match["line"]) - 1]
    except (OSError, IndexError):
        return None
    found = PRAGMA_IN_SOURCE.search(source)
    return found[1] if found else None


def allowed(target, match, lines):
    flag = match["flag"]
    if flag == "-Wunknown-attributes":
        name = ATTRIBUTE.search(match["message"])
        name = name[1] if name else None
    elif flag == "-Wunknown-pragmas":
        name = pragma_name(match, lines)
    else:
        return False
    return (target, flag, name) in ALLOWED


def compile_problems(clang, includes, path, target, label):
    """Compiles one file under one target; returns its problems as `path:line: message` lines."""
    command = [clang] + COMMON_OPTIONS + [f"-I{d}" for d in includes] + ([f"-D{target}"] if target else []) + [path]
    run = subprocess.run(command, capture_output=True, text=True, check=False)
    problems = []
    for match, lines in diagnostics(run.stderr):
        if match["severity"] == "warning" and allowed(target, match, lines):
            continue
        flag = f" [{match['flag']}]" if match["flag"] else ""
        problems.append(f"{match['file']}:{match['line']}: {label}: {match['severity']}: {match['message']}{flag}")
    if run.returncode != 0 and not problems:
        problems.append(f"{path}:1: {label}: clang exited {run.returncode}: {run.stderr.strip()}")
    return problems


def strip_comments(text):
    """The text with comments blanked out, newlines kept so that line numbers stay."""
    return re.sub(r"/\*.*?\*/|//[^\n]*", lambda m: re.sub(r"[^\n]", " ", m[0]), text, flags=re.S)


def entry_problems(path, display):
    """Each `_single` kernel carries RF_SINGLE_TASK in its declaration, and no other kernel does."""
    with open(path, encoding="utf-8") as f:
        text = strip_comments(f.read())
    problems = []
    for match in KERNEL.finditer(text):
        # The declaration starts after the previous statement, block or preprocessor line.
        start = max(text.rfind(";", 0, match.start()), text.rfind("}", 0, match.start()),
                    text.rfind("\n#", 0, match.start()) + 1)
        newline = text.find("\n", start) if text.startswith("#", start) else start
        prefix = text[newline + 1:match.start()]
        marked = re.search(r"\bRF_SINGLE_TASK\b", prefix) is not None
        name = match[1]
        line = text.count("\n", 0, match.start()) + 1
        if name.endswith("_single") and not marked:
            problems.append(f"{display}:{line}: single work-item entry {name} lacks RF_SINGLE_TASK")
        elif not name.endswith("_single") and marked:
            problems.append(f"{display}:{line}: {name} carries RF_SINGLE_TASK but is not a _single entry")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    parser.add_argument("--kernels", help="kernel directory (default ROOT/kernels)")
    parser.add_argument("--clang", default=shutil.which("clang") or shutil.which("clang-14"))
    parser.add_argument("--include", action="append", default=[],
                        help="a further include directory: the build's generated/kernels (common/params.h)")
    args = parser.parse_args()
    if not args.clang:
        print("lint_kernels.py: clang not found: install clang (scripts/setup.sh does)", file=sys.stderr)
        return 2
    kernels = os.path.abspath(args.kernels or os.path.join(args.root, "kernels"))
    files = sorted(os.path.relpath(os.path.join(d, f), kernels)
                   for d, _, names in os.walk(kernels) for f in names if f.endswith(".cl"))
    if not files:
        print(f"lint_kernels.py: no .cl files under {kernels}", file=sys.stderr)
        return 2
    includes = [kernels] + [os.path.abspath(d) for d in args.include]
    os.chdir(kernels)  # diagnostics then name files relative to kernels/, like the host's program names

    problems = []
    for relative in files:
        problems += entry_problems(relative, relative)
    one_program = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"rfrecon_lint_all_{os.getpid()}.cl")
    with open(one_program, "w", encoding="utf-8") as f:
        f.write("".join(f'#include "{relative}"\n' for relative in files))
    try:
        for target in TARGETS:
            label = target or "no target macro"
            for relative in files:
                problems += compile_problems(args.clang, includes, relative, target, label)
            problems += compile_problems(args.clang, includes, one_program, target, f"{label}, all files in one program")
    finally:
        os.remove(one_program)

    for problem in dict.fromkeys(problems):
        print(problem)
    count = len(files) * len(TARGETS)
    print(f"lint_kernels.py: {len(files)} files x {len(TARGETS)} targets ({count} compiles, plus one program each): "
          f"{'ok' if not problems else f'{len(problems)} problem(s)'}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
