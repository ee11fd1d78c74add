#!/usr/bin/env python3
"""Stand-ins for the vendor FPGA compilers (aoc, v++, emconfigutil) used by the hw/ flow tests: each checks its command
line against the options the flows use, logs it (one JSON array per line to $RFRECON_STANDIN_LOG when set) and writes
its outputs as text files marked "rfrecon stand-in", which no OpenCL runtime would load.

  standin_tools.py aoc|v++|emconfigutil ARGS...   (tests/fpga/bin/ holds wrappers named like the real tools)
Exit status 0, or 2 with a message when the command line is wrong. $RFRECON_STANDIN_VERSION overrides the version.
"""
import json
import os
import re
import sys

MARK = "rfrecon stand-in: not an FPGA binary"
KERNEL = re.compile(r"__kernel\s+void\s+(\w+)\s*\(")
HLS_TOP = re.compile(r'extern\s+"C"\s+void\s+(\w+)\s*\(')


class Usage(Exception):
    pass


def take(args, i, option):
    if i + 1 >= len(args):
        raise Usage(f"{option} needs a value")
    return args[i + 1]


def write(path, text):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def check_sources(sources, includes):
    if not sources:
        raise Usage("no .cl input file")
    for path in sources:
        if not os.path.isfile(path):
            raise Usage(f"input {path} does not exist")
    if not includes or not all(os.path.isdir(d) for d in includes):
        raise Usage(f"include directories missing or not directories: {includes}")


def aoc(args):
    if args == ["-version"]:
        version = os.environ.get("RFRECON_STANDIN_VERSION", "22.4.0")
        print(f"Intel(R) FPGA SDK for OpenCL(TM), 64-Bit Offline Compiler (rfrecon stand-in)\n"
              f"Version {version} Build 94 Pro Edition")
        return
    flags, board, output, includes, defines, sources = set(), None, None, [], [], []
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in ("-march=emulator", "-rtl", "-report"):
            flags.add(arg)
        elif arg.startswith("-board="):
            board = arg.split("=", 1)[1]
        elif arg == "-o":
            output = take(args, i, arg)
            i += 1
        elif arg == "-I":
            includes.append(take(args, i, arg))
            i += 1
        elif arg.startswith("-D") and len(arg) > 2:
            defines.append(arg[2:])
        elif arg.endswith(".cl"):
            sources.append(arg)
        else:
            raise Usage(f"unexpected argument {arg}")
        i += 1
    if flags not in (set(), {"-march=emulator"}, {"-rtl", "-report"}):
        raise Usage(f"flags {sorted(flags)}: expected -march=emulator, -rtl -report, or neither")
    if not board:
        raise Usage("no -board=")
    check_sources(sources, includes)
    suffix = ".aocr" if "-rtl" in flags else ".aocx"
    if not output or not output.endswith(suffix):
        raise Usage(f"-o must name a {suffix} file, got {output}")
    write(output, f"{MARK}\naoc {' '.join(args)}\n")
    if "-report" in flags:
        write(os.path.join(os.path.splitext(output)[0], "reports", "report.html"), f"<p>{MARK}</p>\n")


def vxx_version():
    return os.environ.get("RFRECON_STANDIN_VERSION", "2022.2")


def vxx(args):
    if args == ["--version"]:
        print(f"****** v++ v{vxx_version()} (64-bit) (rfrecon stand-in)\n  **** SW Build 0 on 2022-10-13-17:52:11")
        return
    mode, target, platform, kernel, output, config = None, None, None, None, None, None
    includes, defines, inputs = [], [], []
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in ("-c", "-l"):
            if mode:
                raise Usage("both -c and -l")
            mode = arg
        elif arg in ("-t", "--platform", "-k", "-o", "--config", "--temp_dir", "-I"):
            value = take(args, i, arg)
            i += 1
            if arg == "-t":
                target = value
            elif arg == "--platform":
                platform = value
            elif arg == "-k":
                if kernel:
                    raise Usage("v++ takes one -k per compile")
                kernel = value
            elif arg == "-o":
                output = value
            elif arg == "--config":
                config = value
            elif arg == "-I":
                includes.append(value)
        elif arg.startswith("-D") and len(arg) > 2:
            defines.append(arg[2:])
        elif arg.endswith((".cl", ".cpp", ".xo")):
            inputs.append(arg)
        else:
            raise Usage(f"unexpected argument {arg}")
        i += 1
    if target not in ("sw_emu", "hw_emu", "hw"):
        raise Usage(f"-t {target}: expected sw_emu, hw_emu or hw")
    if not platform:
        raise Usage("no --platform")
    if mode == "-c":
        # Vitis 2023.1 and later compile C++ (HLS) kernels only, earlier releases the OpenCL C ones too.
        hls = tuple(int(part) for part in vxx_version().split(".")[:2]) >= (2023, 1)
        language = ".cpp" if hls else ".cl"
        check_sources(inputs, includes)
        if len(inputs) != 1 or not inputs[0].endswith(language):
            raise Usage(f"v++ {vxx_version()} -c compiles one {language} file, got {inputs}")
        with open(inputs[0], encoding="utf-8") as f:
            names = (HLS_TOP if hls else KERNEL).findall(f.read())
        if kernel not in names:
            raise Usage(f"-k {kernel}: not a kernel of {inputs[0]} ({names})")
        if not output or not output.endswith(".xo"):
            raise Usage(f"-o must name a .xo file, got {output}")
        write(output, json.dumps({"mark": MARK, "target": target, "platform": platform, "kernel": kernel}) + "\n")
    elif mode == "-l":
        if not inputs or not all(p.endswith(".xo") for p in inputs):
            raise Usage(f"v++ -l links .xo files, got {inputs}")
        kernels = []
        for path in inputs:
            with open(path, encoding="utf-8") as f:
                xo = json.load(f)
            if xo.get("mark") != MARK or xo["target"] != target or xo["platform"] != platform:
                raise Usage(f"{path}: not a stand-in .xo for -t {target} --platform {platform}")
            kernels.append(xo["kernel"])
        if not config or not os.path.isfile(config):
            raise Usage(f"--config {config}: no such file")
        with open(config, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                cu = re.match(r"(nk|sp)=(\w+)", line)
                if cu and cu[2] not in kernels and cu[2].rsplit("_", 1)[0] not in kernels:
                    raise Usage(f"{config}:{number}: {cu[2]} is not a linked kernel ({kernels})")
        if not output or not output.endswith(".xclbin"):
            raise Usage(f"-o must name a .xclbin file, got {output}")
        write(output, json.dumps({"mark": MARK, "target": target, "platform": platform, "kernels": kernels}) + "\n")
    else:
        raise Usage("neither -c nor -l")


def emconfigutil(args):
    if len(args) != 4 or args[0] != "--platform" or args[2] != "--od":
        raise Usage("expected --platform NAME --od DIR")
    write(os.path.join(args[3], "emconfig.json"), json.dumps({"mark": MARK, "platform": args[1]}) + "\n")


def main():
    tool, args = sys.argv[1], sys.argv[2:]
    log = os.environ.get("RFRECON_STANDIN_LOG")
    if log and not any(a in ("-version", "--version") for a in args):
        with open(log, "a", encoding="utf-8") as f:
            f.write(json.dumps([tool] + args) + "\n")
    try:
        {"aoc": aoc, "v++": vxx, "emconfigutil": emconfigutil}[tool](args)
    except Usage as problem:
        print(f"{tool} (rfrecon stand-in): {problem}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
