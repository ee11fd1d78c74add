#!/usr/bin/env python3
"""Self-test of scripts/fpga_budget.py: block arithmetic, and presets and trees made to fail, so the budget can fail.

Run: python3 scripts/test_fpga_budget.py  (ctest: fpga_budget_selftest, label fpga)
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import fpga_budget  # noqa: E402
import fpga_devices  # noqa: E402

SCRIPT = os.path.join(HERE, "fpga_budget.py")


class BlockArithmeticTest(unittest.TestCase):
    def test_blocks_of_one_row_array(self):
        # 160 rows x 4096 floats: 512 words per M20K, 1,024 per BRAM36, 4,096 per URAM (one float per 72-bit word).
        self.assertEqual(fpga_devices.blocks(655360, 32, "M20K", True), 1280)
        self.assertEqual(fpga_devices.blocks(655360, 32, "BRAM36", True), 640)
        self.assertEqual(fpga_devices.blocks(655360, 32, "URAM", True), 160)
        self.assertEqual(fpga_devices.blocks(655360, 8, "BRAM36", True), 160)  # 4K x 9

    def test_wide_words_need_the_simple_dual_port_shapes(self):
        self.assertEqual(fpga_devices.blocks(160, 160, "M20K", False), 4)  # 512 x 40
        self.assertEqual(fpga_devices.blocks(160, 160, "M20K", True), 8)  # 1K x 20
        self.assertEqual(fpga_devices.blocks(160, 96, "BRAM36", False), 2)  # 512 x 72

    def test_copies_from_ports(self):
        self.assertEqual(fpga_budget.copies_for(2, 0), (1, True, False))
        self.assertEqual(fpga_budget.copies_for(1, 1), (1, False, False))
        self.assertEqual(fpga_budget.copies_for(16, 0), (8, True, False))
        self.assertEqual(fpga_budget.copies_for(3, 0), (2, True, False))
        self.assertEqual(fpga_budget.copies_for(1, 2), (1, True, True))  # only double-pumped
        self.assertEqual(fpga_budget.copies_for(0, 2), (1, True, False))  # a write on each port
        self.assertEqual(fpga_budget.copies_for(4, 1), (4, False, False))  # every copy takes the write

    def test_shell_share(self):
        self.assertEqual(fpga_devices.STRATIX10_2800.available("M20K"), 9962)
        self.assertEqual(fpga_devices.ALVEO_U250.available("BRAM36", 1), 302)  # the static region's SLR
        self.assertEqual(fpga_devices.ALVEO_U250.available("BRAM36", 3), 604)


class MeasuredPortsTest(unittest.TestCase):
    """--measured: PORTS against a C simulation table, the real kernels' loop lines."""

    def table(self, rows):
        lines = ["| loop | II claimed | memory | reads | writes | II allowed | shortest RAW distance | claimed |",
                 "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        path = os.path.join(tempfile.mkdtemp(), "access.md")
        self.addCleanup(shutil.rmtree, os.path.dirname(path))
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines + rows) + "\n")
        return path

    def loop_line(self, function, index):
        """The line of the index-th RF_HLS_PIPELINE of a function of kernels/depth/row_interleave.h."""
        with open(os.path.join(ROOT, "kernels", "depth", "row_interleave.h"), encoding="utf-8") as f:
            lines = f.read().splitlines()
        start = next(i for i, line in enumerate(lines) if line.startswith(f"RF_INLINE void {function}("))
        return [i + 1 for i, line in enumerate(lines) if i > start and line.strip() == "RF_HLS_PIPELINE"][index]

    def rows(self, z_rows_reads):
        """Every array PORTS names, as PORTS says, but the integration's z_rows read `z_rows_reads` times."""
        rows = []
        for (function, index), (kernel, loop) in fpga_budget.LOOPS.items():
            line = self.loop_line(function, index)
            for name, phases in fpga_budget.PORTS[kernel].items():
                counts = [(r, w) for l, r, w in phases if l == loop]
                if not counts:
                    continue
                reads, writes = max(c[0] for c in counts), max(c[1] for c in counts)
                if kernel == "integrate_rows_single" and name == "z_rows":
                    reads = z_rows_reads
                rows.append(f"| `kernels/depth/row_interleave.h:{line}` | 1 | {name} | {reads} | {writes} | 1 | - | - |")
        return rows

    def test_ports_as_counted_pass(self):
        self.assertEqual(fpga_budget.measured_mismatches(ROOT, self.table(self.rows(1))), [])

    def test_a_read_more_than_ports_says_fails(self):
        mismatches = fpga_budget.measured_mismatches(ROOT, self.table(self.rows(2)))
        self.assertEqual(len(mismatches), 1)
        self.assertIn("integrate_rows_single z_rows in the slope loop", mismatches[0])

    def test_an_array_ports_misses_fails(self):
        line = self.loop_line("rf_fuse_rows_interleaved", 0)
        rows = self.rows(1) + [f"| `kernels/depth/row_interleave.h:{line}` | 1 | scratch[1] | 1 | 1 | 1 | - | - |"]
        self.assertIn("fuse_rows_single scratch in the forward loop", fpga_budget.measured_mismatches(ROOT, self.table(rows))[0])


class BudgetTest(unittest.TestCase):
    def boards(self, presets):
        """A board directory of copies of hw/boards/ presets with lines added: {new name: (preset, added text)}, and
        the link configurations."""
        directory = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, directory)
        for name in os.listdir(os.path.join(ROOT, "hw", "boards")):
            if name.endswith(".cfg"):
                shutil.copy(os.path.join(ROOT, "hw", "boards", name), directory)
        for name, (preset, added) in presets.items():
            with open(os.path.join(ROOT, "hw", "boards", preset + ".cmake"), encoding="utf-8") as f:
                text = f.read()
            with open(os.path.join(directory, name + ".cmake"), "w", encoding="utf-8") as f:
                f.write(text + added)
        return directory

    def budget(self, *arguments, root=ROOT):
        return subprocess.run([sys.executable, SCRIPT, "--root", root] + list(arguments), capture_output=True,
                              text=True, check=False)

    def test_real_stratix_preset_fits(self):
        run = self.budget("--board", "520n")
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("520n: Stratix 10 GX/SX 2800: M20K", run.stdout)

    def test_oversized_preset_fails_naming_kernel_array_and_blocks(self):
        boards = self.boards({"big": ("520n", "set(RFRECON_MAX_ROW_WIDTH 8192)\n")})
        run = self.budget("--boards", boards)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("big (Stratix 10 GX/SX 2800) does not fit: M20K blocks of the device:", run.stdout)
        self.assertIn("available (11,721 less 15% for the BSP)", run.stdout)
        self.assertIn("integrate_rows_single e_cam_rows: 2,560 M20K (1 x 1,310,720 x 32 bit)", run.stdout)
        self.assertIn("fuse_rows_single e_proj_rows: 4,096 M20K (1 x 2,097,152 x 32 bit)", run.stdout)

    def test_oversized_amd_preset_fails_per_slr(self):
        # The u250 preset with rows of 4096 pixels: the device has the blocks, the integration's SLR (slr=) not.
        boards = self.boards({"big": ("u250", "set(RFRECON_MAX_ROW_WIDTH 4096)\n")})
        run = self.budget("--boards", boards)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertNotIn("blocks of the device", run.stdout)
        self.assertIn("URAM blocks of SLR3: 480 needed, 288 available (320 less 10% for infrastructure)", run.stdout)
        self.assertIn("integrate_rows_single (placed by slr= of the link configuration): 480 URAM", run.stdout)
        self.assertIn("BRAM36 blocks of SLR3:", run.stdout)

    def test_amd_kernels_without_slr_lie_in_their_banks_slr(self):
        # Without the link configuration's slr= lines both depth kernels lie in SLR3, beside DDR[3]: too many for it.
        boards = self.boards({"packed": ("u250", "")})
        config = os.path.join(boards, "u250.cfg")
        with open(config, encoding="utf-8") as f:
            lines = [line for line in f if not line.startswith("slr=")]
        with open(config, "w", encoding="utf-8") as f:
            f.writelines(lines)
        run = self.budget("--boards", boards, "--board", "packed")
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("URAM blocks of SLR3: 400 needed", run.stdout)
        self.assertIn("fuse_rows_single (placed by its memory bank DDR[3]): 160 URAM", run.stdout)

    def test_amd_binds_the_marked_arrays_to_uram(self):
        # RF_IN_URAM in a kernel's function binds that kernel's array: the integration's e_cam_rows, not the fusion's.
        run = self.budget("--board", "u250", "--set", "MAX_ROW_WIDTH=16384")
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("integrate_rows_single e_cam_rows: 640 URAM (1 x 2,621,440 x 32 bit)", run.stdout)
        self.assertIn("fuse_rows_single e_cam_rows: 640 BRAM36 (1 x 655,360 x 32 bit)", run.stdout)
        self.assertIn("integrate_rows_single z_rows: 2,560 BRAM36", run.stdout)

    def test_unsupported_preset_that_fits_fails(self):
        boards = self.boards({"stale": ("520n", "set(RFRECON_FPGA_SUPPORTED OFF)\n")})
        run = self.budget("--boards", boards)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("stale fits its board, but hw/boards/stale.cmake declares it unsupported", run.stdout)

    def test_unsupported_preset_that_does_not_fit_passes(self):
        wide = "set(RFRECON_FPGA_SUPPORTED OFF)\nset(RFRECON_MAX_ROW_WIDTH 4096)\n"
        boards = self.boards({"small": ("pac_a10", wide)})
        run = self.budget("--boards", boards)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("small: Arria 10 GX 1150: M20K", run.stdout)
        self.assertIn("does not fit, declared unsupported", run.stdout)

    def test_array_without_port_counts_fails(self):
        root = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, root)
        for d in ("kernels", "cmake"):
            shutil.copytree(os.path.join(ROOT, d), os.path.join(root, d))
        os.makedirs(os.path.join(root, "hw"))
        shutil.copytree(os.path.join(ROOT, "hw", "boards"), os.path.join(root, "hw", "boards"))
        path = os.path.join(root, "kernels", "depth", "row_interleave.h")
        with open(path, encoding="utf-8") as f:
            text = f.read()
        with open(path, "w", encoding="utf-8") as f:
            f.write(text.replace("betas", "gammas"))
        run = self.budget("--board", "520n", root=root)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("fuse_rows_single: on-chip array gammas (32 x 32 bit) has no reads and writes per iteration",
                      run.stdout)

    def test_docs_table_drift_fails_and_update_fixes_it(self):
        directory = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, directory)
        doc = os.path.join(directory, "fpga.md")
        with open(doc, "w", encoding="utf-8") as f:
            f.write("# Budget\n\n<!-- fpga_budget.py: begin -->\n| stale | table |\n<!-- fpga_budget.py: end -->\n\nAfter.\n")
        run = self.budget("--board", "520n", "--docs", doc)
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn("the budget tables differ", run.stdout)
        self.assertIn("-| stale | table |", run.stdout)
        run = self.budget("--board", "520n", "--update-docs", doc)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        run = self.budget("--board", "520n", "--docs", doc)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        with open(doc, encoding="utf-8") as f:
            text = f.read()
        self.assertTrue(text.startswith("# Budget\n") and text.endswith("<!-- fpga_budget.py: end -->\n\nAfter.\n"))


if __name__ == "__main__":
    unittest.main()
