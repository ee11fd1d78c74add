#!/usr/bin/env python3
"""Runs every ctest test labelled `kernel` under oclgrind and fails on any oclgrind report.

Tests are grouped per executable (one oclgrind run per binary, gtest filters joined). Suites named *ApiErrorTest
provoke OpenCL errors on purpose and are skipped. Usage: oclgrind_kernel_tests.py BUILD_DIR

Reports are read from oclgrind's stderr, not from a --log file: oclgrind 21.10 starts that file again for every
OpenCL context, so it held only a binary's last test's reports (a test reported alone came out clean in a group).
Checks: out-of-bounds accesses (always on), the OpenCL API (--check-api) and data races (--data-races). Not
--uninitialized: oclgrind 21.10 takes the contents of CL_MEM_USE_HOST_PTR buffers for uninitialized, so every kernel
that reads a frame or a state array the host lends (cl::borrow, cl::share) is reported, while the same data in
CL_MEM_COPY_HOST_PTR buffers comes out clean (docs/building.md, CI step 3).
"""
import json
import os
import subprocess
import sys

build_dir = sys.argv[1]
listing = json.loads(subprocess.run(["ctest", "--test-dir", build_dir, "-L", "kernel", "--show-only=json-v1"],
                                    check=True, capture_output=True, text=True).stdout)
by_binary = {}
for test in listing["tests"]:
    command = test.get("command") or []
    if not command:
        continue
    binary = command[0]
    filters = [arg.split("=", 1)[1] for arg in command[1:] if arg.startswith("--gtest_filter=")]
    by_binary.setdefault(binary, set()).update(filters or ["*"])

failed = False
for binary, filters in sorted(by_binary.items()):
    gtest_filter = ":".join(sorted(filters)) + ":-*ApiErrorTest.*"
    cmd = ["oclgrind", "--check-api", "--data-races", binary, "--gtest_filter=" + gtest_filter, "--gtest_brief=1"]
    print("+", " ".join(cmd), flush=True)
    run = subprocess.run(cmd, capture_output=True, text=True, cwd=build_dir, env=dict(os.environ, RFRECON_DEVICES="all"))
    # A kernel report names its kernel and work-item on tab-indented lines; API errors start with "Oclgrind - ".
    report = [line for line in run.stderr.splitlines()
              if line.startswith(("\tKernel: ", "\tEntity: ", "Oclgrind - ")) or "errors generated" in line]
    sys.stdout.write(run.stdout[-3000:])
    if run.returncode != 0 or report:
        failed = True
        print(f"FAILED under oclgrind: {binary} (exit {run.returncode}, {len(report)} report lines)")
        print(run.stderr[-5000:])
print("oclgrind: " + ("errors found" if failed else f"clean ({len(by_binary)} test binaries)"))
sys.exit(1 if failed else 0)
