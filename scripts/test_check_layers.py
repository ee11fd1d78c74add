#!/usr/bin/env python3
"""Self-test of scripts/check_layers.py: fake source trees with known violations, so the check provably fails.

Run: python3 scripts/test_check_layers.py  (ctest: layer_includes_selftest, label lint)
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_layers.py")

# The layer graph of the fake tree (the real one at the time of writing); directory -> (name, PUBLIC deps).
GRAPH = {
    "host/core": ("core", []),
    "host/cl": ("cl", ["core"]),
    "host/sched": ("sched", ["cl"]),
    "host/selfcheck": ("selfcheck", ["cl"]),
    "host/capture": ("capture", ["core"]),
    "host/acquire": ("acquire", ["capture"]),
    "host/drivers": ("drivers", ["acquire"]),
    "host/transport": ("transport", ["capture", "sched", "kernels"]),
    "host/outputs": ("outputs", ["core"]),
    "host/truth": ("truth", ["core"]),
    "host/depth": ("depth", ["transport", "calib", "outputs"]),
    "host/evaluation": ("evaluation", ["outputs", "truth"]),
    "host/pipeline": ("pipeline", ["depth", "evaluation", "sim"]),
    "calib": ("calib", ["core"]),
    "sim": ("sim", ["capture", "acquire", "calib", "truth"]),
    "rfrecon": ("api", ["pipeline"]),
}
DIRS = {name: d for d, (name, _) in GRAPH.items()}
DIRS.update(kernels="kernels", cli="host/cli")


class FakeTree:
    def __init__(self):
        self.root = tempfile.mkdtemp(prefix="check_layers_")
        self.write("CMakeLists.txt", "project(fake)\n")
        for directory, (name, deps) in GRAPH.items():
            self.set_deps(name, deps)
            self.write(f"{directory}/{name}.h", "#pragma once\n#include <vector>\n")
            self.write(f"{directory}/{name}.cc", f'#include "{directory}/{name}.h"\n' +
                       "".join(f'#include "{DIRS[d]}/{d}.h"\n' for d in deps if d != "kernels"))
        self.write("kernels/CMakeLists.txt", "add_library(rfrecon_kernels INTERFACE)\n"
                                             "add_library(rfrecon::kernels ALIAS rfrecon_kernels)\n")
        self.write("kernels/common/target.h", "#pragma once\n")
        self.write("kernels/depth/runs.h", '#pragma once\n#include "common/target.h"\n')
        self.write("kernels/depth/fuse.cl", '#include "common/target.h"\n#include "depth/runs.h"\n')
        self.write("host/CMakeLists.txt", "foreach(layer core cl)\n  add_subdirectory(${layer})\nendforeach()\n")
        self.write("host/cli/CMakeLists.txt",
                   "add_library(rfrecon_cli_commands STATIC ${cli_sources})\n"
                   "target_link_libraries(rfrecon_cli_commands PUBLIC rfrecon::pipeline rfrecon::selfcheck\n"
                   "                      PRIVATE spdlog::spdlog)\n"
                   "add_executable(rfrecon_cli main.cc)\n"
                   "target_link_libraries(rfrecon_cli PRIVATE rfrecon_cli_commands)\n")
        self.write("host/cli/main.cc", '#include "host/pipeline/pipeline.h"\n#include "sim/sim.h"\n')
        self.write("tests/core/ply_test.cc", '#include "sim/sim.h"\n#include "host/cli/anything.h"\n')

    def write(self, rel, text):
        path = os.path.join(self.root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

    def set_deps(self, name, public, private=(), extra=""):
        args = " ".join(f"rfrecon::{d}" for d in public)
        priv = " ".join(f"rfrecon::{d}" for d in private)
        self.write(f"{DIRS[name]}/CMakeLists.txt",
                   f"# The {name} layer.\nrfrecon_add_layer({name} PUBLIC {args} nlohmann_json::nlohmann_json\n"
                   f"                  PRIVATE {priv} spdlog::spdlog {extra})\n")

    def run(self, *args):
        result = subprocess.run([sys.executable, SCRIPT, "--root", self.root, *args],
                                capture_output=True, text=True, check=False)
        return result.returncode, result.stdout + result.stderr

    def cleanup(self):
        shutil.rmtree(self.root)


class CheckLayersTest(unittest.TestCase):
    def setUp(self):
        self.tree = FakeTree()
        self.addCleanup(self.tree.cleanup)

    def assertFails(self, *expected, args=()):
        rc, out = self.tree.run(*args)
        self.assertEqual(rc, 1, out)
        for text in expected:
            self.assertIn(text, out)
        return out

    def test_clean_tree_passes(self):
        rc, out = self.tree.run()
        self.assertEqual(rc, 0, out)
        self.assertIn("18 layers", out)

    def test_front_door_users_include_only_the_front_door(self):
        self.tree.write("python/src/module.cc", '#include "rfrecon/rfrecon.h"\n#include "python/src/arrays.h"\n'
                                                '#include <pybind11/pybind11.h>\n')
        rc, out = self.tree.run()
        self.assertEqual(rc, 0, out)
        self.tree.write("tests/install/consumer/main.cc", '#include "rfrecon/rfrecon.h"\n#include "calib/calib.h"\n')
        self.assertFails("tests/install/consumer/main.cc:2: tests/install/consumer/main.cc includes calib/calib.h: "
                         "tests/install/consumer/ uses the library through its front door only (rfrecon/rfrecon.h)")

    def test_wrong_way_include(self):
        self.tree.write("host/core/core.cc", '#include "host/core/core.h"\n\n#include "host/depth/depth.h"\n')
        self.assertFails("host/core/core.cc:3: host/core/core.cc (layer core) includes host/depth/depth.h "
                         "(layer depth), not a dependency of core")

    def test_include_through_a_transitive_dependency_passes(self):
        self.tree.write("host/depth/depth.cc", '#include "host/cl/cl.h"\n#include "kernels/depth/runs.h"\n'
                                               '#include "depth/runs.h"\n')
        rc, out = self.tree.run()
        self.assertEqual(rc, 0, out)

    def test_cycle(self):
        self.tree.set_deps("core", ["cl"])
        self.assertFails("host/cl/CMakeLists.txt:2: layer cycle: cl -> core -> cl",
                         "calib depends on cl (via calib -> core -> cl)")

    def test_longer_cycle_and_sched_on_a_stage(self):
        self.tree.set_deps("sched", ["cl", "depth"])
        self.assertFails("layer cycle: depth -> transport -> sched -> depth",
                         "host/sched/CMakeLists.txt:2: sched depends on depth (via sched -> depth)")

    def test_sched_on_a_stage_without_cycle(self):
        self.tree.set_deps("sched", ["cl", "outputs"])
        out = self.assertFails("sched depends on outputs (via sched -> outputs): the scheduler")
        self.assertNotIn("cycle", out)

    def test_calib_on_opencl(self):
        self.tree.set_deps("calib", ["core", "cl"])
        self.assertFails("calib/CMakeLists.txt:2: calib depends on cl (via calib -> cl): calib is CPU only")

    def test_calib_naming_opencl_or_hdf5(self):
        self.tree.set_deps("calib", ["core"], extra="\n  OpenCL::OpenCL hdf5::hdf5_cpp")
        self.assertFails("calib/CMakeLists.txt:4: calib/CMakeLists.txt names OpenCL::")

    def test_core_linking_opencl_reaches_calib(self):
        self.tree.set_deps("core", [], extra="OpenCL::OpenCL")
        self.assertFails("host/core/CMakeLists.txt:3: layer core links OpenCL::OpenCL, and calib depends on it")

    def test_evaluation_on_sim(self):
        self.tree.set_deps("evaluation", ["outputs", "truth", "sim"])
        self.assertFails("host/evaluation/CMakeLists.txt:2: layer evaluation depends on sim (via evaluation -> sim): "
                         "evaluation reads ground truth through host/truth")

    def test_production_include_of_sim(self):
        self.tree.write("host/outputs/outputs.cc", '#include "sim/sim.h"\n')
        self.assertFails("host/outputs/outputs.cc:1: host/outputs/outputs.cc (layer outputs) includes sim/sim.h "
                         "(layer sim), not a dependency of outputs: only api, cli, pipeline, sim may use the simulator")

    def test_depth_on_sim_in_cmake(self):
        self.tree.set_deps("depth", ["transport", "calib", "outputs", "sim"])
        self.assertFails("layer depth depends on sim (via depth -> sim): only api, cli, pipeline, sim may use")

    def test_unknown_host_folder(self):
        self.tree.write("host/depth/depth.cc", '#include "host/calibration/dual.h"\n')
        self.tree.write("host/calibration/dual.h", "#pragma once\n")
        self.assertFails("host/depth/depth.cc:1: host/depth/depth.cc (layer depth) includes host/calibration/dual.h, "
                         "under no layer directory (unknown prefix)",
                         "host/calibration/dual.h:1: host/calibration/dual.h is in no layer directory")

    def test_production_include_of_tests(self):
        self.tree.write("host/depth/depth.cc", '#include "tests/common/run_cli.h"\n')
        self.assertFails("production code never includes tests/")

    def test_relative_include(self):
        self.tree.write("host/cl/cl.cc", '#include "cl.h"\n')
        self.assertFails("host/cl/cl.cc:1: host/cl/cl.cc (layer cl) includes cl.h relative to its directory")

    def test_kernels_include_host(self):
        self.tree.write("kernels/depth/runs.h", '#include "host/core/core.h"\n')
        self.assertFails("kernels/depth/runs.h:1: kernels/depth/runs.h (layer kernels) includes host/core/core.h "
                         "(layer core), not a dependency of kernels")

    def test_angle_include_of_a_project_header_is_checked(self):
        self.tree.write("host/core/core.cc", "#include <host/depth/depth.h>\n#include <opencv2/core.hpp>\n")
        self.assertFails("host/core/core.cc:1: host/core/core.cc (layer core) includes host/depth/depth.h")

    def test_includes_in_comments_are_ignored(self):
        self.tree.write("host/core/core.cc", '// #include "host/depth/depth.h"\n/*\n#include "sim/sim.h"\n*/\n')
        rc, out = self.tree.run()
        self.assertEqual(rc, 0, out)

    def test_header_including_a_private_dependency(self):
        self.tree.set_deps("depth", ["transport", "calib"], private=["outputs"])
        self.tree.write("host/depth/depth.h", '#include "host/outputs/outputs.h"\n')
        self.tree.write("host/depth/depth.cc", '#include "host/outputs/outputs.h"\n')
        out = self.assertFails("host/depth/depth.h:1: host/depth/depth.h (layer depth) includes "
                               "host/outputs/outputs.h (layer outputs), a PRIVATE dependency of depth")
        self.assertNotIn("depth.cc", out)

    def test_undeclared_layer(self):
        self.tree.write("host/extra/CMakeLists.txt", "rfrecon_add_layer(extra PUBLIC rfrecon::core)\n")
        self.tree.write("host/extra/extra.cc", '#include "host/core/core.h"\n')
        self.assertFails("host/extra/CMakeLists.txt:1: layer extra (host/extra/) is not in the declared policy")

    def test_dependency_on_an_undeclared_layer(self):
        self.tree.set_deps("outputs", ["core", "nosuch"])
        self.assertFails("host/outputs/CMakeLists.txt:2: layer outputs depends on rfrecon::nosuch, which is not a "
                         "layer of the declared policy")

    def test_missing_layer(self):
        os.remove(os.path.join(self.tree.root, "host/truth/CMakeLists.txt"))
        self.assertFails("layer truth of the declared policy has no CMake target here")

    def test_graph_and_doc(self):
        rc, graph = self.tree.run("--graph")
        self.assertEqual(rc, 0, graph)
        self.assertTrue(graph.startswith("```text layers\n"), graph)
        self.assertIn("\ndepth: transport outputs calib\n", graph)
        self.tree.write("docs/architecture.md", "# Architecture\n\nThe layers:\n\n" + graph + "\nMore text.\n")
        rc, out = self.tree.run("--check-doc", "docs/architecture.md")
        self.assertEqual(rc, 0, out)

        wrong = graph.replace("depth: transport outputs calib", "# a comment\ndepth: transport, calib sched")
        wrong = wrong.replace("truth: core\n", "")
        self.tree.write("docs/architecture.md", "# Architecture\n\n" + wrong)
        self.assertFails("docs/architecture.md:16: layer depth: the doc lists 'calib sched transport', CMake has "
                         "'calib outputs transport' (missing outputs; not in CMake: sched)",
                         "docs/architecture.md:3: layer truth is missing from the ```text layers block",
                         args=("--check-doc", "docs/architecture.md"))

    def test_doc_without_block(self):
        self.tree.write("docs/architecture.md", "# Architecture\n")
        self.assertFails("docs/architecture.md:1: no ```text layers block",
                         args=("--check-doc", "docs/architecture.md"))


if __name__ == "__main__":
    unittest.main()
