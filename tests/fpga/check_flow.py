#!/usr/bin/env python3
"""Checks one board preset's hw/ flow with the stand-in vendor compilers of tests/fpga/bin/ (ctest fpga_flow_<board>).

In a scratch build directory: configures hw/ for the board, builds `all` (no vendor tool may run), then each FPGA
target, and checks the logged aoc / v++ command lines (every kernel file, the board or platform, the -D target macro,
the include path of the generated parameters header, the link configuration), the header's default values, the
manifest beside each binary, the link configuration's memory banks (every global buffer of every linked kernel), the
environment of the emulation binary's runs (emulation.env: for Intel boards the emulator's private memory), for AMD
boards the same with Vitis 2023.1 and 2025.1 (every single work-item entry compiled from its HLS C++ top in hw/hls/:
`v++ -c -k`, and from 2024.2 for hw_emu and hw `v++ -c --mode hls` with a generated configuration, whose keys are
checked; RFRECON_VITIS_HLS_MODE=kernel forces the first), and that a tool version outside the supported range, or
--mode hls with a Vitis without it, is refused at configure.

  check_flow.py --board NAME --root SOURCE_DIR --scratch DIR [--cmake PATH]
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

BIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin")
KERNEL = re.compile(r"__kernel\s+void\s+(\w+)\s*\(([^)]*)\)")
HLS_TOP = re.compile(r'extern\s+"C"\s+void\s+(\w+)\s*\(([^)]*)\)')
INTEL = {"520n": "p520_max_sg280l", "pac_a10": "pac_a10", "d5005": "pac_s10_dc"}
XILINX = {"u250": "xilinx_u250_gen3x16_xdma_4_1_202210_1", "u280": "xilinx_u280_gen3x16_xdma_1_202211_1"}


class Failure(Exception):
    pass


def expect(condition, message):
    if not condition:
        raise Failure(message)


# The parameters header's defaults (cmake/EmbedKernelsParams.cmake); a preset's set(RFRECON_PRESET_<NAME> value)
# replaces one (preset_parameters).
DEFAULTS = {"RF_K": 8, "RF_INTEGRATE_INTERLEAVE": 160, "RF_FUSE_INTERLEAVE": 32, "RF_MAX_ROW_WIDTH": 4096,
            "RF_FRAME_BATCH": 16, "RF_DOT_SPACINGS": list(range(2, 65))}
PARAMS_H = os.path.join("common", "params.h")


def preset_parameters(root, board):
    """The parameters a board's flow, and its manifests, must hold: the defaults, with the preset's own values."""
    with open(os.path.join(root, "hw", "boards", board + ".cmake"), encoding="utf-8") as f:
        found = re.findall(r"^set\(RFRECON_PRESET_(\w+) ([\d ;]+)\)$", f.read(), re.M)
    parameters = dict(DEFAULTS)
    for name, value in found:
        values = [int(v) for v in re.split(r"[ ;]+", value.strip())]
        parameters["RF_" + name] = values if isinstance(DEFAULTS["RF_" + name], list) else values[0]
    return parameters


def file_digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def listing_hash(digests):
    """A manifest's source hash: SHA-256 over "path\\n<SHA-256 of the file>\\n" of each (path, digest), sorted."""
    return hashlib.sha256("".join(f"{path}\n{digest}\n" for path, digest in sorted(digests)).encode()).hexdigest()


def kernels_of(kernel_dir, generated_dir):
    """{relative .cl path: {kernel name: [global buffer argument names]}}, and the (path, SHA-256) of every .cl and .h
    file of kernels/ and of the generated common/params.h, which an OpenCL binary's source hash covers."""
    files = {}
    for d, _, names in os.walk(kernel_dir):
        for name in names:
            path = os.path.join(d, name)
            relative = os.path.relpath(path, kernel_dir)
            if name.endswith(".cl"):
                with open(path, encoding="utf-8") as f:
                    files[relative] = {m[1]: [re.findall(r"(\w+)\s*$", a)[0] for a in m[2].split(",")
                                              if "__global" in a] for m in KERNEL.finditer(f.read())}
    sources = [os.path.relpath(os.path.join(d, n), kernel_dir) for d, _, names in os.walk(kernel_dir)
               for n in names if n.endswith((".cl", ".h"))]
    digests = [(relative, file_digest(os.path.join(generated_dir if relative == PARAMS_H else kernel_dir, relative)))
               for relative in sources + [PARAMS_H]]
    return files, digests


def hls_digests(root):
    """The (hw/hls/NAME, SHA-256) of each .cpp and .h file of the HLS C++ tops, which an HLS binary's hash adds."""
    hls_dir = os.path.join(root, "hw", "hls")
    return [(f"hw/hls/{name}", file_digest(os.path.join(hls_dir, name))) for name in os.listdir(hls_dir)
            if name.endswith((".cpp", ".h"))]


def run(command, env, must_pass=True):
    result = subprocess.run(command, env=env, capture_output=True, text=True, check=False)
    if must_pass and result.returncode != 0:
        raise Failure(f"{' '.join(command)} exited {result.returncode}:\n{result.stdout}{result.stderr}")
    return result


def logged(log):
    if not os.path.exists(log):
        return []
    with open(log, encoding="utf-8") as f:
        lines = [json.loads(line) for line in f]
    os.remove(log)
    return lines


def check_manifest(binary, target, tool, macro, device, board, kernels, source_hash, parameters):
    expect(os.path.isfile(binary), f"{binary} not built")
    with open(binary + ".json", encoding="utf-8") as f:
        manifest = json.load(f)
    wanted = {"binary": os.path.basename(binary), "board": board, "device": device, "target": target, "tool": tool,
              "target_macro": macro, "stand_in": True, "source_sha256": source_hash,
              "parameters": parameters, "extra_flags": []}
    wanted["binary_sha256"] = file_digest(binary)
    for key, value in wanted.items():
        expect(manifest.get(key) == value, f"{binary}.json: {key} is {manifest.get(key)!r}, expected {value!r}")
    expect(sorted(manifest["kernels"]) == sorted(kernels), f"{binary}.json: kernels {manifest['kernels']}")
    expect(re.fullmatch(r"\d+\.\d+(\.\d+)?", manifest["tool_version"]), f"tool_version {manifest['tool_version']}")


def emulator_private_mb(root, parameters):
    """CL_CONFIG_CPU_FORCE_PRIVATE_MEM_SIZE in MB: twice the larger of the depth kernels' private rows, which
    kernels/depth/row_buffers.h gives as RF_INTEGRATE_PRIVATE_BYTES and RF_FUSE_PRIVATE_BYTES (evaluated here with the
    preset's parameters, a 4-byte float and the header's numeric macros), rounded up to whole MB."""
    with open(os.path.join(root, "kernels", "depth", "row_buffers.h"), encoding="utf-8") as f:
        text = f.read().replace("\\\n", " ")
    numbers = dict(parameters, **{m[1]: int(m[2]) for m in re.finditer(r"^#define (\w+) (\d+)$", text, re.M)})
    largest = 0
    for kernel in ("INTEGRATE", "FUSE"):
        found = re.search(rf"^#define RF_{kernel}_PRIVATE_BYTES (.*)$", text, re.M)
        expect(found, f"row_buffers.h defines no RF_{kernel}_PRIVATE_BYTES")
        expression = found[1].replace("(size_t)", "").replace("sizeof(float)", "4")
        expression = re.sub(r"\bRF_\w+\b", lambda m: str(numbers.get(m[0], m[0])), expression)
        expect(re.fullmatch(r"[\d\s()*+]+", expression), f"RF_{kernel}_PRIVATE_BYTES: cannot evaluate {expression}")
        largest = max(largest, eval(expression))  # digits and arithmetic only, checked above
    return 2 * -(-largest // (1 << 20))


def check_emulation_env(build, expected):
    """emulation.env, the environment of the emulation binary's runs, holds exactly `expected` (VARIABLE: value)."""
    with open(os.path.join(build, "emulation.env"), encoding="utf-8") as f:
        found = dict(line.rstrip("\n").split("=", 1) for line in f if line.strip())
    expect(found == expected, f"emulation.env: {found}, expected {expected}")


def read_hls_config(path):
    """{(section, key): [values]} of a generated v++ --mode hls configuration ("" for the general options)."""
    entries, section = {}, ""
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if re.fullmatch(r"\[\w+\]", line):
                section = line[1:-1]
                continue
            key, _, value = line.partition("=")
            entries.setdefault((section, key), []).append(value)
    return entries


def check_params_header(generated_dir, parameters):
    """The generated header defines each parameter with its value (the dot spacings as an initializer list)."""
    with open(os.path.join(generated_dir, PARAMS_H), encoding="utf-8") as f:
        text = f.read()
    for name, value in parameters.items():
        wanted = "{" + ", ".join(map(str, value)) + "}" if isinstance(value, list) else str(value)
        expect(re.search(rf"^#define {name} {re.escape(wanted)}$", text, re.M), f"{PARAMS_H}: {name} is not {wanted}")


def check_host_follows_preset(args, build, env):
    """The host's parameters (cmake/EmbedKernelsParams.cmake, as the whole project includes it) follow the board
    preset that its build is configured with, so that the host accepts the board's binary."""
    script = os.path.join(build, "host_params.cmake")
    with open(script, "w", encoding="utf-8") as f:
        f.write(f"include({args.root}/cmake/EmbedKernelsParams.cmake)\n"
                f"rfrecon_configure_kernel_params({build}/host_params)\n")
    run([args.cmake, f"-DRFRECON_FPGA_BOARD={args.board}", "-P", script], env)
    check_params_header(os.path.join(build, "host_params", "kernels"), args.parameters)


def includes_of(line):
    return [line[i + 1] for i, a in enumerate(line) if a == "-I"]


def check_intel(args, build, env, files, source_hash):
    device, kernel_dir = INTEL[args.board], os.path.join(args.root, "kernels")
    generated_dir = os.path.join(build, "generated", "kernels")
    cl_paths = sorted(os.path.join(kernel_dir, f) for f in files)
    every_kernel = [k for names in files.values() for k in names]
    for target, flags, binary in (("emulator", ["-march=emulator"], f"rfrecon_{args.board}_emulator.aocx"),
                                  ("report", ["-rtl", "-report"], f"rfrecon_{args.board}_report.aocr"),
                                  ("hardware", [], f"rfrecon_{args.board}.aocx")):
        run([args.cmake, "--build", build, "--target", f"rfrecon_fpga_{target}"], env)
        calls = logged(env["RFRECON_STANDIN_LOG"])
        expect(len(calls) == 1 and calls[0][0] == "aoc", f"{target}: expected one aoc call, got {calls}")
        line = calls[0][1:]
        for flag in flags + [f"-board={device}", "-DRF_TARGET_INTEL_FPGA"]:
            expect(flag in line, f"{target}: {flag} missing from aoc {' '.join(line)}")
        expect(not ({"-march=emulator", "-rtl", "-report"} - set(flags)) & set(line), f"{target}: stray flag in {line}")
        expect(sorted(a for a in line if a.endswith(".cl")) == cl_paths, f"{target}: not every kernel file in {line}")
        expect(includes_of(line) == [kernel_dir, generated_dir], f"{target}: include paths {includes_of(line)}")
        expect(not [a for a in line if a.startswith("-DRF_K") or a.startswith("-DRF_ROW")],
               f"{target}: parameters given as -D options, which would bypass the header: {line}")
        check_manifest(os.path.join(build, binary), target, "aoc", "RF_TARGET_INTEL_FPGA", device, args.board,
                       every_kernel, source_hash, args.parameters)
    check_emulation_env(build, {"RFRECON_KERNEL_BINARY": os.path.join(build, f"rfrecon_{args.board}_emulator.aocx"),
                                "CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA": "1",
                                "CL_CONFIG_CPU_FORCE_PRIVATE_MEM_SIZE":
                                    f"{emulator_private_mb(args.root, args.parameters)}MB"})


def check_link_config(path, single):
    """Every global buffer of every single work-item entry has a memory bank; nothing else is named."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    banks = dict(re.findall(r"^sp=(\w+\.\w+):(\S+)$", text, re.M))
    units = set(re.findall(r"^nk=(\w+):1:(\w+)$", text, re.M))
    expect(units == {(k, f"{k}_1") for k in single}, f"{path}: compute units {sorted(units)}")
    wanted = {f"{k}_1.{a}" for k, buffers in single.items() for a in buffers}
    expect(set(banks) == wanted,
           f"{path}: missing banks {sorted(wanted - set(banks))}, extra {sorted(set(banks) - wanted)}")


def hls_tops(hls_dir):
    """{entry name: (the hw/hls/*.cpp file that defines it, its pointer arguments' names)}."""
    tops = {}
    for name in sorted(os.listdir(hls_dir)):
        if name.endswith(".cpp"):
            with open(os.path.join(hls_dir, name), encoding="utf-8") as f:
                for m in HLS_TOP.finditer(f.read()):
                    pointers = [re.findall(r"(\w+)\s*$", a)[0] for a in m[2].split(",") if "*" in a]
                    tops[m[1]] = (os.path.join(hls_dir, name), pointers)
    return tops


def check_hls_compile(line, kernel_of, device, top_file, includes, build):
    """A `v++ -c --mode hls` line: nothing but its config and work directory; the config names the platform, the
    Vitis flow target, the entry's top and file, the include paths (no -D) and the .xo, and nothing else. Returns the
    entry and its .xo."""
    expect(line[:4] == ["-c", "--mode", "hls", "--config"] and line[5] == "--work_dir" and len(line) == 7,
           f"v++ --mode hls line {line}")
    config = read_hls_config(line[4])
    kernel = config.get(("hls", "syn.top"), [None])[0]
    expect(kernel in kernel_of, f"{line[4]}: syn.top {kernel} is no single work-item entry")
    xo = os.path.join(build, "xo.hls", f"{kernel}.xo")
    wanted = {("", "platform"): [device], ("hls", "flow_target"): ["vitis"], ("hls", "syn.file"): [top_file[kernel]],
              ("hls", "syn.top"): [kernel], ("hls", "syn.cflags"): [" ".join(f"-I{d}" for d in includes)],
              ("hls", "package.output.format"): ["xo"], ("hls", "package.output.file"): [xo]}
    expect(config == wanted, f"{line[4]}: {config}, expected {wanted}")
    expect(line[6] == os.path.join(build, "_x.hls", kernel), f"{kernel}: work directory {line[6]}")
    return kernel, xo


def check_standin_refuses_bad_hls_forms(build, env):
    """The stand-in v++ refuses what a --mode hls compile must not be: an unknown or missing key of the configuration,
    options besides it, a Vitis without --mode hls, and its .xo linked for software emulation."""
    config_dir = os.path.join(build, "hls_config")
    config = os.path.join(config_dir, sorted(os.listdir(config_dir))[0])
    with open(config, encoding="utf-8") as f:
        text = f.read()
    broken = os.path.join(build, "broken.cfg")
    xo = read_hls_config(config)[("hls", "package.output.file")][0]
    platform = read_hls_config(config)[("", "platform")][0]
    cases = {"unknown key": (text + "syn.unknown=1\n", []), "no syn.top": (re.sub(r"syn.top=.*\n", "", text), []),
             "flow_target vivado": (text.replace("flow_target=vitis", "flow_target=vivado"), []),
             "a -k besides the config": (text, ["-k", "axpy_single"])}
    vxx = os.path.join(BIN, "v++")
    for case, (content, extra) in cases.items():
        with open(broken, "w", encoding="utf-8") as f:
            f.write(content)
        result = run([vxx, "-c", "--mode", "hls", "--config", broken] + extra, env, must_pass=False)
        expect(result.returncode == 2, f"stand-in v++ --mode hls accepted a config with {case}")
    old = run([vxx, "-c", "--mode", "hls", "--config", config], dict(env, RFRECON_STANDIN_VERSION="2022.2"),
              must_pass=False)
    expect(old.returncode == 2, "stand-in v++ 2022.2 accepted --mode hls")
    link = run([vxx, "-l", "-t", "sw_emu", "--platform", platform, "--config", broken, "-o",
                os.path.join(build, "broken.xclbin"), xo], env, must_pass=False)
    expect(link.returncode == 2 and "one for hw_emu, hw" in link.stderr,
           f"stand-in v++ linked a --mode hls .xo for sw_emu, or refused it for another reason: {link.stderr}")
    os.remove(broken)
    logged(env["RFRECON_STANDIN_LOG"])


def check_xilinx(args, build, env, files, source_hash, mode="opencl"):
    """The OpenCL C flow (Vitis up to 2022.2, `mode` opencl), or the flow of the HLS C++ tops (2023.1 and later): with
    `mode` kernel every target compiles each top with `v++ -c -t TARGET -k`, with hls sw_emu does and hw_emu and hw
    share one `v++ -c --mode hls` .xo per top."""
    device, kernel_dir = XILINX[args.board], os.path.join(args.root, "kernels")
    generated_dir = os.path.join(build, "generated", "kernels")
    config = os.path.join(args.root, "hw", "boards", f"{args.board}.cfg")
    single = {k: buffers for names in files.values() for k, buffers in names.items() if k.endswith("_single")}
    file_of = {k: os.path.join(kernel_dir, f) for f, names in files.items() for k in names}
    includes, macro = [kernel_dir, generated_dir], "RF_TARGET_XILINX_FPGA"
    if mode != "opencl":
        tops = hls_tops(os.path.join(args.root, "hw", "hls"))
        expect(set(single) <= set(tops), f"single entries without an HLS top: {sorted(set(single) - set(tops))}")
        for kernel, buffers in single.items():  # the link config's ports are the OpenCL entries' buffer names
            expect(tops[kernel][1] == buffers, f"{kernel}: HLS top buffers {tops[kernel][1]}, OpenCL {buffers}")
        file_of = {k: path for k, (path, _) in tops.items()}
        includes, macro = includes + [os.path.join(args.root, "hw")], "RF_TARGET_HLS"
    check_link_config(config, single)
    hls_xos = {}  # the --mode hls .xo of each entry, built with the first hardware target
    for target, binary in (("sw_emu", f"rfrecon_{args.board}_sw_emu.xclbin"),
                           ("hw_emu", f"rfrecon_{args.board}_hw_emu.xclbin"), ("hw", f"rfrecon_{args.board}.xclbin")):
        run([args.cmake, "--build", build, "--target", f"rfrecon_fpga_{target}"], env)
        calls = logged(env["RFRECON_STANDIN_LOG"])
        compiles = [c[1:] for c in calls if c[:2] == ["v++", "-c"] and "--mode" not in c]
        hls_compiles = [c[1:] for c in calls if c[:2] == ["v++", "-c"] and "--mode" in c]
        links = [c[1:] for c in calls if c[:2] == ["v++", "-l"]]
        expect(len(links) == 1, f"{target}: expected one v++ -l, got {links}")
        compiled = {}
        for line in compiles + links:
            for flag in ("-t", target), ("--platform", device):
                expect(line[line.index(flag[0]) + 1] == flag[1], f"{target}: {flag} missing from v++ {' '.join(line)}")
        for line in compiles:
            defines = [a for a in line if a.startswith("-D")]
            expect(defines == ([] if mode != "opencl" else ["-DRF_TARGET_XILINX_FPGA"]),
                   f"{target}: -D options {defines} in {line}")
            expect(includes_of(line) == includes, f"{target}: include paths {includes_of(line)}")
            kernel = line[line.index("-k") + 1]
            expect(line[-1] == file_of.get(kernel), f"{target}: {kernel} compiled from {line[-1]}")
            compiled[kernel] = line[line.index("-o") + 1]
        for line in hls_compiles:
            kernel, xo = check_hls_compile(line, single, device, file_of, includes, build)
            hls_xos[kernel] = xo
        if mode == "hls" and target != "sw_emu":
            expect(not compiles, f"{target}: v++ -c -k with RFRECON_VITIS_HLS_MODE hls: {compiles}")
            expect(len(hls_compiles) == (len(single) if target == "hw_emu" else 0),
                   f"{target}: {len(hls_compiles)} v++ --mode hls compiles (hw_emu makes them, hw reuses them)")
            compiled = dict(hls_xos)
        else:
            expect(not hls_compiles, f"{target}: v++ --mode hls in mode {mode}: {hls_compiles}")
        expect(set(compiled) == set(single), f"{target}: compiled {sorted(compiled)}, expected {sorted(single)}")
        link = links[0]
        expect(link[link.index("--config") + 1] == config, f"{target}: link config is not {config}")
        expect(sorted(a for a in link if a.endswith(".xo")) == sorted(compiled.values()), f"{target}: link inputs")
        # emconfig.json is made once, by the first emulation target built, and never for hardware.
        emconfig = [c for c in calls if c[0] == "emconfigutil"]
        expect(len(emconfig) == (1 if target == "sw_emu" else 0), f"{target}: emconfigutil {emconfig}")
        check_manifest(os.path.join(build, binary), target, "v++", macro, device, args.board, list(single),
                       source_hash, args.parameters)
    run([args.cmake, "--build", build, "--target", "rfrecon_fpga_report"], env)
    expect(logged(env["RFRECON_STANDIN_LOG"]) == [], "report: the hw .xo files are those of rfrecon_fpga_hw")
    check_emulation_env(build, {"RFRECON_KERNEL_BINARY": os.path.join(build, f"rfrecon_{args.board}_sw_emu.xclbin"),
                                "XCL_EMULATION_MODE": "sw_emu", "EMCONFIG_PATH": build})
    if mode == "hls":
        check_standin_refuses_bad_hls_forms(build, env)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--board", required=True, choices=sorted(INTEL) + sorted(XILINX))
    parser.add_argument("--root", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--cmake", default="cmake")
    args = parser.parse_args()
    args.root = os.path.abspath(args.root)
    args.parameters = preset_parameters(args.root, args.board)
    build = os.path.abspath(args.scratch)
    shutil.rmtree(build, ignore_errors=True)
    os.makedirs(build)
    env = dict(os.environ, RFRECON_STANDIN_LOG=os.path.join(build, "standin.log"))
    env.pop("RFRECON_STANDIN_VERSION", None)
    tools = ([f"-DRFRECON_AOC={BIN}/aoc"] if args.board in INTEL else
             [f"-DRFRECON_VXX={BIN}/v++", f"-DRFRECON_EMCONFIGUTIL={BIN}/emconfigutil"])
    configure = [args.cmake, "-S", os.path.join(args.root, "hw"), f"-DRFRECON_FPGA_BOARD={args.board}"] + tools
    try:
        configured = run(configure + ["-B", os.path.join(build, "flow")], env)
        expect("RFRECON_DOT_SPACINGS" not in configured.stderr,
               f"a warning about the preset's {len(args.parameters['RF_DOT_SPACINGS'])} dot spacings:\n"
               f"{configured.stderr}")
        # Values given on the command line win over the preset's; more than 4 spacings are warned about.
        many = run(configure + ["-B", os.path.join(build, "many_spacings"), "-DRFRECON_DOT_SPACINGS=2;3;4;5;6",
                                "-DRFRECON_MAX_ROW_WIDTH=1000"], env)
        expect("RFRECON_DOT_SPACINGS holds 5 spacings" in " ".join(many.stderr.split()),
               "no warning about 5 dot spacings' dividers")
        check_params_header(os.path.join(build, "many_spacings", "generated", "kernels"),
                            dict(args.parameters, RF_DOT_SPACINGS=[2, 3, 4, 5, 6], RF_MAX_ROW_WIDTH=1000))
        check_host_follows_preset(args, build, env)
        generated_dir = os.path.join(build, "flow", "generated", "kernels")
        check_params_header(generated_dir, args.parameters)
        files, digests = kernels_of(os.path.join(args.root, "kernels"), generated_dir)
        run([args.cmake, "--build", os.path.join(build, "flow")], env)
        expect(logged(env["RFRECON_STANDIN_LOG"]) == [], "`all` ran a vendor tool: synthesis must never be in all")
        (check_intel if args.board in INTEL else check_xilinx)(args, os.path.join(build, "flow"), env, files,
                                                              listing_hash(digests))
        if args.board in XILINX:  # Vitis 2023.1 and later: the HLS C++ tops, by v++ -c -k or v++ --mode hls
            for version, options, mode in (("2023.1", [], "kernel"), ("2025.1", [], "hls"),
                                           ("2025.1", ["-DRFRECON_VITIS_HLS_MODE=kernel"], "kernel")):
                hls_env = dict(env, RFRECON_STANDIN_VERSION=version)
                hls_build = os.path.join(build, f"hls_{version}_{mode}")
                run(configure + options + ["-B", hls_build], hls_env)
                run([args.cmake, "--build", hls_build], hls_env)
                expect(logged(env["RFRECON_STANDIN_LOG"]) == [],
                       "`all` ran a vendor tool: synthesis must never be in all")
                check_xilinx(args, hls_build, hls_env, files, listing_hash(digests + hls_digests(args.root)), mode)
            for options, problem in ((["-DRFRECON_VITIS_HLS_MODE=hls"], "need Vitis 2023.1"),
                                     (["-DRFRECON_VITIS_HLS_MODE=synth"], "expected auto, kernel or hls")):
                refused = run(configure + options + ["-B", os.path.join(build, "mode_refused")], env, must_pass=False)
                expect(refused.returncode != 0 and problem in " ".join(refused.stderr.split()),
                       f"{options} with v++ 2022.2 accepted or refused for another reason:\n{refused.stderr}")
                shutil.rmtree(os.path.join(build, "mode_refused"))
        unsupported = dict(env, RFRECON_STANDIN_VERSION="23.1.0" if args.board in INTEL else "2019.1")
        refused = run(configure + ["-B", os.path.join(build, "unsupported")], unsupported, must_pass=False)
        expect(refused.returncode != 0 and "supports" in refused.stderr,
               f"tool {unsupported['RFRECON_STANDIN_VERSION']} accepted:\n{refused.stderr}")
    except Failure as failure:
        print(f"fpga_flow_{args.board}: FAILED: {failure}")
        return 1
    shutil.rmtree(build)
    print(f"fpga_flow_{args.board}: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
