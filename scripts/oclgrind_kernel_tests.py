#!/usr/bin/env python3
"""Runs every ctest test labelled `kernel` under oclgrind and fails on any oclgrind report.

Tests are grouped per executable (one oclgrind run per binary, gtest filters joined). Suites named *ApiErrorTest
provoke OpenCL errors on purpose and are skipped. Usage: oclgrind_kernel_tests.py BUILD_DIR
"""
import json
import os
import re
import subprocess
import sys
import tempfile

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
    with tempfile.NamedTemporaryFile("r", suffix=".log") as log:
        cmd = ["oclgrind", "--check-api", "--data-races", "--uninitialized", "--log", log.name,
               binary, "--gtest_filter=" + gtest_filter, "--gtest_brief=1"]
        print("+", " ".join(cmd), flush=True)
        run = subprocess.run(cmd, capture_output=True, text=True, cwd=build_dir,
                             env=dict(os.environ, RFRECON_DEVICES="all"))
        report = log.read()
    api_errors = [line for line in run.stderr.splitlines() if line.startswith("Oclgrind - ")]
    sys.stdout.write(run.stdout[-3000:])
    if run.returncode != 0 or report.strip() or api_errors:
        failed = True
        print(f"FAILED under oclgrind: {binary} (exit {run.returncode})")
        print(report[-5000:])
        print(run.stderr[-5000:])
print("oclgrind: " + ("errors found" if failed else f"clean ({len(by_binary)} test binaries)"))
sys.exit(1 if failed else 0)
