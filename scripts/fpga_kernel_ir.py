"""What clang's LLVM IR of the kernels shows a resource budget: on-chip arrays and DSP-heavy operators per kernel.

Each .cl file is compiled as the hw/ flows compile it (OpenCL C 1.2, a target macro, include paths kernels/ and the
generated parameters header's directory), to IR at -O2 without vectorizing or unrolling beyond the kernels' own
unroll directives: every helper is inlined into its kernel, so an array still held in memory is an `alloca` of the
kernel (its element count and width as the parameters make them), and every operator instruction left in a kernel
is one operator of its pipeline (a tool shares none at II 1).
"""
import collections
import re
import subprocess

CLANG_OPTIONS = ["-target", "spir64", "-x", "cl", "-cl-std=CL1.2", "-Xclang", "-finclude-default-header",
                 "-D__OPENCL_VERSION__=120", "-O2", "-fno-vectorize", "-fno-slp-vectorize", "-fno-unroll-loops",
                 "-fno-discard-value-names", "-w", "-emit-llvm", "-S", "-o", "-"]

FUNCTION = re.compile(r"^define ([^@\n]*)@(\w+)\(.*?^}", re.S | re.M)
STRUCT = re.compile(r"^%(struct\.\w+) = type \{ (.*) \}$", re.M)
ALLOCA = re.compile(r"^\s+%([\w.-]+) = alloca (\[.*?\]), align", re.M)
FDIV = re.compile(r"= fdiv (?:\w+ )*?(?:<(\d+) x )?(?:float|double)")
CALL = re.compile(r"\bcall [^@\n]*?(?:<(\d+) x \w+>|\w+) @([\w.]+)\(")
INTEGER_DIVIDE = re.compile(r"= [su](?:div|rem) (?:exact )?(?:<(\d+) x )?i\d+ [^,]+, (%?)")

# Operator categories: a name of the mathematical function a call is to, demangled ("_Z4sqrtf" -> "sqrt").
CALL_CATEGORY = {"sqrt": "sqrt", "rsqrt": "sqrt", "hypot": "atan2/hypot", "atan2": "atan2/hypot", "atan": "atan2/hypot",
                 "exp": "exp/log/pow", "log": "exp/log/pow", "pow": "exp/log/pow", "sin": "sin/cos",
                 "cos": "sin/cos"}
OPERATORS = ("fdiv", "sqrt", "atan2/hypot", "exp/log/pow", "sin/cos", "int div by constant", "int div")


def element_bits(type_text, structs):
    """Bits of one element of an IR type: a scalar, a vector, a struct of the module, or an array."""
    type_text = type_text.strip()
    array = re.fullmatch(r"\[(\d+) x (.*)\]", type_text)
    if array:
        return int(array[1]) * element_bits(array[2], structs)
    vector = re.fullmatch(r"<(\d+) x (.*)>", type_text)
    if vector:
        return int(vector[1]) * element_bits(vector[2], structs)
    if type_text in ("float", "i32"):
        return 32
    if type_text in ("double", "i64") or type_text.endswith("*"):
        return 64
    scalar = re.fullmatch(r"i(\d+)", type_text)
    if scalar:
        return int(scalar[1])
    if type_text == "half":
        return 16
    if type_text.startswith("%struct."):
        return sum(element_bits(field, structs) for field in split_fields(structs[type_text[1:]]))
    raise ValueError(f"unknown IR type {type_text}")


def split_fields(text):
    """The comma-separated fields of a struct type, commas inside brackets kept."""
    fields, depth, start = [], 0, 0
    for i, c in enumerate(text):
        depth += c in "[<{"
        depth -= c in "]>}"
        if c == "," and depth == 0:
            fields.append(text[start:i])
            start = i + 1
    return fields + [text[start:]]


def demangled(name):
    """"_Z5atan2ff" -> "atan2", "llvm.sqrt.f32" -> "sqrt", other names as they are."""
    itanium = re.match(r"_Z(\d+)(\w+)", name)
    if itanium:
        return itanium[2][:int(itanium[1])]
    if name.startswith("llvm."):
        return name.split(".")[1]
    return name


class Kernel:
    """One kernel of the IR: `arrays` [(name, words, width in bits)], `operators` {category: count}."""

    def __init__(self, name, arrays, operators):
        self.name = name
        self.arrays = arrays
        self.operators = operators


def kernels_of_ir(ir_text):
    """{kernel name: Kernel} of one module's IR text."""
    structs = {m[1]: m[2] for m in STRUCT.finditer(ir_text)}
    kernels = {}
    for function in FUNCTION.finditer(ir_text):
        if "spir_kernel" not in function[1]:
            continue
        body = function[0]
        arrays = []
        for alloca in ALLOCA.finditer(body):
            outer = re.fullmatch(r"\[(\d+) x (.*)\]", alloca[2])
            arrays.append((alloca[1].split(".")[0], int(outer[1]), element_bits(outer[2], structs)))
        operators = collections.Counter()
        for fdiv in FDIV.finditer(body):
            operators["fdiv"] += int(fdiv[1] or 1)
        for call in CALL.finditer(body):
            category = CALL_CATEGORY.get(demangled(call[2]))
            if category:
                operators[category] += int(call[1] or 1)
        for divide in INTEGER_DIVIDE.finditer(body):
            operators["int div" if divide[2] else "int div by constant"] += int(divide[1] or 1)
        kernels[function[2]] = Kernel(function[2], arrays, operators)
    return kernels


def compile_ir(clang, cl_path, includes, macro, extra_options=()):
    """The LLVM IR text of one .cl file compiled under `macro` with the include directories and options given."""
    command = [clang] + CLANG_OPTIONS + list(extra_options) + [f"-I{d}" for d in includes] + [f"-D{macro}", cl_path]
    run = subprocess.run(command, capture_output=True, text=True, check=False)
    if run.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {run.returncode}:\n{run.stderr.strip()}")
    return run.stdout


def compile_kernels(clang, cl_path, includes, macro):
    """{kernel name: Kernel} of one .cl file compiled under `macro` with the include directories given."""
    return kernels_of_ir(compile_ir(clang, cl_path, includes, macro))
