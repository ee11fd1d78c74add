#!/usr/bin/env python3
"""Latency model of the pipelined loops of the FPGA kernels' single work-item entries, without vendor tools.

Every kernels/**/*.cl is compiled by clang to LLVM IR under each vendor's target macro, with the parameters header of
the board presets, as scripts/fpga_budget.py compiles it (scripts/fpga_kernel_ir.py), with line tables (so that each
loop of the IR names its source line) and without builtins (so that a copy loop stays a loop rather than a memcpy).
A pipelined loop is a `for` the source marks with RF_PIPELINE_II. Its loop-carried dependences are
  - registers: each phi of the loop header, from the phi to its value from the latch, at distance 1;
  - memory: each array the loop reads and writes (an on-chip array, or a global buffer unless each iteration has its
    own element), from a read of it to a write of it (a RAM read and a RAM write), at the distance the source
    declares for the vendor: Intel, RF_IVDEP_SAFELEN(R) before the loop (every array in memory); AMD's HLS C++ tops,
    RF_HLS_DEPENDENCE(array, R) in its body (that array); else 1. An array kept in registers (RF_PARTITION_COMPLETE
    under the OpenCL targets) has distance 1 whatever ivdep says, and reads and writes of no latency.
Its latency L is the longest path of operators from its start to its end in the loop body (data, the branch
conditions that select a merged value, and the conditions that guard a write or a global read), each operator
counted with the vendor's latency at the stated clock (LATENCIES, with their sources). The loop starts an iteration
every II = max over its dependences of ceil(L / distance) clocks, at least 1; clocks per pixel are II times the loop's
iterations per pixel (TRIPS). Not modelled: port limits of the RAMs and AXI bundles (fpga_budget.py's PORTS, the C
simulation's access check), stalls on global memory, the vendor tools' own scheduling; only their reports show those.

docs/fpga.md's section "Pipelines of the single work-item entries" states the design II of each loop in a table with
the header `| kernel | loop | design II |`; the check fails where the model's II exceeds a design II, or where a
pipelined loop has no design II there.

  fpga_latency.py [--root DIR] [--boards DIR] [--board NAME]... [--set NAME=VALUE]... [--cmake PATH] [--clang PATH]
                  [--scratch DIR] [--verbose] [--claims FILE] [--markdown | --docs FILE | --update-docs FILE]
--markdown prints the section's generated tables; --docs checks that FILE holds them between its markers, and
--update-docs writes them there; --verbose prints every dependence's operators.
"""
import argparse
import collections
import math
import os
import re
import shutil
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the modules below
import docs_table  # noqa: E402
import fpga_budget  # noqa: E402
import fpga_kernel_ir  # noqa: E402

IR_OPTIONS = ["-gline-tables-only", "-fno-builtin"]

# Operator latencies in clocks, per vendor. Integer and logic operations, comparisons of integers, selects and
# multiplexers are 0: both tools chain them within a clock; a chain of them still takes one clock when it is carried
# (II >= 1).
#
# AMD: Vitis HLS at the default clock of Vitis kernels, 300 MHz (3.33 ns), on UltraScale+ (U250, U280). The
# floating-point latencies are those of the cores Vitis HLS binds by default, as its csynth output names them (the
# name ends in the core's stages, the latency plus one): fadd_32ns_32ns_32_5_full_dsp (4 clocks),
# fmul_32ns_32ns_32_4_max_dsp (3), fdiv_32ns_32ns_32_16_no_dsp and fsqrt_32ns_32ns_32_16_no_dsp (15),
# fcmp_32ns_32ns_1_2_no_dsp (1), sitofp_32ns_32_6_no_dsp (5), urem_32ns_..._36_seq (35): the figures public Vitis HLS
# outputs for UltraScale+ show, taken here as those of 300 MHz (UG1399, "Operator Configuration", config_op and
# BIND_OP, sets others; the csynth report confirms them). The block RAM's read latency 2 (the RAM_AUTO_1R1W storage
# core of the same outputs), a write 1; an m_axi read 64, the latency Vitis HLS assumes for an AXI4 master in the
# Vitis kernel flow (UG1399, config_interface -m_axi_latency). atan2 / hypot: hls_math's cores, about 40 (estimate).
# llvm.fmuladd (a * b + c, where the source lets clang contract) counts as a multiply and an add.
#
# Intel: aoc 19.x to 22.4 on Stratix 10 at 480 MHz, the fmax its Stratix 10 flow aims at unless -fmax says otherwise
# (the BSPs' kernel clocks often close lower). Intel publishes no per-operator latency table for aoc, so these are
# estimates, to be replaced by the report's (aoc -rtl -report, loop analysis and schedule viewer): the hardened
# single-precision adder and multiplier of the Stratix 10 DSP block with its pipeline registers, 4 (Stratix 10
# Variable Precision DSP Blocks User Guide, "Pipeline Registers for Fixed-Point and Floating-Point Arithmetic"); a
# divider and a square root of DSPs and tables, 24 and 20 (Floating-Point IP Cores User Guide, FP_FUNCTIONS: the
# latency grows with the target frequency); an M20K read 3 (address and output registers at 480 MHz), a write 1; a
# global read through a burst-coalesced load-store unit 150 (DDR4 at 480 MHz). Arria 10 (pac_a10) runs at a lower
# clock with fewer stages: its latencies are lower than these.
LATENCIES = {
    "intel": {"fadd": 4, "fmul": 4, "fdiv": 24, "sqrt": 20, "fcmp": 2, "fminmax": 2, "f2i": 3, "i2f": 3,
              "atan2/hypot": 60, "imul": 3, "idiv by constant": 5, "idiv": 36, "int": 0, "ram read": 3, "ram write": 1,
              "global read": 150, "global write": 1, "register": 0},
    "amd": {"fadd": 4, "fmul": 3, "fdiv": 15, "sqrt": 15, "fcmp": 1, "fminmax": 1, "f2i": 3, "i2f": 5,
            "atan2/hypot": 40, "imul": 2, "idiv by constant": 4, "idiv": 35, "int": 0, "ram read": 2, "ram write": 1,
            "global read": 64, "global write": 1, "register": 0},
}
CLOCK_MHZ = {"intel": 480, "amd": 300}


class Target:
    """How one vendor flow compiles a loop: the latency table and where a dependence distance comes from."""

    def __init__(self, name, title, vendor, macro, ivdep, hls_dependence, registers):
        self.name, self.title, self.vendor, self.macro = name, title, vendor, macro
        self.latency = LATENCIES[vendor]
        self.ivdep = ivdep  # RF_IVDEP_SAFELEN applies to every array in memory
        self.hls_dependence = hls_dependence  # RF_HLS_DEPENDENCE applies to its array
        self.registers = registers  # RF_PARTITION_COMPLETE keeps an array in registers


TARGETS = {
    "intel": Target("intel", "Intel, aoc, Stratix 10 at 480 MHz", "intel", "RF_TARGET_INTEL_FPGA", True, False, True),
    "amd": Target("amd", "AMD, Vitis HLS (HLS C++ tops), 300 MHz", "amd", "RF_TARGET_XILINX_FPGA", False, True, False),
    # Vitis 2019.2 to 2022.2 with the OpenCL C kernels: no dependence attribute (docs/fpga.md), so no distance.
    "amd_opencl": Target("amd_opencl", "AMD, v++ OpenCL C (2019.2 to 2022.2), 300 MHz", "amd", "RF_TARGET_XILINX_FPGA",
                         False, False, True),
}
VENDOR_TARGETS = {"intel": ("intel",), "xilinx": ("amd", "amd_opencl")}
TABLE_TARGETS = ("intel", "amd")  # the targets of the docs table; amd_opencl is summed up in a sentence

# Operator class of each IR opcode (LATENCIES' keys); calls by their demangled name. An opcode or call not here fails
# the model, so that the table grows with the kernels.
OPCODE_CLASS = {
    "fadd": "fadd", "fsub": "fadd", "fmul": "fmul", "fdiv": "fdiv", "frem": "fdiv", "fcmp": "fcmp", "fneg": "int",
    "fptosi": "f2i", "fptoui": "f2i", "sitofp": "i2f", "uitofp": "i2f", "fpext": "int", "fptrunc": "f2i",
    "mul": "imul", "udiv": "idiv", "sdiv": "idiv", "urem": "idiv", "srem": "idiv",
    "add": "int", "sub": "int", "and": "int", "or": "int", "xor": "int", "shl": "int", "lshr": "int", "ashr": "int",
    "icmp": "int", "select": "int", "zext": "int", "sext": "int", "trunc": "int", "getelementptr": "int",
    "bitcast": "int", "addrspacecast": "int", "ptrtoint": "int", "inttoptr": "int", "freeze": "int", "phi": "int",
    "extractelement": "int", "insertelement": "int", "shufflevector": "int", "extractvalue": "int",
    "insertvalue": "int", "br": "int", "switch": "int", "ret": "int", "unreachable": "int",
    "alloca": "int", "load": "load", "store": "store",
}
CALL_CLASS = {
    "fmuladd": ("fmul", "fadd"), "fma": ("fmul", "fadd"), "mad": ("fmul", "fadd"), "sqrt": ("sqrt",),
    "rsqrt": ("sqrt",), "native_sqrt": ("sqrt",), "fabs": ("int",), "copysign": ("int",), "fmin": ("fminmax",),
    "fmax": ("fminmax",), "minnum": ("fminmax",), "maxnum": ("fminmax",), "floor": ("f2i",), "ceil": ("f2i",),
    "rint": ("f2i",), "round": ("f2i",), "trunc": ("f2i",), "atan2": ("atan2/hypot",), "hypot": ("atan2/hypot",),
    "atan": ("atan2/hypot",), "min": ("int",), "max": ("int",), "smin": ("int",), "smax": ("int",), "umin": ("int",),
    "umax": ("int",), "abs": ("int",), "clamp": ("int",), "select": ("int",), "isnan": ("int",),
    "isinf": ("int",), "isfinite": ("int",), "signbit": ("int",),
}
IGNORED_CALLS = ("lifetime", "dbg", "assume", "experimental")  # llvm.* intrinsics that are no hardware

# Names of the pipelined loops by the source function that holds them, in source order; a function with one loop not
# named here calls it "pixel".
LOOP_NAMES = {
    "rf_load_row_group": ("rows in", "projector rows in"),
    "rf_store_row_group": ("z out",),
    "rf_integrate_rows_interleaved": ("slope",),
    "rf_fuse_rows_interleaved": ("forward", "backward"),
    "rf_dual_entries": ("rows to 0", "entry"),
    "rf_axpy_elements": ("element",),
}

# Iterations of each pipelined loop per unit of work (the unit per kernel), with the host's defaults: 3 shooting
# passes of the integration and 3 linearised solves of the fusion (host/depth/row_solvers.h); the projector rows'
# copy counts proj_width / width ~ 1 per camera pixel. Kernel -> (unit, {loop: (iterations, how)}).
TRIPS = {
    "integrate_rows_single": ("camera pixel", {
        "rows in": (1, "1"), "projector rows in": (1, "~1"), "slope": (12, "3 passes x 4 slopes"),
        "z out": (1, "1")}),
    "fuse_rows_single": ("camera pixel", {
        "rows in": (1, "1"), "projector rows in": (1, "~1"), "forward": (3, "3 iterations"),
        "backward": (3, "3 iterations"), "z out": (1, "1")}),
    "dual_single": ("entry of T or projector pixel", {"rows to 0": (1, "1"), "entry": (1, "1")}),
    "axpy_single": ("element", {"element": (1, "1")}),
    "gray_pairs_single": ("camera pixel and batch of {pairs} Gray pairs", {}),
    "phase_steps_single": ("camera pixel and batch of {batch} phase steps", {}),
    "dot_frames_single": ("camera pixel and batch of {batch} dot frames", {}),
}
DEFAULT_UNIT = "camera pixel"

# How the docs name the operators of a path (add and multiply together: the vendors weigh them alike).
SUMMARY_NAMES = {"fadd": "add/mul", "fmul": "add/mul", "fdiv": "divide", "sqrt": "square root", "fcmp": "compare",
                 "f2i": "float to int", "i2f": "int to float"}

SECTION = "## Pipelines of the single work-item entries"
CLAIMS_HEADER = re.compile(r"^\|\s*kernel\s*\|\s*loop\s*\|\s*design II\s*\|", re.M)


class Problem(Exception):
    pass


# ---- LLVM IR: functions, blocks, instructions ----

VALUE = re.compile(r"%([-\w.$]+)")
LABEL = re.compile(r"^([-\w.$]+):")
METADATA = re.compile(r",\s*!([\w.]+) (!\d+)")
PHI_PAIR = re.compile(r"\[\s*([^,\]]+?)\s*,\s*%([-\w.$]+)\s*\]")
CALLEE = re.compile(r"@([\w.$]+)\(")
TYPE_NAME = re.compile(r"^(struct|union|class)\.")


class Instruction:
    """One instruction: result name (or None), opcode, operands (value names), phi pairs, successors, condition."""

    def __init__(self, text, block, index):
        self.text, self.block, self.index = text, block, index
        self.loop_md = None
        for key, ref in METADATA.findall(text):
            if key == "llvm.loop":
                self.loop_md = ref
        body = METADATA.sub("", text)
        assigned = re.match(r"%([-\w.$]+) = (.*)$", body)
        self.name, rest = (assigned[1], assigned[2]) if assigned else (None, body)
        rest = re.sub(r"^(tail |musttail |notail )", "", rest)
        self.opcode = rest.split()[0]
        self.callee = None
        if self.opcode == "call":
            callee = CALLEE.search(rest)
            self.callee = callee[1] if callee else ""
        self.successors = re.findall(r"label %([-\w.$]+)", rest)
        self.phi = []
        if self.opcode == "phi":
            self.phi = [(v if v.startswith("%") else None, b) for v, b in PHI_PAIR.findall(rest)]
            self.phi = [(v[1:] if v else None, b) for v, b in self.phi]
            self.operands = [v for v, _ in self.phi if v]
        else:
            without_labels = re.sub(r"label %[-\w.$]+", "", rest)
            if self.callee is not None:
                without_labels = without_labels[without_labels.find("("):]
            self.operands = [v for v in VALUE.findall(without_labels) if not TYPE_NAME.match(v)]
        self.condition = None
        if self.opcode in ("br", "switch") and self.operands:
            self.condition = self.operands[0]


class Function:
    """One function of the IR: blocks in order, {name: [Instruction]}, successors, the values it defines."""

    def __init__(self, name, lines):
        self.name = name
        self.order, self.blocks = [], {}
        current = None
        pending = ""
        for line in lines:
            label = LABEL.match(line)
            if label:
                current = label[1]
                self.order.append(current)
                self.blocks[current] = []
                continue
            stripped = line.strip()
            if not stripped or stripped.startswith(";"):
                continue
            if current is None:
                current = "entry"
                self.order.append(current)
                self.blocks[current] = []
            pending += (" " if pending else "") + stripped
            if pending.startswith("switch") and not pending.rstrip().endswith("]"):
                continue
            self.blocks[current].append(Instruction(pending, current, len(self.blocks[current])))
            pending = ""
        self.defs = {i.name: i for b in self.order for i in self.blocks[b] if i.name}
        self.succ = {b: (self.blocks[b][-1].successors if self.blocks[b] else []) for b in self.order}
        self.pred = {b: [] for b in self.order}
        for b in self.order:
            for s in self.succ[b]:
                self.pred[s].append(b)


FUNCTION = re.compile(r"^define [^@\n]*@(\w+)\(([^\n]*)\{\n(.*?)^}", re.S | re.M)


def functions_of_ir(ir_text):
    """{name: Function} of the kernels of one module, with the arguments' names in `arguments`."""
    functions = {}
    for match in FUNCTION.finditer(ir_text):
        if "spir_kernel" not in match[0].split("\n", 1)[0]:
            continue
        function = Function(match[1], match[3].splitlines())
        function.arguments = {v for v in VALUE.findall(match[2]) if not TYPE_NAME.match(v)}
        functions[match[1]] = function
    return functions


# ---- debug locations: the source line of each loop ----

def metadata_of_ir(ir_text):
    """{"!N": text} of the module's metadata nodes."""
    return {m[1]: m[2] for m in re.finditer(r"^(!\d+) = (.*)$", ir_text, re.M)}


def loop_location(metadata, loop_md):
    """(file path, line, source function) where the loop of metadata node `loop_md` starts, or None."""
    node = metadata.get(loop_md, "")
    for ref in re.findall(r"!\d+", node)[1:]:
        location = metadata.get(ref, "")
        found = re.match(r"!DILocation\(line: (\d+),.*?scope: (!\d+)", location)
        if not found:
            continue
        scope = metadata.get(found[2], "")
        name = re.search(r'name: "(\w+)"', scope)
        file_ref = re.search(r"file: (!\d+)", scope)
        file_node = metadata.get(file_ref[1], "") if file_ref else ""
        filename = re.search(r'filename: "([^"]+)"', file_node)
        directory = re.search(r'directory: "([^"]*)"', file_node)
        if not filename:
            return None
        path = os.path.join(directory[1] if directory else "", filename[1])
        return os.path.realpath(path), int(found[1]), name[1] if name else "?"
    return None


# ---- the pipelined loops of the source and their directives ----

class SourceLoop:
    """A `for` the source marks with RF_PIPELINE_II: file, line, its ivdep distance and HLS dependence distances."""

    def __init__(self, path, line, safelen, dependences):
        self.path, self.line, self.safelen, self.dependences = path, line, safelen, dependences


def safelen_before(lines, at):
    """The RF_IVDEP_SAFELEN argument among the directive lines just before line `at` (the `for`), or None."""
    before = at - 1
    while before >= 0 and re.match(r"\s*(RF_IVDEP_SAFELEN|RF_PIPELINE_II)\(", lines[before]):
        found = re.search(r"RF_IVDEP_SAFELEN\((\w+)\)", lines[before])
        if found:
            return found[1]
        before -= 1
    return None


def dependences_after(lines, at):
    """{array: distance text} of the RF_HLS_DEPENDENCE lines that open the body of the `for` on line `at`."""
    dependences, body = {}, at + 1
    while body < len(lines) and re.match(r"\s*(RF_HLS_PIPELINE|RF_HLS_DEPENDENCE\(|//)", lines[body]):
        found = re.search(r"RF_HLS_DEPENDENCE\((\w+),\s*(\w+)\)", lines[body])
        if found:
            dependences[found[1]] = found[2]
        body += 1
    return dependences


def source_loops(kernel_dir):
    """{(real path, line of the `for`): SourceLoop} of every loop under kernel_dir that RF_PIPELINE_II marks."""
    loops = {}
    for d, _, files in os.walk(kernel_dir):
        for f in sorted(files):
            if not f.endswith((".h", ".cl")):
                continue
            path = os.path.realpath(os.path.join(d, f))
            with open(path, encoding="utf-8") as text:
                lines = text.read().splitlines()
            for n, line in enumerate(lines):
                if not re.match(r"\s*RF_PIPELINE_II\(", line):
                    continue
                at = n + 1
                while at < len(lines) and re.match(r"\s*RF_\w+\(", lines[at]) and not re.match(r"\s*for\b", lines[at]):
                    at += 1
                if at < len(lines) and re.match(r"\s*for\s*\(", lines[at]):
                    loops[(path, at + 1)] = SourceLoop(path, at + 1, safelen_before(lines, at),
                                                       dependences_after(lines, at))
    return loops


def parameter_value(text, params):
    """An integer written as a number or as a parameter of the header (RF_FUSE_INTERLEAVE)."""
    if text is None:
        return None
    if re.fullmatch(r"\d+", text):
        return int(text)
    if text in params and re.fullmatch(r"\d+", params[text].strip()):
        return int(params[text].strip())
    raise Problem(f"dependence distance {text}: not a number nor an integer parameter of the parameters header")


# ---- loops of a function: dominators, natural loops ----

def dominators(order, pred, entry):
    """{block: set of its dominators} over `order` (blocks reachable from entry), iteratively."""
    dom = {b: set(order) for b in order}
    dom[entry] = {entry}
    changed = True
    while changed:
        changed = False
        for b in order:
            if b == entry:
                continue
            preds = [p for p in pred[b] if p in dom]
            new = set.intersection(*(dom[p] for p in preds)) if preds else set()
            new = new | {b}
            if new != dom[b]:
                dom[b], changed = new, True
    return dom


class Loop:
    """A natural loop: header, blocks (in function order), latches, the llvm.loop node of its latch branch."""

    def __init__(self, function, header, blocks, latches):
        self.function, self.header, self.latches = function, header, latches
        self.blocks = [b for b in function.order if b in blocks]
        self.loop_md = None
        for latch in latches:
            term = function.blocks[latch][-1]
            self.loop_md = term.loop_md or self.loop_md


def natural_loops(function):
    """[Loop] of a function, one per header."""
    reachable, stack = set(), [function.order[0]]
    while stack:
        b = stack.pop()
        if b not in reachable:
            reachable.add(b)
            stack.extend(function.succ[b])
    order = [b for b in function.order if b in reachable]
    dom = dominators(order, function.pred, order[0])
    by_header = collections.defaultdict(lambda: (set(), []))
    for b in order:
        for h in function.succ[b]:
            if h in dom[b]:  # back edge b -> h
                blocks, latches = by_header[h]
                latches.append(b)
                blocks.add(h)
                work = [b]
                while work:
                    x = work.pop()
                    if x not in blocks:
                        blocks.add(x)
                        work.extend(function.pred[x])
    return [Loop(function, h, blocks, latches) for h, (blocks, latches) in by_header.items()]


# ---- the chains of one loop ----

class Chain:
    """One loop-carried dependence: what carries it, its latency, distance and the operators on its longest path."""

    def __init__(self, carrier, kind, latency, distance, path):
        self.carrier, self.kind, self.latency, self.distance, self.path = carrier, kind, latency, distance, path
        self.ii = max(1, math.ceil(latency / distance)) if latency else 1


def operator_classes(inst):
    """The operator classes (LATENCIES' keys) of one instruction, a load or store by the memory it reaches later."""
    if inst.opcode == "call":
        name = fpga_kernel_ir.demangled(inst.callee)
        if inst.callee.startswith("llvm.") and name in IGNORED_CALLS:
            return ()
        if name not in CALL_CLASS:  # memset and memcpy too: a copy loop the model cannot see as a loop
            raise Problem(f"call to {inst.callee} in a pipelined loop: no operator class in CALL_CLASS")
        return CALL_CLASS[name]
    if inst.opcode not in OPCODE_CLASS:
        raise Problem(f"IR opcode {inst.opcode} in a pipelined loop: no class in OPCODE_CLASS ({inst.text})")
    if inst.opcode in ("udiv", "sdiv", "urem", "srem") and not re.search(r", %[-\w.$]+$", inst.text.split(", !")[0]):
        return ("idiv by constant",)
    return (OPCODE_CLASS[inst.opcode],)


class LoopModel:
    """The dependences of one pipelined loop for one target: chains, II, and the loop's place in the source."""

    def __init__(self, loop, source, target, params, registers):
        self.loop, self.source, self.target = loop, source, target
        self.function = loop.function
        self.registers = registers if target.registers else set()
        self.params = params
        self.insts = [i for b in self.ordered_blocks() for i in self.function.blocks[b]]
        self.position = {id(i): n for n, i in enumerate(self.insts)}
        self.in_loop = {i.name: i for i in self.insts if i.name}
        self.header_phis = [i for i in self.function.blocks[loop.header] if i.opcode == "phi"]
        self.roots = {}
        self.keys = {}
        self.guards, self.selectors = self.control_conditions()
        self.preds = self.dependence_edges()
        self.chains = self.register_chains() + self.memory_chains()
        worst = max(self.chains, key=lambda c: (c.ii, c.latency), default=None)
        self.worst = worst
        self.ii = worst.ii if worst else 1

    def ordered_blocks(self):
        """The loop's blocks in reverse post-order of the loop body without its back edges."""
        blocks, seen, post = set(self.loop.blocks), set(), []

        def visit(b):
            seen.add(b)
            for s in self.function.succ[b]:
                if s in blocks and s not in seen and s != self.loop.header:
                    visit(s)
            post.append(b)

        sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))
        visit(self.loop.header)
        return list(reversed(post))

    def control_dependences(self, order):
        """{block: the blocks whose branch decides whether it runs}, by the post-dominators of the loop body (its
        back edges and exits lead to one virtual exit)."""
        inside, exit_node = set(order), ""
        succ = {b: [s for s in self.function.succ[b] if s in inside and s != self.loop.header] for b in order}
        for b in order:
            if any(s not in inside or s == self.loop.header for s in self.function.succ[b]):
                succ[b].append(exit_node)
        post = dominators([exit_node] + list(reversed(order)), dict(succ, **{exit_node: []}), exit_node)

        def immediate(b):
            strict = post[b] - {b}
            return max(strict, key=lambda d: len(post[d])) if strict else None

        depends = {b: set() for b in order}
        for a in order:
            if not self.function.blocks[a][-1].condition or len(set(self.function.succ[a])) < 2:
                continue
            stop = immediate(a)
            for runner in set(succ[a]):
                while runner not in (stop, None, exit_node):
                    depends[runner].add(a)
                    runner = immediate(runner)
        return depends

    def control_conditions(self):
        """({block: its guards}, {block: its selectors}): the branch conditions on which a block of the loop body
        depends to run at all (guards, transitively), and those that pick which of its predecessors it is entered
        from (selectors: they select the values its phis merge)."""
        order = self.ordered_blocks()
        inside = set(order)
        depends = self.control_dependences(order)
        guards = {}
        for b in order:  # in order, so that a block's guards are known before those that depend on it
            closure = set(depends[b])
            for a in depends[b]:
                closure |= guards.get(a, set())
            guards[b] = closure
        selectors = {}
        for b in order:
            chosen = set()
            for p in self.function.pred[b]:
                if p in inside and b != self.loop.header:
                    chosen |= guards[p] | ({p} if self.function.blocks[p][-1].condition else set())
            selectors[b] = chosen - guards[b]

        def values(blocks):
            conditions = [self.function.blocks[a][-1].condition for a in blocks]
            return [v for v in conditions if v in self.in_loop]

        return ({b: values(g) for b, g in guards.items()}, {b: values(c) for b, c in selectors.items()})

    def roots_of(self, value, depth=0):
        """The memories a pointer value may reach, sorted: ("ram" or "register", alloca) or ("global", argument);
        several where it selects between arrays."""
        if value in self.roots:
            return self.roots[value]
        inst = self.function.defs.get(value)
        roots = (("unknown", value),)
        if inst is None and value in self.function.arguments:
            roots = (("global", value),)
        elif inst is not None and depth < 50:
            if inst.opcode == "alloca":
                name = value.split(".")[0]
                roots = (("register" if name in self.registers else "ram", name),)
            elif inst.opcode in ("getelementptr", "bitcast", "addrspacecast") and inst.operands:
                roots = self.roots_of(inst.operands[0], depth + 1)
            elif inst.opcode in ("phi", "select"):
                pointers = inst.operands if inst.opcode == "phi" else inst.operands[1:]
                roots = tuple(sorted({r for v in pointers for r in self.roots_of(v, depth + 1)}))
        self.roots[value] = roots
        return roots

    def memory_kind(self, inst):
        """"global", "ram" or "register": the slowest memory a load or store may reach."""
        kinds = {kind for kind, _ in self.roots_of(self.pointer(inst))}
        if "unknown" in kinds:
            raise Problem(f"{self.function.name}: a {inst.opcode} in a pipelined loop reaches memory the model cannot "
                          f"name ({inst.text})")
        return next(k for k in ("global", "ram", "register") if k in kinds)

    def canonical(self, value):
        """A value through its integer casts (sext, zext, trunc), so that two casts of one index compare equal."""
        inst = self.function.defs.get(value)
        while inst is not None and inst.opcode in ("sext", "zext", "trunc") and inst.operands:
            value = inst.operands[0]
            inst = self.function.defs.get(value)
        return value

    def key_of(self, value, depth=0):
        """The address a pointer value names, as a tuple of its root and indices, equal for equal addresses."""
        if value in self.keys:
            return self.keys[value]
        inst = self.function.defs.get(value)
        key = (value,)
        if inst is not None and depth < 50:
            if inst.opcode == "getelementptr" and inst.operands:
                indices = re.sub(r"^.*?%" + re.escape(inst.operands[0]) + r"\b", "", inst.text.split(", !")[0])
                parts = []
                for part in indices.split(","):
                    token = part.strip().split()[-1] if part.strip() else ""
                    parts.append(self.canonical(token[1:]) if token.startswith("%") else token)
                key = self.key_of(inst.operands[0], depth + 1) + tuple(parts)
            elif inst.opcode in ("bitcast", "addrspacecast") and inst.operands:
                key = self.key_of(inst.operands[0], depth + 1)
            elif inst.opcode == "phi":
                keys = {self.key_of(v, depth + 1) for v in inst.operands}
                key = keys.pop() if len(keys) == 1 and len(inst.operands) == len(inst.phi) else (value,)
        self.keys[value] = key
        return key

    def pointer(self, inst):
        """The pointer operand of a load or store (a store's last operand)."""
        return inst.operands[-1] if inst.operands else None

    def inductions(self):
        """Names of the header phis that are simple induction variables: the latch adds a constant to them."""
        names = set()
        for phi in self.header_phis:
            for value, block in phi.phi:
                step = self.in_loop.get(value) if block in self.loop.latches else None
                if step is not None and step.opcode in ("add", "sub") and step.operands == [phi.name]:
                    names.add(phi.name)
        return names

    def address_keys(self, pointer):
        """The address keys a pointer may take: one, or one per pointer it selects between."""
        inst = self.function.defs.get(pointer)
        if inst is not None and inst.opcode in ("select", "phi") and inst.opcode + " " in inst.text and \
                self.roots_of(pointer)[0][0] != "unknown":
            pointers = inst.operands if inst.opcode == "phi" else inst.operands[1:]
            keys = [k for p in pointers for k in self.address_keys(p)]
            if len(set(keys)) > 1:
                return keys
        return [self.key_of(pointer)]

    def stride_of(self, key):
        """The induction variable an address key moves with (every other index loop-invariant), or None."""
        inductions, moving = self.inductions(), set()
        for part in key[1:]:
            if part in self.in_loop:
                base = self.affine_base(part, inductions)
                if base is None:
                    return None
                if base != "invariant":
                    moving.add(base)
        return moving.pop() if len(moving) == 1 else None

    def affine_base(self, value, inductions, depth=0):
        """"invariant" for a value the loop does not define, the induction variable a value is affine in, or None."""
        inst = self.in_loop.get(value)
        if inst is None:
            return "invariant"
        if value in inductions:
            return value
        if depth > 20 or inst.opcode not in ("add", "sub", "mul", "shl", "or", "sext", "zext", "trunc", "select"):
            return None
        operands = inst.operands[1:] if inst.opcode == "select" else inst.operands  # either of two addresses
        bases = {self.affine_base(v, inductions, depth + 1) for v in operands}
        if None in bases:
            return None
        bases.discard("invariant")
        moving = [v for v in operands if v in self.in_loop]
        if len(bases) > 1 or (inst.opcode in ("mul", "shl") and len(moving) > 1):
            return None
        return bases.pop() if bases else "invariant"

    def latency(self, inst):
        """Clocks of one instruction for the target."""
        table = self.target.latency
        if inst.opcode == "phi" and inst.block == self.loop.header:
            return 0
        total = 0
        for cls in operator_classes(inst):
            if cls in ("load", "store"):
                memory = self.memory_kind(inst)
                cls = "register" if memory == "register" else f"{memory} {'read' if cls == 'load' else 'write'}"
            total += table[cls]
        return total

    def dependence_edges(self):
        """{id(instruction): [predecessor instructions]} within one iteration: data, the conditions that select a
        merged value or guard a write or a global read, and a write to the address a later read reads."""
        preds = {}
        last_store = {}
        for inst in self.insts:
            edges = [self.in_loop[v] for v in inst.operands if v in self.in_loop]
            if inst.opcode == "phi" and inst.block != self.loop.header:
                edges = [self.in_loop[v] for v, _ in inst.phi if v in self.in_loop]
                edges += [self.in_loop[c] for c in self.selectors[inst.block]]
            if inst.opcode == "phi" and inst.block == self.loop.header:
                edges = []
            if inst.opcode == "store" or (inst.opcode == "load" and self.memory_kind(inst) == "global"):
                edges += [self.in_loop[c] for c in self.guards[inst.block]]
            if inst.opcode == "load":
                key = self.key_of(self.pointer(inst))
                if key in last_store:
                    edges.append(last_store[key])
            if inst.opcode == "store":
                last_store[self.key_of(self.pointer(inst))] = inst
            preds[id(inst)] = [e for e in edges if self.position[id(e)] < self.position[id(inst)]]
        return preds

    def longest(self, sources):
        """{id(instruction): (clocks, previous instruction)} of the longest paths from any of `sources`."""
        best = {}
        source_ids = {id(s) for s in sources}
        for inst in self.insts:
            start = 0 if id(inst) in source_ids else None
            prev = None
            for p in self.preds[id(inst)]:
                if id(p) in best and (start is None or best[id(p)][0] > start):
                    start, prev = best[id(p)][0], p
            if start is not None:
                best[id(inst)] = (start + self.latency(inst), prev)
        return best

    def path(self, best, end):
        """The instructions of the longest path ending at `end`, first to last."""
        out = []
        while end is not None:
            out.append(end)
            end = best[id(end)][1]
        return list(reversed(out))

    def register_chains(self):
        """Each header phi's dependence: from the phi to its value from the latch (distance 1)."""
        chains = []
        for phi in self.header_phis:
            ends = [self.in_loop[v] for v, b in phi.phi if b in self.loop.latches and v in self.in_loop]
            if not ends:
                continue
            best = self.longest([phi])
            reached = [e for e in ends if id(e) in best]
            if not reached:
                continue
            end = max(reached, key=lambda e: best[id(e)][0])
            chains.append(Chain(phi.name, "register", best[id(end)][0], 1, self.path(best, end)))
        return chains

    def memory_chains(self):
        """Each array read and written in the loop: from a read to a write of it, at its declared distance."""
        accesses = collections.defaultdict(lambda: ([], []))
        for inst in self.insts:
            if inst.opcode in ("load", "store"):
                for root in self.roots_of(self.pointer(inst)):
                    accesses[root][0 if inst.opcode == "load" else 1].append(inst)
        chains = []
        for (kind, name), (loads, stores) in sorted(accesses.items()):
            if not loads or not stores:
                continue
            strides = {self.stride_of(k) for i in loads + stores for k in self.address_keys(self.pointer(i))}
            if len(strides) == 1 and None not in strides:
                continue  # each iteration reads and writes its own elements (one per plane of the index space)
            best = self.longest(loads)
            reached = [s for s in stores if id(s) in best]
            if not reached:
                continue
            end = max(reached, key=lambda s: best[id(s)][0])
            distance = self.distance(kind, name)
            chains.append(Chain(name, kind, best[id(end)][0], distance, self.path(best, end)))
        return chains

    def distance(self, kind, name):
        """The dependence distance the source declares for an array, for the target."""
        if kind == "register":
            return 1
        if self.target.ivdep and self.source.safelen:
            return parameter_value(self.source.safelen, self.params)
        if self.target.hls_dependence and name in self.source.dependences:
            return parameter_value(self.source.dependences[name], self.params)
        return 1

    def summary(self, chain):
        """The operators of a chain's longest path with a latency, counted: "RAM read, fmul x3, fdiv x2 (1 by a
        constant), ..."."""
        counts = collections.Counter()
        constant_divisions = 0
        for inst in chain.path:
            if self.latency(inst) == 0:
                continue
            for cls in operator_classes(inst):
                if cls in ("load", "store"):
                    kind = self.memory_kind(inst)
                    if kind == "register":
                        continue
                    cls = f"{'global' if kind == 'global' else 'RAM'} {'read' if cls == 'load' else 'write'}"
                counts[SUMMARY_NAMES.get(cls, cls)] += 1
            if inst.opcode == "fdiv" and re.search(r", [-\d.e+]+$|, 0x[0-9A-F]+$", inst.text.split(", !")[0]):
                constant_divisions += 1
        parts = []
        for cls, n in counts.items():
            text = cls if n == 1 else f"{cls} x{n}"
            if cls == "divide" and constant_divisions:
                text += f" ({constant_divisions} by a constant)"
            parts.append(text)
        return ", ".join(parts) or "no operator of latency"


# ---- the model of all kernels, per target ----

class KernelLoop:
    """One pipelined loop of one kernel with its model per target."""

    def __init__(self, kernel, name, source, function_name):
        self.kernel, self.name, self.source, self.function_name = kernel, name, source, function_name
        self.models = {}  # target -> LoopModel (the worst of the loop's copies in the IR)


def loop_names(located):
    """{(path, line): loop name} of located loops [(path, line, source function)]."""
    by_function = collections.defaultdict(set)
    for path, line, function in located:
        by_function[function].add((path, line))
    names = {}
    for function, places in by_function.items():
        ordered = sorted(places)
        given = LOOP_NAMES.get(function)
        for n, place in enumerate(ordered):
            if given and n < len(given):
                names[place] = given[n]
            else:
                names[place] = "pixel" if len(ordered) == 1 else f"{function} loop {n + 1}"
    return names


def model_kernels(args, params_dir, params, vendor):
    """{(kernel, loop name): KernelLoop} of every pipelined loop of the single work-item entries, modelled for the
    vendor's targets, with the parameters header in params_dir."""
    kernel_dir = os.path.join(args.root, "kernels")
    sources = source_loops(kernel_dir)
    registers = fpga_budget.registers_in(kernel_dir)
    cl_files = sorted(os.path.join(d, f) for d, _, files in os.walk(kernel_dir) for f in files if f.endswith(".cl"))
    targets = [TARGETS[t] for t in VENDOR_TARGETS[vendor]]
    found, located = [], []
    for path in cl_files:
        ir = fpga_kernel_ir.compile_ir(args.clang, path, [kernel_dir, params_dir], targets[0].macro, IR_OPTIONS)
        metadata = metadata_of_ir(ir)
        for function in functions_of_ir(ir).values():
            if not function.name.endswith("_single"):
                continue
            for loop in natural_loops(function):
                where = loop_location(metadata, loop.loop_md) if loop.loop_md else None
                if where and (where[0], where[1]) in sources:
                    found.append((function, loop, where))
                    located.append(where)
    names = loop_names(located)
    result = {}
    for function, loop, where in found:
        key = (function.name, names[(where[0], where[1])])
        entry = result.setdefault(key, KernelLoop(function.name, key[1], sources[(where[0], where[1])], where[2]))
        for target in targets:
            model = LoopModel(loop, entry.source, target, params, registers)
            old = entry.models.get(target.name)
            if old is None or (model.ii, model.worst.latency if model.worst else 0) > (
                    old.ii, old.worst.latency if old.worst else 0):
                entry.models[target.name] = model
    missing = {k for k in sources if k not in {(w[0], w[1]) for w in located}}
    return result, missing


class VendorModel:
    """The model of one vendor's presets that share a parameters header."""

    def __init__(self, vendor, presets, params, loops, missing):
        self.vendor, self.presets, self.params, self.loops, self.missing = vendor, presets, params, loops, missing


def models(args):
    """[VendorModel] of the presets chosen, one per vendor and parameters header."""
    names = args.board or sorted(f[:-6] for f in os.listdir(args.boards) if f.endswith(".cmake"))
    groups = collections.OrderedDict()
    for name in names:
        out = os.path.join(args.scratch, name)
        fields, params, header = fpga_budget.preset_params(args, os.path.join(args.boards, name + ".cmake"), out)
        vendor = fields["VENDOR"]
        if vendor not in VENDOR_TARGETS:
            raise Problem(f"{name}: vendor {vendor} has no latency table in fpga_latency.py")
        key = (vendor, header)
        if key not in groups:
            groups[key] = (out, params, [])
        groups[key][2].append(name)
    result = []
    for (vendor, _), (out, params, presets) in sorted(groups.items(), key=lambda g: g[0][0]):
        loops, missing = model_kernels(args, os.path.join(out, "kernels"), params, vendor)
        result.append(VendorModel(vendor, presets, params, loops, missing))
    return result


# ---- output ----

def trips(kernel, loop, params):
    """(unit, iterations per unit, how) of a loop with the parameters header's values."""
    unit, loops = TRIPS.get(kernel, (DEFAULT_UNIT, {}))
    iterations, how = loops.get(loop, (1, "1"))
    batch = int(params.get("RF_FRAME_BATCH", "16"))
    return unit.format(batch=batch, pairs=batch // 2), iterations, how


def loop_order(keys):
    """Kernel loops in the order of the tables: by kernel, then as the kernel runs them."""
    ranks = {"rows in": 0, "projector rows in": 1, "slope": 2, "forward": 2, "backward": 3, "z out": 4}
    return sorted(keys, key=lambda k: (k[0], ranks.get(k[1], 2), k[1]))


def chain_text(model):
    """The dominating dependence of a loop model, in words: what carries it and the operators on its path."""
    chain = model.worst
    if chain is None or (chain.kind == "register" and chain.latency == 0):
        return "the loop counters only"
    what = {"register": "register", "ram": "on-chip RAM", "global": "global memory"}[chain.kind]
    return f"`{chain.carrier.split('.')[0]}` ({what}): {model.summary(chain)}"


def columns_of(vendor_models, targets):
    """[(target, VendorModel, title)] of the targets named, one per model of the target's vendor; the title names the
    presets where a vendor's presets have more than one parameters header."""
    titles = {"intel": "Intel", "amd": "AMD", "amd_opencl": "AMD OpenCL C"}
    columns = []
    for t in targets:
        models = [vm for vm in vendor_models if t in VENDOR_TARGETS[vm.vendor]]
        for vm in models:
            columns.append((t, vm, titles[t] if len(models) == 1 else f"{titles[t]} {', '.join(vm.presets)}"))
    return columns


def latency_table(targets):
    """The operator latencies of the targets shown, as a Markdown table."""
    vendors = []
    for t in targets:
        if TARGETS[t].vendor not in vendors:
            vendors.append(TARGETS[t].vendor)
    names = {"intel": f"Intel, Stratix 10 at {CLOCK_MHZ['intel']} MHz",
             "amd": f"AMD, Vitis HLS at {CLOCK_MHZ['amd']} MHz"}
    lines = ["| operator (clocks) | " + " | ".join(names[v] for v in vendors) + " |",
             "| --- |" + " --- |" * len(vendors)]
    for cls in LATENCIES["amd"]:
        if cls in ("int", "register"):
            continue
        lines.append(f"| {cls} | " + " | ".join(str(LATENCIES[v][cls]) for v in vendors) + " |")
    return lines


def markdown(vendor_models):
    """The generated tables of docs/fpga.md's pipelines section: latencies, loops, kernels, and the OpenCL C path."""
    columns = columns_of(vendor_models, TABLE_TARGETS)
    lines = latency_table(list(dict.fromkeys(t for t, _, _ in columns))) + [""]
    for t, vm, _ in columns:
        p = vm.params
        lines.append(f"{TARGETS[t].title}: presets {', '.join(f'`{n}`' for n in vm.presets)}, R_int "
                     f"{p['RF_INTEGRATE_INTERLEAVE']}, R_fuse {p['RF_FUSE_INTERLEAVE']}.")
    titles = [title for _, _, title in columns]
    lines += ["", "| kernel | loop | longest carried dependence: operators on its path | " +
              " | ".join(f"{title}: L / R, II" for title in titles) + " | iterations per unit | clocks per unit, " +
              " / ".join(titles) + " |", "| --- | --- | --- |" + " --- |" * (len(columns) + 2)]
    keys = loop_order({k for _, vm, _ in columns for k in vm.loops})
    totals = collections.OrderedDict()
    for key in keys:
        texts, cells, clocks = [], [], []
        for column, (t, vm, title) in enumerate(columns):
            kl = vm.loops.get(key)
            if kl is None:
                cells.append("-")
                continue
            model = kl.models[t]
            chain = model.worst
            text = chain_text(model)
            if text not in [x for _, x in texts]:
                texts.append((title.split()[0], text))
            latency, distance = (chain.latency, chain.distance) if chain else (0, 1)
            cells.append(f"{latency} / {distance}, **{model.ii}**" if model.ii > 1 else
                         f"{latency} / {distance}, {model.ii}")
            unit, iterations, how = trips(key[0], key[1], vm.params)
            clocks.append(str(iterations * model.ii))
            total = totals.setdefault(key[0], [unit, {}])
            total[1][column] = total[1].get(column, 0) + iterations * model.ii
        chains = texts[0][1] if len(texts) == 1 else "; ".join(f"{v}: {x}" for v, x in texts)
        lines.append(f"| `{key[0]}` | {key[1]} | {chains} | " + " | ".join(cells) + f" | {how} | "
                     + " / ".join(clocks) + " |")
    lines += ["", "| kernel | unit | clocks per unit, " + " / ".join(titles) + " | units per second, "
              + " / ".join(f"{title} at {CLOCK_MHZ[TARGETS[t].vendor]} MHz" for t, _, title in columns) + " |",
              "| --- | --- | --- | --- |"]
    for kernel, (unit, clocks) in totals.items():
        rates = [f"{CLOCK_MHZ[TARGETS[t].vendor] / clocks[c]:.3g} M" for c, (t, _, _) in enumerate(columns)
                 if c in clocks]
        counts = [str(clocks[c]) for c in range(len(columns)) if c in clocks]
        lines.append(f"| `{kernel}` | {unit} | " + " / ".join(counts) + " | " + " / ".join(rates) + " |")
    for _, vm, title in columns_of(vendor_models, ("amd_opencl",)):
        slow = [(key, vm.loops[key].models["amd_opencl"]) for key in loop_order(vm.loops)]
        text = ", ".join(f"`{k[0]}` {k[1]} II {m.ii}" for k, m in slow if m.ii > 1) or "none"
        lines += ["", f"{TARGETS['amd_opencl'].title}: no dependence attribute, so every distance is 1 (and arrays "
                  f"`RF_PARTITION_COMPLETE` in registers); loops above II 1: {text}."]
    return "\n".join(lines) + "\n"


def claims_of(path):
    """[(kernel, loop, {"intel" | "amd" | "all": II})] of the design II table in the pipelines section of a Markdown
    file: `| kernel | loop | design II | ... |`, kernels in backquotes and loops separated by commas (a row holds each
    pair of them), the design II a number or "Intel n, AMD m", where a preset in backquotes may have its own
    ("Intel 2 (`pac_a10` 3), AMD 1"); the keys are "all", "intel", "amd" and preset names."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    start = text.find(SECTION)
    if start < 0:
        raise Problem(f"{path}: no section {SECTION!r}")
    end = text.find("\n## ", start + len(SECTION))
    section = text[start:end if end > 0 else len(text)]
    header = CLAIMS_HEADER.search(section)
    if not header:
        raise Problem(f"{path}: its section {SECTION!r} has no table `| kernel | loop | design II |`")
    claims = []
    for line in section[header.start():].splitlines()[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3:
            raise Problem(f"{path}: design II table row {line!r}: fewer than 3 cells")
        design = cells[2]
        values = {"all": int(design)} if re.fullmatch(r"\d+", design) else {
            name.strip("`").lower(): int(value)
            for name, value in re.findall(r"(Intel|AMD|`\w+`)[^\d`]*?(\d+)", design)}
        if not values:
            raise Problem(f"{path}: design II {design!r}: expected a number or 'Intel n, AMD m'")
        for kernel in re.findall(r"`(\w+)`", cells[0]):
            for loop in cells[1].split(","):
                claims.append((kernel, loop.strip(), values))
    return claims


def check(vendor_models, claims_path, verbose):
    """Problems: a loop whose model II exceeds its design II, a pipelined loop without a design II, a design II of
    no such loop, a marked loop no kernel compiles to. Returns their count; prints the interleaved loops' figures (every
    loop's with verbose, and its dependences)."""
    claims = claims_of(claims_path)
    claimed = {(k, l): v for k, l, v in claims}
    problems = 0
    for vm in vendor_models:
        for path, line in sorted(vm.missing):
            problems += 1
            print(f"{path}:{line}: a loop marked RF_PIPELINE_II that no single work-item entry compiles to as a loop "
                  f"({vm.vendor}): the model cannot see it")
        for key in loop_order(vm.loops):
            for target, model in vm.loops[key].models.items():
                if target not in TABLE_TARGETS:
                    continue
                chain = model.worst
                figure = f"{target} {key[0]} {key[1]}: II {model.ii}"
                if chain:
                    figure += f" (L {chain.latency}, distance {chain.distance}: {chain_text(model)})"
                if verbose or (chain and (chain.distance > 1 or model.ii > 1)):
                    print(figure)
                if verbose:
                    for c in model.chains:
                        ops = " > ".join(f"{i.opcode if i.opcode != 'call' else i.callee}({model.latency(i)})"
                                         for i in c.path if model.latency(i))
                        print(f"    {c.carrier} [{c.kind}, distance {c.distance}]: L {c.latency}, II {c.ii}: {ops}")
                design = claimed.get(key)
                if design is None:
                    problems += 1
                    print(f"  problem: {claims_path} states no design II for {key[0]} {key[1]} (its table "
                          f"`| kernel | loop | design II |`)")
                    continue
                own = [design[p.lower()] for p in vm.presets if p.lower() in design]
                limit = min(own) if own else design.get(TARGETS[target].vendor, design.get("all"))
                if limit is not None and model.ii > limit:
                    problems += 1
                    print(f"  problem: {target} {key[0]} {key[1]}: the model's II {model.ii} exceeds the design II "
                          f"{limit} of {claims_path}: L {chain.latency} over a distance of {chain.distance}, "
                          f"{chain_text(model)}")
    modelled = {key for vm in vendor_models for key in vm.loops}
    for kernel, loop, _ in claims:
        if (kernel, loop) not in modelled:
            problems += 1
            print(f"  problem: {claims_path}: a design II for {kernel} {loop}, which is no pipelined loop of the model")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    fpga_budget.add_preset_arguments(parser)
    parser.add_argument("--claims", help="the Markdown file with the design II table (default ROOT/docs/fpga.md)")
    parser.add_argument("--verbose", action="store_true", help="every dependence of every loop, with its operators")
    docs_table.add_output_arguments(parser, "latency tables")
    args = parser.parse_args()
    ready, scratch = fpga_budget.resolve_preset_arguments(args, "fpga_latency.py")
    if not ready:
        return 2
    args.claims = args.claims or os.path.join(args.root, "docs", "fpga.md")
    try:
        vendor_models = models(args)
        written = docs_table.output(args, "fpga_latency.py", lambda: markdown(vendor_models), "latency tables")
        if written is not None:
            return written
        problems = check(vendor_models, args.claims, args.verbose)
        count = sum(len(vm.loops) for vm in vendor_models)
        print(f"fpga_latency.py: {count} pipelined loops: {'ok' if not problems else f'{problems} problem(s)'}",
              file=sys.stderr)
        return 1 if problems else 0
    except (Problem, fpga_budget.Problem, docs_table.MissingMarkers) as problem:
        print(f"fpga_latency.py: {problem}")
        return 1
    finally:
        if scratch:
            shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
