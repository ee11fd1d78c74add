#!/usr/bin/env python3
"""Stand-ins for the vendor FPGA compilers (aoc, v++, emconfigutil) used by the hw/ flow tests: each checks its command
line against the options the flows use, logs it (one JSON array per line to $RFRECON_STANDIN_LOG when set) and writes
its outputs as text files marked "rfrecon stand-in", which no OpenCL runtime would load.

  standin_tools.py aoc|v++|emconfigutil ARGS...   (tests/fpga/bin/ holds wrappers named like the real tools)
v++ takes both forms of compiling an HLS C++ top: `v++ -c -t TARGET -k TOP FILE.cpp` and `v++ -c --mode hls --config
FILE.cfg` (the platform and an [hls] section: flow_target=vitis, syn.file, syn.top, syn.cflags, package.output.*).
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


def vxx_at_least(version):
    return tuple(int(part) for part in vxx_version().split(".")[:2]) >= version


# The keys a `v++ -c --mode hls` configuration may hold (UG1702 / UG1399 "HLS Config File Commands"), by section: ""
# for the general options before any section header.
HLS_CONFIG_KEYS = {"": {"platform", "part"},
                   "hls": {"flow_target", "syn.file", "syn.top", "syn.cflags", "package.output.format",
                           "package.output.file"}}


def read_hls_config(path):
    """{(section, key): [values]} of an HLS configuration file; refuses unknown sections and keys."""
    if not path or not os.path.isfile(path):
        raise Usage(f"--config {path}: no such file")
    entries, section = {}, ""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            header = re.fullmatch(r"\[(\w+)\]", line)
            if header:
                section = header[1].lower()
                if section not in HLS_CONFIG_KEYS:
                    raise Usage(f"{path}:{number}: section [{header[1]}] is not one of v++ --mode hls")
                continue
            key, equals, value = line.partition("=")
            key, value = key.strip(), value.strip()
            if not equals or key not in HLS_CONFIG_KEYS[section]:
                raise Usage(f"{path}:{number}: {line!r} is not an option of section [{section}]"
                            f" (expected one of {sorted(HLS_CONFIG_KEYS[section])})")
            entries.setdefault((section, key), []).append(value)
    return entries


def vxx_hls(config, work_dir):
    """`v++ -c --mode hls --config FILE`: HLS synthesis of one top into a .xo for hw_emu and hw (Vitis 2023.1 on)."""
    if not vxx_at_least((2023, 1)):
        raise Usage(f"v++ {vxx_version()} has no --mode hls (Vitis 2023.1 and later)")
    entries = read_hls_config(config)

    def one(section, key):
        values = entries.get((section, key), [])
        if len(values) != 1:
            raise Usage(f"{config}: expected one {key}= in [{section or 'general'}], found {values}")
        return values[0]

    platforms = entries.get(("", "platform"), []) + entries.get(("", "part"), [])
    if len(platforms) != 1:
        raise Usage(f"{config}: expected one platform= or part= before [hls], found {platforms}")
    if one("hls", "flow_target") != "vitis":
        raise Usage(f"{config}: flow_target must be vitis for a Vitis kernel (.xo)")
    sources = entries.get(("hls", "syn.file"), [])
    if not sources or not all(s.endswith(".cpp") and os.path.isfile(s) for s in sources):
        raise Usage(f"{config}: syn.file {sources}: expected existing .cpp files")
    cflags = " ".join(entries.get(("hls", "syn.cflags"), [])).split()
    includes = [flag[2:] for flag in cflags if flag.startswith("-I")]
    if [flag for flag in cflags if not flag.startswith("-I")] or not includes:
        raise Usage(f"{config}: syn.cflags {cflags}: expected -I<dir> options only")
    check_sources(sources, includes)
    top = one("hls", "syn.top")
    names = []
    for path in sources:
        with open(path, encoding="utf-8") as f:
            names += HLS_TOP.findall(f.read())
    if top not in names:
        raise Usage(f"{config}: syn.top={top}: not an extern \"C\" top of {sources} ({names})")
    if one("hls", "package.output.format") != "xo":
        raise Usage(f"{config}: package.output.format must be xo")
    output = one("hls", "package.output.file")
    if not output.endswith(".xo"):
        raise Usage(f"{config}: package.output.file must name a .xo file, got {output}")
    if work_dir:
        os.makedirs(work_dir, exist_ok=True)
    platform = entries.get(("", "platform"), [None])[0]
    write(output, json.dumps({"mark": MARK, "target": "hls", "platform": platform, "kernel": top}) + "\n")


def vxx(args):
    if args == ["--version"]:
        print(f"****** v++ v{vxx_version()} (64-bit) (rfrecon stand-in)\n  **** SW Build 0 on 2022-10-13-17:52:11")
        return
    mode, target, platform, kernel, output, config = None, None, None, None, None, None
    hls_mode, work_dir = None, None
    includes, defines, inputs = [], [], []
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in ("-c", "-l"):
            if mode:
                raise Usage("both -c and -l")
            mode = arg
        elif arg in ("-t", "--platform", "-k", "-o", "--config", "--temp_dir", "-I", "--mode", "--work_dir"):
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
            elif arg == "--mode":
                hls_mode = value
            elif arg == "--work_dir":
                work_dir = value
        elif arg.startswith("-D") and len(arg) > 2:
            defines.append(arg[2:])
        elif arg.endswith((".cl", ".cpp", ".xo")):
            inputs.append(arg)
        else:
            raise Usage(f"unexpected argument {arg}")
        i += 1
    if hls_mode is not None:
        # Everything but the work directory comes from the configuration file.
        if hls_mode != "hls" or mode != "-c":
            raise Usage(f"--mode {hls_mode}: this stand-in knows only v++ -c --mode hls")
        stray = [a for a, v in (("-t", target), ("--platform", platform), ("-k", kernel), ("-o", output),
                                ("-I", includes), ("-D", defines), ("inputs", inputs)) if v]
        if stray:
            raise Usage(f"v++ -c --mode hls takes its settings from --config, not {stray}")
        vxx_hls(config, work_dir)
        return
    if work_dir:
        raise Usage("--work_dir belongs to v++ -c --mode hls")
    if target not in ("sw_emu", "hw_emu", "hw"):
        raise Usage(f"-t {target}: expected sw_emu, hw_emu or hw")
    if not platform:
        raise Usage("no --platform")
    if mode == "-c":
        # Vitis 2023.1 and later compile C++ (HLS) kernels only, earlier releases the OpenCL C ones too.
        hls = vxx_at_least((2023, 1))
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
            # An .xo of v++ --mode hls (HLS synthesis) serves hw_emu and hw; software emulation needs v++ -c -k.
            built_for = ("hw_emu", "hw") if xo.get("target") == "hls" else (xo.get("target"),)
            if xo.get("mark") != MARK or target not in built_for or xo["platform"] != platform:
                raise Usage(f"{path}: not a stand-in .xo for -t {target} --platform {platform} (one for"
                            f" {', '.join(map(str, built_for))}, --platform {xo.get('platform')})")
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
