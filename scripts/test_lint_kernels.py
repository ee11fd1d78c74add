#!/usr/bin/env python3
"""Self-test of scripts/lint_kernels.py: fake kernel trees with known problems, so the lint provably fails.

Run: python3 scripts/test_lint_kernels.py  (ctest: fpga_kernel_lint_selftest, label fpga)
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "lint_kernels.py")
TARGET_H = os.path.join(HERE, "..", "kernels", "common", "target.h")

# Both entries of one algorithm, written the way kernels/*.cl are; a clean file the lint must accept.
CLEAN = """#include "common/target.h"
__kernel void scale_ndrange(__global float* restrict x, uint n) {
  const uint i = get_global_id(0);
  if (i < n) x[i] *= 2.0f;
}

RF_SINGLE_TASK
__kernel void scale_single(__global float* restrict x, uint n) {
  RF_PIPELINE_II(1)
  for (uint i = 0; i < n; ++i) x[i] *= 2.0f;
}
"""


class LintKernelsTest(unittest.TestCase):
    def lint(self, files):
        root = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, root)
        os.makedirs(os.path.join(root, "common"))
        shutil.copy(TARGET_H, os.path.join(root, "common", "target.h"))
        for name, text in files.items():
            with open(os.path.join(root, name), "w", encoding="utf-8") as f:
                f.write(text)
        return subprocess.run([sys.executable, SCRIPT, "--kernels", root], capture_output=True, text=True, check=False)

    def test_clean_kernels_pass(self):
        run = self.lint({"scale.cl": CLEAN})
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)

    def test_single_entry_without_attribute_fails(self):
        run = self.lint({"scale.cl": CLEAN.replace("RF_SINGLE_TASK\n", "")})
        self.assertEqual(run.returncode, 1)
        self.assertIn("scale.cl:7: single work-item entry scale_single lacks RF_SINGLE_TASK", run.stdout)

    def test_ndrange_entry_with_attribute_fails(self):
        marked = CLEAN.replace("__kernel void scale_ndrange", "RF_SINGLE_TASK __kernel void scale_ndrange")
        run = self.lint({"scale.cl": marked})
        self.assertEqual(run.returncode, 1)
        self.assertIn("scale_ndrange carries RF_SINGLE_TASK", run.stdout)

    def test_ordinary_warning_fails(self):
        run = self.lint({"scale.cl": CLEAN.replace("  const uint i", "  int unused;\n  const uint i")})
        self.assertEqual(run.returncode, 1)
        self.assertIn("no target macro: warning: unused variable 'unused' [-Wunused-variable]", run.stdout)

    def test_pragma_outside_allowlist_fails(self):
        run = self.lint({"scale.cl": CLEAN.replace("  RF_PIPELINE_II(1)\n", "  #pragma loop_coalesce\n")})
        self.assertEqual(run.returncode, 1)
        self.assertIn("unknown pragma ignored [-Wunknown-pragmas]", run.stdout)

    def test_vendor_attribute_of_the_other_target_fails(self):
        intel_only = CLEAN.replace("RF_SINGLE_TASK\n", "RF_SINGLE_TASK __attribute__((max_global_work_dim(0)))\n")
        run = self.lint({"scale.cl": intel_only})
        self.assertEqual(run.returncode, 1)
        self.assertIn("RF_TARGET_XILINX_FPGA: warning: unknown attribute 'max_global_work_dim' ignored", run.stdout)
        self.assertNotIn("RF_TARGET_INTEL_FPGA: warning", run.stdout)

    def test_helper_defined_in_two_files_fails_as_one_program(self):
        helper = "inline float twice(float x) { return 2.0f * x; }\n"
        run = self.lint({"a.cl": helper + CLEAN, "b.cl": helper + CLEAN.replace("scale", "shift")})
        self.assertEqual(run.returncode, 1)
        self.assertIn("all files in one program: error: redefinition of 'twice'", run.stdout)


if __name__ == "__main__":
    unittest.main()
