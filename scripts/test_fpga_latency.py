#!/usr/bin/env python3
"""Self-test of scripts/fpga_latency.py: chains of small IR functions with known latencies, and the real kernels made
to fail (an interleave shorter than the chain, a design II the model does not reach, a loop without one, a drifted
table), so that the model can fail.

Run: python3 scripts/test_fpga_latency.py  (ctest: fpga_latency_selftest, label fpga)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import fpga_latency  # noqa: E402

SCRIPT = os.path.join(HERE, "fpga_latency.py")
DOCS = os.path.join(ROOT, "docs", "fpga.md")

# A loop of n iterations with three dependences: state[i % 4] = state[i % 4] / x + 1 (on-chip RAM: read, divide, add,
# write), sum += a[i] * x (a register: one add) and a[i] = a[i] * x (global, each iteration its own element: none).
RAM_AND_REGISTER = """
define dso_local spir_kernel void @toy_single(float addrspace(1)* noalias %a, """ + \
    """float addrspace(1)* noalias %out, i32 %n, float %x) {
entry:
  %state = alloca [4 x float], align 4
  br label %loop

loop:                                             ; preds = %loop, %entry
  %i = phi i32 [ 0, %entry ], [ %i.next, %loop ]
  %sum = phi float [ 0.000000e+00, %entry ], [ %sum.next, %loop ]
  %k = urem i32 %i, 4
  %k64 = zext i32 %k to i64
  %slot = getelementptr inbounds [4 x float], [4 x float]* %state, i64 0, i64 %k64
  %old = load float, float* %slot, align 4
  %q = fdiv float %old, %x
  %new = fadd float %q, 1.000000e+00
  store float %new, float* %slot, align 4
  %i64 = zext i32 %i to i64
  %pa = getelementptr inbounds float, float addrspace(1)* %a, i64 %i64
  %v = load float, float addrspace(1)* %pa, align 4
  %w = fmul float %v, %x
  store float %w, float addrspace(1)* %pa, align 4
  %sum.next = fadd float %sum, %w
  %i.next = add nuw nsw i32 %i, 1
  %done = icmp eq i32 %i.next, %n
  br i1 %done, label %exit, label %loop, !llvm.loop !1

exit:                                             ; preds = %loop
  store float %sum.next, float addrspace(1)* %out, align 4
  ret void
}
"""

# The dual SpMV's pattern: the next iteration's branch compares with a value a guarded global read gives.
GUARDED_GLOBAL_READ = """
define dso_local spir_kernel void @fetch_single(i32 addrspace(1)* noalias %starts, i32 %n) {
entry:
  br label %loop

loop:                                             ; preds = %latch, %entry
  %i = phi i32 [ 0, %entry ], [ %i.next, %latch ]
  %end = phi i32 [ 0, %entry ], [ %end.next, %latch ]
  %more = icmp slt i32 %i, %end
  br i1 %more, label %latch, label %fetch

fetch:                                            ; preds = %loop
  %i64 = sext i32 %i to i64
  %p = getelementptr inbounds i32, i32 addrspace(1)* %starts, i64 %i64
  %e = load i32, i32 addrspace(1)* %p, align 4
  br label %latch

latch:                                            ; preds = %fetch, %loop
  %end.next = phi i32 [ %end, %loop ], [ %e, %fetch ]
  %i.next = add nsw i32 %i, 1
  %done = icmp eq i32 %i.next, %n
  br i1 %done, label %exit, label %loop

exit:                                             ; preds = %latch
  ret void
}
"""


def model_of(ir, target, safelen=None, dependences=None, registers=()):
    """The LoopModel of the one loop of the one kernel of `ir`, with R = 8 as the parameter "R"."""
    function = next(iter(fpga_latency.functions_of_ir(ir).values()))
    loops = fpga_latency.natural_loops(function)
    assert len(loops) == 1, loops
    source = fpga_latency.SourceLoop("toy.h", 1, safelen, dependences or {})
    return fpga_latency.LoopModel(loops[0], source, fpga_latency.TARGETS[target], {"R": "8", "BIG": "32"},
                                  set(registers))


def chain(model, carrier):
    return next(c for c in model.chains if c.carrier == carrier)


class ChainTest(unittest.TestCase):
    def test_ram_chain_is_read_divide_add_write(self):
        amd = model_of(RAM_AND_REGISTER, "amd", dependences={"state": "R"})
        self.assertEqual(chain(amd, "state").latency, 2 + 15 + 4 + 1)
        self.assertEqual(chain(amd, "state").distance, 8)
        self.assertEqual(chain(amd, "state").ii, 3)  # ceil(22 / 8)
        intel = model_of(RAM_AND_REGISTER, "intel", safelen="R")
        self.assertEqual(chain(intel, "state").latency, 3 + 24 + 4 + 1)
        self.assertEqual(chain(intel, "state").ii, 4)  # ceil(32 / 8)

    def test_interleave_covering_the_chain_gives_ii_1(self):
        amd = model_of(RAM_AND_REGISTER, "amd", dependences={"state": "BIG"})
        self.assertEqual(chain(amd, "state").ii, 1)

    def test_without_a_distance_the_chain_is_the_ii(self):
        amd = model_of(RAM_AND_REGISTER, "amd")  # no RF_HLS_DEPENDENCE: distance 1
        self.assertEqual(chain(amd, "state").ii, 22)
        intel = model_of(RAM_AND_REGISTER, "intel", safelen="R", registers=("state",))  # ivdep cannot waive registers
        self.assertEqual(chain(intel, "state").distance, 1)
        self.assertEqual(chain(intel, "state").latency, 24 + 4)

    def test_register_chain_and_own_elements(self):
        amd = model_of(RAM_AND_REGISTER, "amd", dependences={"state": "BIG"})
        self.assertEqual(chain(amd, "sum").latency, 4)
        self.assertEqual(amd.ii, 4)  # the accumulation, not the interleaved state
        self.assertEqual(chain(amd, "i").latency, 0)
        self.assertFalse([c for c in amd.chains if c.carrier == "a"])  # a[i] = a[i] * x: no dependence

    def test_guarded_global_read_is_on_the_chain(self):
        amd = model_of(GUARDED_GLOBAL_READ, "amd")
        self.assertEqual(chain(amd, "end").latency, 64)
        self.assertEqual(amd.ii, 64)
        intel = model_of(GUARDED_GLOBAL_READ, "intel")
        self.assertEqual(intel.ii, 150)


class ClaimsTest(unittest.TestCase):
    def test_lists_and_vendors(self):
        directory = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, directory)
        path = os.path.join(directory, "claims.md")
        with open(path, "w", encoding="utf-8") as f:
            f.write("## Pipelines of the single work-item entries\n\n| kernel | loop | design II | why |\n"
                    "| --- | --- | --- | --- |\n| `a_single`, `b_single` | x, y | 1 | . |\n"
                    "| `c_single` | z | Intel 2, AMD 1 | . |\n| `d_single` | w | Intel 2 (`pac_a10` 3), AMD 1 | . |\n"
                    "\n## Next\n")
        claims = fpga_latency.claims_of(path)
        self.assertEqual(len(claims), 6)
        self.assertIn(("b_single", "y", {"all": 1}), claims)
        self.assertIn(("c_single", "z", {"intel": 2, "amd": 1}), claims)
        self.assertIn(("d_single", "w", {"intel": 2, "pac_a10": 3, "amd": 1}), claims)


class KernelsTest(unittest.TestCase):
    def latency(self, *arguments, boards=("520n", "u250")):
        """fpga_latency.py run on the real kernels with the presets given (all: none given)."""
        presets = [a for b in boards for a in ("--board", b)]
        return subprocess.run([sys.executable, SCRIPT, "--root", ROOT] + presets + list(arguments),
                              capture_output=True, text=True, check=False)

    def docs_copy(self, edit):
        """A copy of docs/fpga.md changed by edit(text) -> text."""
        directory = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, directory)
        with open(DOCS, encoding="utf-8") as f:
            text = f.read()
        changed = edit(text)
        self.assertNotEqual(changed, text)
        path = os.path.join(directory, "fpga.md")
        with open(path, "w", encoding="utf-8") as f:
            f.write(changed)
        return path

    def test_real_kernels_meet_the_documented_design(self):
        run = self.latency()
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("integrate_rows_single slope", run.stdout)

    def test_interleave_shorter_than_the_chain_fails(self):
        run = self.latency("--set", "INTEGRATE_INTERLEAVE=8", "--set", "FUSE_INTERLEAVE=4")
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertRegex(run.stdout, r"problem: amd integrate_rows_single slope: the model's II \d+ exceeds the "
                                     r"design II \d of .*distance of 8, `states` \(on-chip RAM\)")
        self.assertIn("problem: intel fuse_rows_single backward", run.stdout)

    def test_design_ii_the_model_does_not_reach_fails(self):
        claims = self.docs_copy(lambda text: re.sub(r"(\| `dual_single` \| entry \| )[^|]*\|", r"\g<1>1 |", text))
        run = self.latency("--claims", claims)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("dual_single entry: the model's II 4 exceeds the design II 1", run.stdout)
        self.assertIn("`sum` (register): add/mul", run.stdout)

    def test_preset_beyond_its_vendors_design_ii_fails(self):
        # pac_a10's interleaves are shorter than the Stratix 10 presets': without its own design II, its vendor's fails.
        claims = self.docs_copy(lambda text: text.replace(" (`pac_a10` 3)", ""))
        run = self.latency("--claims", claims, boards=("pac_a10",))
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("problem: intel integrate_rows_single slope: the model's II 3 exceeds the design II 2",
                      run.stdout)
        self.assertEqual(self.latency(boards=("pac_a10",)).returncode, 0)

    def test_loop_without_design_ii_fails(self):
        claims = self.docs_copy(lambda text: re.sub(r"\n\| `axpy_single` \| element \|[^\n]*", "", text))
        run = self.latency("--claims", claims)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("states no design II for axpy_single element", run.stdout)

    def test_drifted_table_fails(self):
        docs = self.docs_copy(lambda text: text.replace("| 3 passes x 4 slopes |", "| 3 passes x 4 slope |", 1))
        run = self.latency("--docs", docs, boards=())
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("the latency tables differ from the generated ones", run.stdout)


if __name__ == "__main__":
    unittest.main()
