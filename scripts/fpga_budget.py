#!/usr/bin/env python3
"""Resource budget of the FPGA kernels per board preset, without vendor tools (standard library, CMake and clang).

For each board preset (hw/boards/<name>.cmake): its parameters header, written from the table of
cmake/EmbedKernelsParams.cmake as the hw/ flow writes it (scripts/fpga_budget_params.cmake); every kernels/**/*.cl
compiled by clang to LLVM IR under the preset's target macro (scripts/fpga_kernel_ir.py); from the IR, each single
work-item entry's on-chip arrays and each kernel's DSP-heavy operators. Each array is counted in the memory blocks
the vendor tool binds it to (Intel M20K; AMD BRAM36, or URAM where kernels/depth/row_interleave.h says RF_IN_URAM in the
kernel's function), times the copies
that its reads and writes per loop iteration force at II 1 (PORTS below: a block has two ports, every copy takes
every write), and the sum is checked against the board's blocks less its shell (scripts/fpga_devices.py); for AMD
boards per SLR too, each kernel in the SLR of its memory bank (the preset's link configuration).

A preset must fit, unless its file declares it unsupported (`set(RFRECON_FPGA_SUPPORTED OFF)`), in which case it must
not fit (so that the declaration, and docs/fpga.md, follow the budget). Otherwise exit 1 with the block kind, the
count against the budget and each kernel's arrays. Not counted: every load / store unit's cache, fabric memory (LUTRAM,
MLAB), logic and DSP use; only the vendor reports show those.

  fpga_budget.py [--root DIR] [--boards DIR] [--board NAME]... [--set NAME=VALUE]... [--cmake PATH] [--clang PATH]
                 [--scratch DIR] [--verbose] [--markdown | --docs FILE | --update-docs FILE | --measured TABLE]
--markdown prints docs/fpga.md's budget tables; --docs checks that FILE holds them between its markers, and
--update-docs writes them there. --measured TABLE checks PORTS against the accesses the C simulation counted (the
table of tests/fpga/hls_access_check.cc).
"""
import argparse
import collections
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the modules below
import docs_table  # noqa: E402
import fpga_devices  # noqa: E402
import fpga_kernel_ir  # noqa: E402

# Reads and writes per iteration of each on-chip array of the single work-item entries, per pipelined loop that
# accesses it (kernels/depth/row_interleave.h and the row functions it calls); a loop whose iterations differ lists
# each kind of iteration. The copy loops (rf_load_row_group, rf_store_row_group) take one access per iteration and run
# alone, so they fit any copy. Every array the IR shows must be here, or be partitioned into registers
# (RF_PARTITION_COMPLETE). The C simulation counts the same accesses (tests/fpga/hls_access_check.cc), and
# --measured checks these figures against its table.
PORTS = {
    "integrate_rows_single": {
        "e_cam_rows": [("slope", 2, 0)],   # e_cam at `from` and `u`
        "e_proj_rows": [("slope", 2, 0)],  # rf_sample_row's two gathers of one slope
        "z_tri_rows": [("slope", 1, 0)],
        # The first slope reads what the pass before left (z_befores); the last writes the pixel's depth and a
        # closing run's rescaled seed.
        "z_rows": [("slope", 1, 0), ("slope", 0, 2)],
        "run_rows": [("slope", 1, 0)],
        "betas": [("slope", 1, 0)],
        "states": [("slope", 1, 1)],  # one row's state read and written back, each field
        "steps": [("slope", 1, 1)],
        "z_befores": [("slope", 1, 1)],
    },
    "fuse_rows_single": {
        "e_cam_rows": [("forward", 2, 0)],   # e_cam at `from` and `from + 1`, for both RK4 increments
        "e_proj_rows": [("forward", 2, 0)],  # RF_FUSE_SLOPES banks: rf_sample_row's two gathers of one slope each
        "z_tri_rows": [("forward", 1, 0)],
        "z_rows": [("forward", 2, 0), ("backward", 1, 1)],  # z at u and u + 1; z += update
        "c_rows": [("forward", 0, 1), ("backward", 1, 0)],
        "d_rows": [("forward", 0, 1), ("backward", 1, 0)],
        "run_rows": [("forward", 2, 0), ("backward", 2, 0)],  # the code at u + 1 (and at u, at the row's start)
        "codes": [("forward", 1, 1)],
        "next_codes": [("forward", 1, 1)],
        "sweeps": [("forward", 1, 1)],
        "updates": [("backward", 1, 1)],
        "betas": [("forward", 1, 0)],
    },
}
# The pipelined loops PORTS names, by function of kernels/depth/row_interleave.h and order in it, and the kernel.
LOOPS = {("rf_integrate_rows_interleaved", 0): ("integrate_rows_single", "slope"),
         ("rf_fuse_rows_interleaved", 0): ("fuse_rows_single", "forward"),
         ("rf_fuse_rows_interleaved", 1): ("fuse_rows_single", "backward")}

VENDOR_MACRO = {"intel": "RF_TARGET_INTEL_FPGA", "xilinx": "RF_TARGET_XILINX_FPGA"}
MEMORY_KIND = {"intel": "M20K", "xilinx": "BRAM36"}  # what the tool binds an array to unless told otherwise
MEMORY_KINDS = {"intel": ["M20K"], "xilinx": ["BRAM36", "URAM"]}
# The file that holds the depth kernels' on-chip arrays and its loops' functions (LOOPS).
ROW_INTERLEAVE = os.path.join("kernels", "depth", "row_interleave.h")
PARTITIONED = re.compile(r"(\w+)\s*\[[^\]]*\]\s*RF_PARTITION_COMPLETE")


class Problem(Exception):
    pass


def copies_for(reads, writes):
    """(copies, true dual-port, double-pumped) of a block array with `reads` and `writes` per iteration at II 1.

    A block has two ports (four double-pumped); every copy takes every write, the reads are spread over the copies."""
    ports = 2 if writes < 2 or (writes == 2 and reads == 0) else 4
    if writes > ports or (writes == ports and reads > 0):
        raise Problem(f"{reads} reads and {writes} writes per iteration: no block serves them at II 1")
    copies = 1 if reads == 0 else math.ceil(reads / (ports - writes))
    reads_per_copy = math.ceil(reads / copies)
    true_dual_port = ports == 4 or (reads_per_copy + writes > 1 and (reads_per_copy > 1 or writes > 1))
    return copies, true_dual_port, ports == 4


class Array:
    """One on-chip array of a kernel with its copies and blocks of each kind."""

    def __init__(self, kernel, name, words, width_bits, loops, uram=False):
        self.kernel, self.name, self.words, self.width_bits, self.loops = kernel, name, words, width_bits, loops
        self.uram = uram  # RF_IN_URAM: bound to URAM on AMD boards
        modes = [copies_for(reads, writes) for _, reads, writes in loops]
        self.copies = max(m[0] for m in modes)
        self.true_dual_port = any(m[1] for m in modes)
        self.double_pumped = any(m[2] for m in modes)
        self.blocks = {kind: self.copies * fpga_devices.blocks(words, width_bits, kind, self.true_dual_port)
                       for kind in ("M20K", "BRAM36", "URAM")}

    def kind(self, vendor):
        """The block kind the vendor's tool binds the array to."""
        return "URAM" if self.uram and vendor == "xilinx" else MEMORY_KIND[vendor]


class Preset:
    """One board preset's budget: parameters, device, arrays, operators, kernel placement, and what does not fit."""

    def __init__(self, name, fields, params, device, kernels, registers, urams):
        self.name = name
        self.vendor = fields["VENDOR"]
        self.supported = fields["SUPPORTED"].upper() not in ("OFF", "NO", "FALSE", "0", "")
        self.params = params
        self.device = device
        self.kinds = MEMORY_KINDS[self.vendor]
        binary = {k: v for k, v in kernels.items() if self.vendor == "intel" or k.endswith("_single")}
        self.operators = {k: v.operators for k, v in binary.items()}
        self.arrays = []
        for kernel in sorted(k for k in binary if k.endswith("_single")):
            self.arrays += arrays_of(binary[kernel], registers, urams.get(kernel, set()))
        self.slr_of, self.placement = ({}, {}) if self.vendor != "xilinx" else kernel_slrs(fields["LINK_CONFIG"],
                                                                                            device)
        self.overflows = self.check()

    def bound(self, kind, slr=None):
        """The arrays bound to blocks of `kind`, on the device or (AMD) in one SLR."""
        return [a for a in self.arrays
                if a.kind(self.vendor) == kind and (slr is None or self.slr_of.get(a.kernel, 0) == slr)]

    def used(self, kind, slr=None):
        """Blocks of `kind` the arrays take, on the device or (AMD) in one SLR."""
        return sum(a.blocks[kind] for a in self.bound(kind, slr))

    def check(self):
        """One message per budget exceeded: each block kind's on the device, and for AMD in each SLR."""
        overflows = []
        scopes = [None] + (list(range(self.device.slr_count)) if self.device.slr_count > 1 else [])
        for kind in self.kinds:
            for slr in scopes:
                needed, available = self.used(kind, slr), self.device.available(kind, slr)
                if needed <= available:
                    continue
                where = "the device" if slr is None else f"SLR{slr}"
                total = self.device.totals[kind] // (1 if slr is None else self.device.slr_count)
                lines = [f"{self.name} ({self.device.name}) does not fit: {kind} blocks of {where}: {needed:,} "
                         f"needed, {available:,} available ({total:,} {self.device.shell_note(slr)})"]
                if slr is None:
                    for a in sorted(self.bound(kind), key=lambda a: -a.blocks[kind]):
                        lines.append(f"  {a.kernel} {a.name}: {a.blocks[kind]:,} {kind} ({a.copies} x "
                                     f"{a.words:,} x {a.width_bits} bit)")
                else:
                    for kernel in sorted({a.kernel for a in self.bound(kind, slr)}):
                        count = sum(a.blocks[kind] for a in self.bound(kind, slr) if a.kernel == kernel)
                        lines.append(f"  {kernel} ({self.placement[kernel]}): {count:,} {kind}")
                overflows.append("\n".join(lines))
        return overflows


def arrays_of(kernel, registers, urams):
    """The on-chip arrays of one single work-item kernel, those named in `registers` left out, those in `urams` bound
    to URAM on AMD boards."""
    ports = PORTS.get(kernel.name, {})
    arrays = []
    for name, words, width_bits in kernel.arrays:
        if name in registers:
            continue
        if name not in ports:
            raise Problem(f"{kernel.name}: on-chip array {name} ({words} x {width_bits} bit) has no reads and writes "
                          f"per iteration in scripts/fpga_budget.py's PORTS")
        arrays.append(Array(kernel.name, name, words, width_bits, ports[name], name in urams))
    return arrays


def kernel_slrs(link_config, device):
    """({kernel: SLR}, {kernel: how, in words}) from a v++ link configuration: `slr=` where given, else the SLR of its
    first buffer's bank."""
    cu_kernel, slr_of = {}, {}
    try:
        with open(link_config, encoding="utf-8") as f:
            lines = [line.strip() for line in f]
    except OSError as error:
        raise Problem(f"the link configuration of an AMD preset: {error}") from error
    for line in lines:
        if line.startswith("nk="):
            kernel, _, cu = line[3:].split(":")
            cu_kernel[cu] = kernel
    for line in lines:
        found = re.match(r"slr=(\w+):SLR(\d+)$", line)
        if found:
            slr_of[cu_kernel.get(found[1], found[1])] = int(found[2])
    how = {kernel: "placed by slr= of the link configuration" for kernel in slr_of}
    for line in lines:
        found = re.match(r"sp=(\w+)\.\w+:(\S+)$", line)
        if found and cu_kernel.get(found[1], found[1]) not in slr_of:
            kernel = cu_kernel.get(found[1], found[1])
            slr_of[kernel] = device.bank_slr(found[2])
            how[kernel] = f"placed by its memory bank {found[2]}"
    return slr_of, how


def registers_in(kernel_dir):
    """Names of the arrays the kernels partition into registers (RF_PARTITION_COMPLETE)."""
    names = set()
    for d, _, files in os.walk(kernel_dir):
        for f in files:
            if f.endswith((".h", ".cl")):
                with open(os.path.join(d, f), encoding="utf-8") as text:
                    names.update(PARTITIONED.findall(text.read()))
    return names


def urams_in(root):
    """{kernel: {array}} that the depth kernels bind to URAM: RF_IN_URAM(array) in the function of one of LOOPS."""
    kernel_of = {function: kernel for (function, _), (kernel, _) in LOOPS.items()}
    urams, function = {}, None
    with open(os.path.join(root, ROW_INTERLEAVE), encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            found = re.match(r"RF_INLINE void (\w+)\(", line)
            function = found[1] if found else function
            for name in re.findall(r"\bRF_IN_URAM\((\w+)\)", line):
                if function not in kernel_of:
                    raise Problem(f"{ROW_INTERLEAVE}:{number}: RF_IN_URAM({name}) outside the functions of LOOPS "
                                  f"({', '.join(sorted(kernel_of))})")
                urams.setdefault(kernel_of[function], set()).add(name)
    return urams


def preset_params(args, board_file, out):
    """Writes and reads one preset's parameters header and variables (scripts/fpga_budget_params.cmake)."""
    command = [args.cmake, f"-DROOT={args.root}", f"-DBOARD_FILE={board_file}", f"-DOUT={out}",
               f"-DBUDGET_SET={';'.join(args.set)}", "-P", os.path.join(os.path.dirname(__file__),
                                                                         "fpga_budget_params.cmake")]
    run = subprocess.run(command, capture_output=True, text=True, check=False)
    if run.returncode != 0:
        raise Problem(f"{board_file}: writing its parameters failed:\n{run.stdout}{run.stderr}")
    with open(os.path.join(out, "preset.txt"), encoding="utf-8") as f:
        fields = dict(line.split("=", 1) for line in f.read().splitlines() if "=" in line)
    with open(os.path.join(out, "kernels", "common", "params.h"), encoding="utf-8") as f:
        header = f.read()
    params = {m[1]: m[2] for m in re.finditer(r"^#define (RF_\w+) (.*)$", header, re.M)
              if m[1] not in ("RF_EACH_FRAME", "RF_PARAMETERS_JSON")}
    return fields, params, header


def budgets(args):
    """[Preset] of every preset chosen."""
    kernel_dir = os.path.join(args.root, "kernels")
    registers = registers_in(kernel_dir)
    urams = urams_in(args.root)
    cl_files = sorted(os.path.join(d, f) for d, _, files in os.walk(kernel_dir) for f in files if f.endswith(".cl"))
    names = args.board or sorted(f[:-6] for f in os.listdir(args.boards) if f.endswith(".cmake"))
    compiled = {}  # (parameters header, vendor) -> {kernel: Kernel}
    presets = []
    for name in names:
        out = os.path.join(args.scratch, name)
        fields, params, header = preset_params(args, os.path.join(args.boards, name + ".cmake"), out)
        device = fpga_devices.device_of(fields["DESCRIPTION"])
        if device is None or fields["VENDOR"] not in VENDOR_MACRO:
            raise Problem(f"{name}: no device of scripts/fpga_devices.py for vendor {fields['VENDOR']}, "
                          f"description {fields['DESCRIPTION']!r}")
        key = (header, fields["VENDOR"])
        if key not in compiled:
            includes = [kernel_dir, os.path.join(out, "kernels")]
            compiled[key] = {}
            for path in cl_files:
                compiled[key].update(fpga_kernel_ir.compile_kernels(args.clang, path, includes,
                                                                    VENDOR_MACRO[fields["VENDOR"]]))
        presets.append(Preset(name, fields, params, device, compiled[key], registers, urams))
    return presets


def operator_text(counters):
    """The operators of all kernels of {kernel: Counter}, summed, in words."""
    total = {op: sum(counter.get(op, 0) for counter in counters.values()) for op in fpga_kernel_ir.OPERATORS}
    return ", ".join(f"{n:,} {op}" for op, n in total.items() if n) or "none"


def markdown(presets):
    """docs/fpga.md's budget tables: one row per preset, then per parameter set the arrays, then the operators."""
    lines = ["| preset | device | blocks | needed / available | most used SLR | fits | status |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for p in presets:
        status = "supported" if p.supported else "**unsupported**"
        for kind in p.kinds:
            slr = "-"
            if p.device.slr_count > 1:
                s = max(range(p.device.slr_count), key=lambda s: p.used(kind, s) / p.device.available(kind, s))
                slr = f"SLR{s}: {p.used(kind, s):,} / {p.device.available(kind, s):,}"
            fits = not any(f" {kind} blocks of " in o for o in p.overflows)
            lines.append(f"| `{p.name}` | {p.device.name} | {kind} | {p.used(kind):,} / "
                         f"{p.device.available(kind):,} | {slr} | {'yes' if fits else 'no'} | {status} |")
    groups = {}
    for p in presets:
        groups.setdefault(tuple(sorted(p.params.items())), []).append(p)
    for group in groups.values():
        p = group[0]
        spacings = p.params["RF_DOT_SPACINGS"].strip("{}").split(", ")
        lines += ["", f"On-chip arrays of {', '.join(f'`{q.name}`' for q in group)}:",
                  f"R_int {p.params['RF_INTEGRATE_INTERLEAVE']}, R_fuse {p.params['RF_FUSE_INTERLEAVE']}, width "
                  f"{p.params['RF_MAX_ROW_WIDTH']}, K {p.params['RF_K']}, batch {p.params['RF_FRAME_BATCH']}, "
                  f"{len(spacings)} dot spacings.", "",
                  "| kernel | array | words x bits | reads, writes per iteration | copies | M20K | BRAM36 | URAM | "
                  "AMD binds |", "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        shown = {}
        for q in group:
            for a in q.arrays:
                shown.setdefault((a.kernel, a.name), a)
        for a in shown.values():
            ports = "; ".join(f"{loop} {r}, {w}" for loop, r, w in a.loops)
            copies = f"{a.copies}{' (double-pumped)' if a.double_pumped else ''}"
            lines.append(f"| `{a.kernel}` | `{a.name}` | {a.words:,} x {a.width_bits} | {ports} | {copies} | "
                         f"{a.blocks['M20K']:,} | {a.blocks['BRAM36']:,} | {a.blocks['URAM']:,} | "
                         f"{a.kind('xilinx')} |")
    operators = [op for op in fpga_kernel_ir.OPERATORS
                 if any(counter.get(op, 0) for p in presets for counter in p.operators.values())]
    rows = {}
    for p in presets:
        for kernel, counter in p.operators.items():
            counts = tuple(counter.get(op, 0) for op in operators)
            if any(counts):
                rows.setdefault((kernel, counts), []).append(p.name)
    lines += ["", "| kernel | in the binaries of | " + " | ".join(operators) + " |",
              "| --- | --- |" + " --- |" * len(operators)]
    for (kernel, counts), names in sorted(rows.items()):
        where = "all presets" if len(names) == len(presets) else ", ".join(names)
        lines.append(f"| `{kernel}` | {where} | " + " | ".join(f"{n:,}" for n in counts) + " |")
    lines += ["", "| preset | DSP-heavy operators in the binary | DSP blocks available |", "| --- | --- | --- |"]
    for p in presets:
        lines.append(f"| `{p.name}` | {operator_text(p.operators)} | {p.device.available('DSP'):,} |")
    return "\n".join(lines) + "\n"


def report(presets, verbose, what_if):
    """Problems (exit 1) and notes, printed; returns the problems' count. What-if: any preset that does not fit."""
    problems = 0
    for p in presets:
        if what_if:
            p.supported = True
        blocks = ", ".join(f"{kind} {p.used(kind):,} / {p.device.available(kind):,}" for kind in p.kinds)
        summary = (f"{p.name}: {p.device.name}: {blocks}; "
                   f"DSP-heavy operators {operator_text(p.operators)}")
        if p.supported and p.overflows:
            problems += 1
            print("\n".join(p.overflows))
        elif not p.supported and not p.overflows:
            problems += 1
            print(f"{p.name} fits its board, but hw/boards/{p.name}.cmake declares it unsupported: remove "
                  f"set(RFRECON_FPGA_SUPPORTED OFF) and update docs/fpga.md (fpga_budget.py --update-docs)")
        elif not p.supported:
            print(f"{summary}: does not fit, declared unsupported")
            if verbose:
                print("\n".join(p.overflows))
        else:
            print(f"{summary}: fits")
        for a in p.arrays:
            if a.double_pumped:
                loops = "; ".join(f"{loop} loop {r} read(s), {w} write(s)" for loop, r, w in a.loops)
                print(f"  note: {p.name} {a.kernel} {a.name} ({loops} per iteration) needs a double-pumped block "
                      f"(aoc) or runs at II 2 (Vitis HLS)")
    return problems


def measured_mismatches(root, table_path):
    """Where PORTS differs from the accesses the C simulation counted (the table tests/fpga/hls_access_check.cc
    writes): each array's most reads and writes in one iteration of each loop LOOPS names, over its fields and banks."""
    loop_at, function, counts = {}, None, collections.Counter()
    with open(os.path.join(root, "kernels", "depth", "row_interleave.h"), encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            found = re.match(r"RF_INLINE void (\w+)\(", line)
            function = found[1] if found else function
            if re.match(r"\s*RF_HLS_PIPELINE\b", line):
                loop_at[number] = LOOPS.get((function, counts[function]))
                counts[function] += 1
    measured = collections.defaultdict(lambda: [0, 0])
    with open(table_path, encoding="utf-8") as f:
        for row in f:
            cells = [c.strip() for c in row.strip().strip("|").split("|")]
            found = re.fullmatch(r"`kernels/depth/row_interleave\.h:(\d+)`", cells[0])
            if not found or "(AXI" in cells[2] or not loop_at.get(int(found[1])):
                continue
            kernel, loop = loop_at[int(found[1])]
            entry = measured[(kernel, re.sub(r"[\[+].*", "", cells[2]), loop)]
            entry[0], entry[1] = max(entry[0], int(cells[3])), max(entry[1], int(cells[4]))
    expected = {}
    for kernel, arrays in PORTS.items():
        for name, phases in arrays.items():
            for loop, reads, writes in phases:
                entry = expected.setdefault((kernel, name, loop), [0, 0])
                entry[0], entry[1] = max(entry[0], reads), max(entry[1], writes)
    return [f"{kernel} {name} in the {loop} loop: PORTS {expected.get((kernel, name, loop))} reads and writes, "
            f"the C simulation {measured.get((kernel, name, loop))}"
            for kernel, name, loop in sorted(set(expected) | set(measured))
            if expected.get((kernel, name, loop)) != measured.get((kernel, name, loop))]


def add_preset_arguments(parser):
    """The options that choose the presets and tools, shared with scripts/fpga_latency.py."""
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--root", default=os.path.join(here, ".."))
    parser.add_argument("--boards", help="board preset directory (default ROOT/hw/boards)")
    parser.add_argument("--board", action="append", default=[], help="a preset (default: all of --boards)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a parameter for every preset, as -DRFRECON_NAME=VALUE (what-if)")
    parser.add_argument("--cmake", default=shutil.which("cmake"))
    parser.add_argument("--clang", default=shutil.which("clang") or shutil.which("clang-14"))
    parser.add_argument("--scratch", help="directory for the presets' parameters headers (default: a temporary one)")


def resolve_preset_arguments(args, script):
    """Absolute --root and --boards, and a temporary --scratch where none was given (returned, for the caller to
    remove; else None). False, having said why, without clang or cmake."""
    if not args.clang or not args.cmake:
        print(f"{script}: needs clang and cmake (scripts/setup.sh installs them)", file=sys.stderr)
        return False, None
    args.root = os.path.abspath(args.root)
    args.boards = os.path.abspath(args.boards or os.path.join(args.root, "hw", "boards"))
    scratch = None
    if not args.scratch:
        scratch = args.scratch = tempfile.mkdtemp(prefix=f"rfrecon_{script.split('.')[0]}_")
    return True, scratch


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_preset_arguments(parser)
    parser.add_argument("--verbose", action="store_true", help="also the arrays of unsupported presets")
    output = docs_table.add_output_arguments(parser, "budget tables")
    output.add_argument("--measured", metavar="TABLE", help="check PORTS against the C simulation's access table")
    args = parser.parse_args()
    if args.measured:
        mismatches = measured_mismatches(os.path.abspath(args.root), args.measured)
        print("\n".join(mismatches) or f"fpga_budget.py: PORTS holds the accesses of {args.measured}")
        return 1 if mismatches else 0
    ready, scratch = resolve_preset_arguments(args, "fpga_budget.py")
    if not ready:
        return 2
    try:
        presets = budgets(args)
        written = docs_table.output(args, "fpga_budget.py", lambda: markdown(presets), "budget tables")
        if written is not None:
            return written
        problems = report(presets, args.verbose, bool(args.set))
        print(f"fpga_budget.py: {len(presets)} presets: {'ok' if not problems else f'{problems} problem(s)'}",
              file=sys.stderr)
        return 1 if problems else 0
    except (Problem, docs_table.MissingMarkers) as problem:
        print(f"fpga_budget.py: {problem}")
        return 1
    finally:
        if scratch:
            shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
