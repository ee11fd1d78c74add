#!/usr/bin/env python3
"""Checks the layer graph and every project #include against it (standard library only).

The allowed graph comes from the CMake files, the single source of truth: each layer directory's
rfrecon_add_layer(NAME PUBLIC deps... PRIVATE deps...) call, kernels/CMakeLists.txt (an INTERFACE library) and
host/cli/CMakeLists.txt (target_link_libraries of rfrecon_cli_commands); every `rfrecon::X` named there is an edge.
A file of layer L may include the headers of L and of every layer in the transitive closure of L's dependencies; a
header (.h) only those reachable over PUBLIC edges, since consumers of L get nothing else. Include paths are mapped
to a layer by their directory prefix from the repository root ("host/core/errors.h" -> core, "calib/rig.h" ->
calib); inside kernels/ paths are relative to kernels/ ("depth/row_runs.h"). System includes (<...>) are ignored,
except ones naming a project directory. tests/ and bench/ are not checked: they may include anything.

On top of the graph, the architecture's rules (the declared policy below): every layer is declared there; no cycles;
calib is CPU only (its closure is exactly {core}, no layer in it links OpenCL or HDF5, and calib/CMakeLists.txt names
no OpenCL or HDF5 target); the scheduler depends on no stage layer (its closure stays within {core, cl}); only sim,
pipeline, cli and api (the front door, over pipeline) may use the simulator, and evaluation never does; the Python
module (python/src) and the installed-package consumer (tests/install/consumer) include no project header but the
front door rfrecon/rfrecon.h.

Exit status 0 when everything holds, 1 with one `path:line: message` line per violation, 2 on bad usage.

  check_layers.py [--root DIR]                      check the CMake graph and all includes
  check_layers.py --graph [text|markdown|mermaid]   print the derived direct dependencies
  check_layers.py --check-doc docs/architecture.md  also check the doc's ```text layers block against the graph

The doc block: a fence line that is exactly ```text layers, then one `layer: dep dep` line for every layer (each
once; its direct rfrecon dependencies, separated by spaces or commas, in any order; nothing after the colon for none;
blank lines and `#` comments allowed), closed by ```. `--graph` prints it ready to paste:

  ```text layers
  kernels:
  core:
  cl: core
  ...
  depth: transport outputs calib
  ```
"""
import argparse
import os
import re
import sys
from collections import deque

# ---- The declared policy --------------------------------------------------------------------------------------------
# Every layer the CMake tree defines must be declared here with its directory; a layer directory, or an rfrecon::X
# dependency, that is not declared is a violation (add it here, with its place in the rules below, when adding one).
LAYERS = {
    "kernels": "kernels",
    "core": "host/core",
    "cl": "host/cl",
    "sched": "host/sched",
    "selfcheck": "host/selfcheck",
    "capture": "host/capture",
    "acquire": "host/acquire",
    "drivers": "host/drivers",
    "transport": "host/transport",
    "outputs": "host/outputs",
    "truth": "host/truth",
    "depth": "host/depth",
    "evaluation": "host/evaluation",
    "pipeline": "host/pipeline",
    "cli": "host/cli",
    "calib": "calib",
    "sim": "sim",
    "api": "rfrecon",
}
# CMake targets of the cli directory (it is no rfrecon_add_layer library).
CLI_TARGETS = ("rfrecon_cli_commands", "rfrecon_cli")
# Top-level directories whose sources belong to layers; files there outside every layer directory are violations.
SOURCE_rootS = ("host", "calib", "sim", "kernels", "rfrecon")
# The front door, and the directories whose code may use the library through it alone (the Python module, the
# installed-package consumer), each also including its own headers.
FRONT_DOOR = "rfrecon/rfrecon.h"
FRONT_DOOR_USERS = ("python/src", "tests/install/consumer")
# Directories production code must never include from.
NON_PRODUCTION_rootS = ("tests", "bench")
SOURCE_EXTENSIONS = (".cc", ".cpp", ".cxx", ".h", ".hpp", ".cl")
HEADER_EXTENSIONS = (".h", ".hpp")

# calib is CPU only: its closure is exactly this.
CALIB_CLOSURE = {"core"}
# The scheduler knows devices, tiles and failures, never a stage: its closure must stay within these (kernels, the
# OpenCL C sources and their parameters header, comes through cl, which embeds them).
SCHED_ALLOWED = {"core", "cl", "kernels"}
# The only layers that may depend on (and include) the simulator.
SIM_USERS = {"sim", "pipeline", "cli", "api"}
# Layers with an explicit "never the simulator" rule of their own (reported with this reason).
NO_SIM = {"evaluation": "evaluation reads ground truth through host/truth, never the simulator"}
# Link items that mean OpenCL or HDF5 (matched against the items of target_link_libraries / rfrecon_add_layer).
HEAVY_LINK_RE = re.compile(r"^(\$<[^>]*:)?(OpenCL::|hdf5::|HDF5::|\$\{OpenCL_|\$\{HDF5_|OpenCL$|hdf5|HDF5)")
# Any mention of OpenCL or HDF5 targets in calib/CMakeLists.txt (comments excluded).
CALIB_FORBIDDEN_TEXT_RE = re.compile(r"OpenCL::|hdf5::|HDF5::|\$\{OpenCL_|\$\{HDF5_|\bhdf5_|rfrecon_embed_kernels",
                                     re.IGNORECASE)

DEP_COMMANDS = ("rfrecon_add_layer", "target_link_libraries")
VISIBILITY = ("PUBLIC", "PRIVATE", "INTERFACE", "LINK_PUBLIC", "LINK_PRIVATE", "LINK_INTERFACE_LIBRARIES")
# Top-level directories that hold no layer (besides build trees: build*/ or any directory with a CMakeCache.txt).
SKIP_DIRS = {"tests", "bench", "docs", "scripts", "cmake", "third_party", "external", "node_modules"}


class Violations:
    def __init__(self):
        self.lines = []
        self._seen = set()

    def add(self, path, line, message):
        entry = f"{path}:{line}: {message}"
        if entry not in self._seen:
            self._seen.add(entry)
            self.lines.append(entry)

    def __len__(self):
        return len(self.lines)


# ---- CMake parsing --------------------------------------------------------------------------------------------------
def cmake_commands(text):
    """Yields (name, line, [(arg, line)...]) for every command invocation; comments are skipped."""
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c == "#":
            m = re.match(r"#\[(=*)\[", text[i:])
            if m:
                end = text.find("]" + m.group(1) + "]", i)
                end = n if end < 0 else end + len(m.group(1)) + 2
            else:
                end = text.find("\n", i)
                end = n if end < 0 else end
            line += text.count("\n", i, end)
            i = end
        elif c.isalpha() or c == "_":
            m = re.match(r"[A-Za-z_][A-Za-z0-9_]*", text[i:])
            name = m.group(0)
            j = i + len(name)
            while j < n and text[j] in " \t":
                j += 1
            if j < n and text[j] == "(":
                start_line = line
                args, i, line = _cmake_args(text, j + 1, line)
                yield name.lower(), start_line, args
            else:
                i = j
        else:
            i += 1


def _cmake_args(text, i, line):
    args, depth, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c in " \t\r":
            i += 1
        elif c == "#":
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif c == "(":
            depth += 1
            i += 1
        elif c == ")":
            if depth == 0:
                return args, i + 1, line
            depth -= 1
            i += 1
        elif c == '"':
            end = i + 1
            while end < n and text[end] != '"':
                end += 2 if text[end] == "\\" else 1
            args.append((text[i + 1:end], line))
            line += text.count("\n", i, end)
            i = end + 1
        else:
            m = re.match(r'(?:\$<[^\s()]*>|[^\s()#"])+', text[i:])
            if not m:
                i += 1
                continue
            args.append((m.group(0), line))
            i += len(m.group(0))
    return args, i, line


def strip_cmake_comments(text):
    return "\n".join(re.sub(r"#.*", "", line) for line in text.splitlines())


class Layer:
    def __init__(self, name, directory, cmake_path):
        self.name = name
        self.directory = directory
        self.cmake_path = cmake_path  # relative to the root
        self.deps = {}  # dep -> (visibility, line) of its first mention
        self.heavy = []  # (item, line): OpenCL / HDF5 link items
        self.line = 1  # line of the defining command


def layer_target_names(name):
    return set(CLI_TARGETS) if name == "cli" else {f"rfrecon_{name}", f"rfrecon::{name}"}


def find_layer_dirs(root):
    """Every directory (outside tests/, bench/, build trees, ...) whose CMakeLists.txt defines a target."""
    found = []
    for dirpath, dirnames, filenames in os.walk(root):
        rel = os.path.relpath(dirpath, root).replace(os.sep, "/")
        rel = "" if rel == "." else rel
        top = not rel
        dirnames[:] = sorted(d for d in dirnames
                             if not d.startswith(".") and not (top and (d.startswith("build") or d in SKIP_DIRS))
                             and not os.path.exists(os.path.join(dirpath, d, "CMakeCache.txt")))
        if not rel or "CMakeLists.txt" not in filenames:
            continue
        with open(os.path.join(dirpath, "CMakeLists.txt"), encoding="utf-8") as f:
            text = f.read()
        names = {name for name, _, _ in cmake_commands(text)}
        if names & {"rfrecon_add_layer", "add_library", "add_executable"}:
            found.append((rel, text))
    return found


def parse_layers(root, violations):
    layers, reported = {}, set()
    dir_to_layer = {d: n for n, d in LAYERS.items()}
    for rel, text in find_layer_dirs(root):
        cmake_path = f"{rel}/CMakeLists.txt"
        commands = list(cmake_commands(text))
        name, line = None, 1
        for cmd, cmd_line, args in commands:
            if cmd == "rfrecon_add_layer" and args:
                name, line = args[0][0], cmd_line
                break
            if cmd == "add_library" and len(args) >= 3 and args[1][0] == "ALIAS" and args[0][0].startswith("rfrecon::"):
                name, line = args[0][0][len("rfrecon::"):], cmd_line
                break
        if name is None:
            name = dir_to_layer.get(rel)
        if name is None or name not in LAYERS or LAYERS[name] != rel or name in layers:
            reported.add(rel)
        if name is None or name not in LAYERS:
            violations.add(cmake_path, line, f"layer {name or rel} ({rel}/) is not in the declared policy "
                                              f"(LAYERS in scripts/check_layers.py)")
            continue
        if LAYERS[name] != rel:
            violations.add(cmake_path, line, f"layer {name} is defined in {rel}/, the policy declares it in "
                                              f"{LAYERS[name]}/")
            continue
        if name in layers:
            violations.add(cmake_path, line, f"layer {name} defined twice")
            continue
        layer = Layer(name, rel, cmake_path)
        layer.line = line
        own = layer_target_names(name)
        for cmd, cmd_line, args in commands:
            if cmd not in DEP_COMMANDS or not args:
                continue
            if cmd == "target_link_libraries" and args[0][0] not in own:
                continue
            visibility = "PUBLIC"
            for item, item_line in args[1:]:
                if item in VISIBILITY:
                    visibility = "PUBLIC" if item in ("PUBLIC", "INTERFACE", "LINK_PUBLIC") else "PRIVATE"
                    continue
                if HEAVY_LINK_RE.match(item):
                    layer.heavy.append((item, item_line))
                dep = None
                m = re.match(r"^(?:\$<[^>]*:)?rfrecon(?:::|_)([A-Za-z0-9_]+)>?$", item)
                if m and item not in own:
                    dep = m.group(1)
                    if dep == "cli_commands":
                        dep = "cli"
                if dep is None or dep == name:
                    continue
                if dep not in LAYERS:
                    violations.add(cmake_path, item_line, f"layer {name} depends on {item}, which is not a "
                                                          f"layer of the declared policy")
                    continue
                if dep not in layer.deps or (visibility == "PUBLIC" and layer.deps[dep][0] != "PUBLIC"):
                    layer.deps[dep] = (visibility, layer.deps.get(dep, (None, item_line))[1])
        layers[name] = layer
    for name, directory in LAYERS.items():
        if name not in layers and directory not in reported:
            violations.add(f"{directory}/CMakeLists.txt", 1, f"layer {name} of the declared policy has no "
                                                             f"CMake target here")
    for layer in layers.values():
        for dep, (_, line) in list(layer.deps.items()):
            if dep not in layers:
                violations.add(layer.cmake_path, line, f"layer {layer.name} depends on {dep}, which the CMake "
                                                       f"tree does not define")
                del layer.deps[dep]
    return layers


# ---- The graph ------------------------------------------------------------------------------------------------------
def closure(layers, start, public_only=False):
    seen, todo = set(), [start]
    while todo:
        for dep, (visibility, _) in layers[todo.pop()].deps.items():
            if public_only and visibility != "PUBLIC":
                continue
            if dep not in seen:
                seen.add(dep)
                todo.append(dep)
    seen.discard(start)
    return seen


def path_to(layers, start, goal):
    """The shortest dependency path start -> ... -> goal, as a list of layer names."""
    prev, queue = {start: None}, deque([start])
    while queue:
        cur = queue.popleft()
        if cur == goal and cur != start:
            break
        for dep in sorted(layers[cur].deps):
            if dep not in prev:
                prev[dep] = cur
                queue.append(dep)
    if goal not in prev:
        return None
    path, cur = [], goal
    while cur is not None:
        path.append(cur)
        cur = prev[cur]
    return path[::-1]


def cycles(layers):
    """Strongly connected components with more than one layer (or a self edge), Tarjan."""
    index, low, stack, on_stack, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(layers[v].deps):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in layers[v].deps:
                out.append(sorted(comp))

    for v in sorted(layers):
        if v not in index:
            visit(v)
    return out


def cycle_path(layers, comp):
    """One cycle through comp[0], e.g. ['a', 'b', 'a']."""
    start, members = comp[0], set(comp)
    if start in layers[start].deps:
        return [start, start]
    prev, queue = {start: None}, deque([start])
    while queue:
        cur = queue.popleft()
        for dep in sorted(layers[cur].deps):
            if dep == start:
                path = [cur]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                return path[::-1] + [start]
            if dep in members and dep not in prev:
                prev[dep] = cur
                queue.append(dep)
    return comp + [start]


def topological(layers):
    """Layers with their dependencies first, ties in LAYERS order (cycles broken arbitrarily)."""
    order_key = {n: i for i, n in enumerate(LAYERS)}
    done, out = set(), []

    def visit(v, active):
        if v in done or v in active:
            return
        active.add(v)
        for dep in sorted(layers[v].deps, key=order_key.get):
            visit(dep, active)
        active.discard(v)
        done.add(v)
        out.append(v)

    for v in sorted(layers, key=order_key.get):
        visit(v, set())
    return out


def check_graph(root, layers, violations):
    for comp in cycles(layers):
        path = cycle_path(layers, comp)
        first = layers[path[0]]
        violations.add(first.cmake_path, first.deps[path[1]][1], "layer cycle: " + " -> ".join(path))

    def dep_line(layer, path):
        return layer.deps[path[1]][1] if path and len(path) > 1 else layer.line

    if "calib" in layers:
        calib = layers["calib"]
        reach = closure(layers, "calib")
        for extra in sorted(reach - CALIB_CLOSURE):
            path = path_to(layers, "calib", extra)
            violations.add(calib.cmake_path, dep_line(calib, path),
                           f"calib depends on {extra} (via {' -> '.join(path)}): calib is CPU only, its closure "
                           f"must be {{{', '.join(sorted(CALIB_CLOSURE))}}}")
        for missing in sorted(CALIB_CLOSURE - reach):
            violations.add(calib.cmake_path, calib.line, f"calib does not depend on {missing}: its closure must be "
                                                         f"{{{', '.join(sorted(CALIB_CLOSURE))}}}")
        for dep in sorted(reach):
            for item, line in layers[dep].heavy:
                violations.add(layers[dep].cmake_path, line,
                               f"layer {dep} links {item}, and calib depends on it (via "
                               f"{' -> '.join(path_to(layers, 'calib', dep))}): calib never gets OpenCL or HDF5")
        with open(os.path.join(root, calib.cmake_path), encoding="utf-8") as f:
            for number, text in enumerate(strip_cmake_comments(f.read()).splitlines(), 1):
                m = CALIB_FORBIDDEN_TEXT_RE.search(text)
                if m:
                    violations.add(calib.cmake_path, number, f"calib/CMakeLists.txt names {m.group(0)}: calib is "
                                                             f"CPU only, never OpenCL or HDF5")

    if "sched" in layers:
        sched = layers["sched"]
        for extra in sorted(closure(layers, "sched") - SCHED_ALLOWED):
            path = path_to(layers, "sched", extra)
            violations.add(sched.cmake_path, dep_line(sched, path),
                           f"sched depends on {extra} (via {' -> '.join(path)}): the scheduler may depend only on "
                           f"{', '.join(sorted(SCHED_ALLOWED))}, never on a stage layer")

    if "sim" in layers:
        for name in sorted(layers):
            if name in SIM_USERS or "sim" not in closure(layers, name):
                continue
            layer = layers[name]
            path = path_to(layers, name, "sim")
            reason = NO_SIM.get(name, f"only {', '.join(sorted(SIM_USERS))} may use the simulator")
            violations.add(layer.cmake_path, dep_line(layer, path),
                           f"layer {name} depends on sim (via {' -> '.join(path)}): {reason}")


# ---- Includes -------------------------------------------------------------------------------------------------------
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


def includes(path):
    """Yields (line, kind, target) of the #include lines outside block comments."""
    in_comment = False
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, raw in enumerate(f, 1):
            line, out = raw, ""
            while line:
                if in_comment:
                    end = line.find("*/")
                    if end < 0:
                        line = ""
                    else:
                        line, in_comment = line[end + 2:], False
                else:
                    start = line.find("/*")
                    cut = line.find("//")
                    if cut >= 0 and (start < 0 or cut < start):
                        out += line[:cut]
                        line = ""
                    elif start >= 0:
                        out += line[:start] + " "
                        line, in_comment = line[start + 2:], True
                    else:
                        out += line
                        line = ""
            m = INCLUDE_RE.match(out)
            if m:
                yield number, m.group(1), os.path.normpath(m.group(2)).replace(os.sep, "/")


def layer_of_path(rel, dir_index):
    """The layer whose directory is the longest prefix of rel, or None."""
    best = None
    for directory, name in dir_index:
        if rel.startswith(directory + "/") and (best is None or len(directory) > len(best[0])):
            best = (directory, name)
    return best[1] if best else None


def resolve_include(root, file_rel, file_layer, kind, target, dir_index):
    """Returns (layer, error): the included layer, or None when the include is no project header."""
    first = target.split("/", 1)[0]
    layer = layer_of_path(target, dir_index)
    if layer:
        return layer, None
    if first in SOURCE_rootS or first in NON_PRODUCTION_rootS:
        if first in NON_PRODUCTION_rootS:
            return None, f"{file_rel} (layer {file_layer}) includes {target}: production code never includes {first}/"
        return None, f"{file_rel} (layer {file_layer}) includes {target}, under no layer directory (unknown prefix)"
    if kind == "<":
        return None, None
    if target.startswith("../") or target == "..":
        return None, f"{file_rel} (layer {file_layer}) includes {target}: include from the repository root"
    file_dir = os.path.dirname(file_rel)
    kernels_dir = LAYERS["kernels"]
    if os.path.isfile(os.path.join(root, kernels_dir, target)):
        # Relative to kernels/ (its include directory): kernels' own convention, and from outside a kernels header
        # reached through rfrecon::kernels' include path.
        return "kernels", None
    if os.path.isfile(os.path.join(root, file_dir, target)):
        if file_layer == "kernels":
            return "kernels", None
        return None, f"{file_rel} (layer {file_layer}) includes {target} relative to its directory: include from the " \
                     f"repository root ({file_dir}/{target})"
    if os.path.isdir(os.path.join(root, first)) and "/" in target:
        return None, f"{file_rel} (layer {file_layer}) includes {target}, under no layer directory (unknown prefix)"
    return None, None  # a third-party header in quotes


def source_files(root, layers):
    starts = set(SOURCE_rootS) | {layer.directory for layer in layers.values()}
    seen = set()
    for start in sorted(starts):
        base = os.path.join(root, start)
        if not os.path.isdir(base):
            continue
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith(".")
                                 and not os.path.exists(os.path.join(dirpath, d, "CMakeCache.txt")))
            for filename in sorted(filenames):
                if filename.endswith(SOURCE_EXTENSIONS):
                    rel = os.path.relpath(os.path.join(dirpath, filename), root).replace(os.sep, "/")
                    if rel not in seen:
                        seen.add(rel)
                        yield rel


def check_includes(root, layers, violations):
    dir_index = [(layer.directory, name) for name, layer in layers.items()]
    closures = {name: closure(layers, name) for name in layers}
    public = {name: closure(layers, name, public_only=True) for name in layers}
    files = includes_checked = 0
    for rel in source_files(root, layers):
        layer = layer_of_path(rel, dir_index)
        if layer is None:
            violations.add(rel, 1, f"{rel} is in no layer directory")
            continue
        files += 1
        is_header = rel.endswith(HEADER_EXTENSIONS)
        for line, kind, target in includes(os.path.join(root, rel)):
            included, error = resolve_include(root, rel, layer, kind, target, dir_index)
            if error:
                violations.add(rel, line, error)
                continue
            if included is None or included == layer:
                continue
            includes_checked += 1
            if included == "sim" and layer not in SIM_USERS:
                violations.add(rel, line, f"{rel} (layer {layer}) includes {target} (layer sim), not a dependency of "
                                          f"{layer}: only {', '.join(sorted(SIM_USERS))} may use the simulator")
            elif included not in closures[layer]:
                violations.add(rel, line, f"{rel} (layer {layer}) includes {target} (layer {included}), not a "
                                          f"dependency of {layer}")
            elif is_header and included not in public[layer]:
                violations.add(rel, line, f"{rel} (layer {layer}) includes {target} (layer {included}), a PRIVATE "
                                          f"dependency of {layer}: its headers may include only PUBLIC ones")
    return files, includes_checked


def check_front_door_users(root, violations):
    """Files of FRONT_DOOR_USERS include of the project only the front door and their own directory's headers."""
    files = 0
    for directory in FRONT_DOOR_USERS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, directory)):
            dirnames.sort()
            for filename in sorted(f for f in filenames if f.endswith(SOURCE_EXTENSIONS)):
                rel = os.path.relpath(os.path.join(dirpath, filename), root).replace(os.sep, "/")
                files += 1
                for line, kind, target in includes(os.path.join(root, rel)):
                    first = target.split("/", 1)[0]
                    project = kind == '"' and (first in SOURCE_rootS or first in NON_PRODUCTION_rootS
                                               or os.path.isdir(os.path.join(root, first)))
                    if project and target != FRONT_DOOR and not target.startswith(directory + "/"):
                        violations.add(rel, line, f"{rel} includes {target}: {directory}/ uses the library through "
                                                  f"its front door only ({FRONT_DOOR})")
    return files


# ---- Output and the doc ---------------------------------------------------------------------------------------------
DOC_FENCE_RE = re.compile(r"^```\s*text\s+layers\s*$")


def graph_text(layers, fmt):
    order = topological(layers)
    key = {n: i for i, n in enumerate(order)}
    lines = []
    if fmt == "text":
        lines.append("```text layers")
        for name in order:
            deps = sorted(layers[name].deps, key=key.get)
            lines.append(f"{name}: {' '.join(deps)}".rstrip())
        lines.append("```")
    elif fmt == "markdown":
        lines += ["| layer | directory | depends on (direct) | may include (closure) |", "| --- | --- | --- | --- |"]
        for name in order:
            deps = ", ".join(sorted(layers[name].deps, key=key.get)) or "nothing"
            reach = ", ".join(sorted(closure(layers, name), key=key.get)) or "nothing"
            lines.append(f"| {name} | `{layers[name].directory}/` | {deps} | {reach} |")
    else:
        lines += ["```mermaid", "graph BT"]
        for name in order:
            deps = sorted(layers[name].deps, key=key.get)
            if not deps and not any(name in layers[other].deps for other in layers):
                lines.append(f"  {name}")
            for dep in deps:
                lines.append(f"  {name} --> {dep}")
        lines.append("```")
    return "\n".join(lines)


def check_doc(layers, doc_path, doc_rel, violations):
    try:
        with open(doc_path, encoding="utf-8") as f:
            text = f.read().splitlines()
    except OSError as e:
        violations.add(doc_rel, 1, f"cannot read the doc: {e.strerror}")
        return
    starts = [i for i, line in enumerate(text) if DOC_FENCE_RE.match(line.strip())]
    if not starts:
        violations.add(doc_rel, 1, "no ```text layers block (run scripts/check_layers.py --graph for one)")
        return
    if len(starts) > 1:
        violations.add(doc_rel, starts[1] + 1, "more than one ```text layers block")
    documented, start = {}, starts[0]
    end = start + 1
    while end < len(text) and not text[end].strip().startswith("```"):
        line = text[end].split("#", 1)[0].strip()
        number = end + 1
        end += 1
        if not line:
            continue
        m = re.match(r"^([A-Za-z0-9_]+)\s*:(.*)$", line)
        if not m:
            violations.add(doc_rel, number, f"cannot parse '{line}' (expected 'layer: dep dep ...')")
            continue
        name, deps = m.group(1), set(re.split(r"[\s,]+", m.group(2).strip())) - {""}
        if name in documented:
            violations.add(doc_rel, number, f"layer {name} listed twice")
            continue
        documented[name] = (deps, number)
    if end >= len(text):
        violations.add(doc_rel, start + 1, "the ```text layers block is not closed")
    for name, (deps, number) in documented.items():
        if name not in layers:
            violations.add(doc_rel, number, f"layer {name} is in the doc but not in the CMake tree")
            continue
        actual = set(layers[name].deps)
        if deps != actual:
            parts = []
            if actual - deps:
                parts.append("missing " + " ".join(sorted(actual - deps)))
            if deps - actual:
                parts.append("not in CMake: " + " ".join(sorted(deps - actual)))
            violations.add(doc_rel, number, f"layer {name}: the doc lists '{' '.join(sorted(deps))}', "
                                            f"CMake has '{' '.join(sorted(actual))}' ({'; '.join(parts)})")
    for name in sorted(set(layers) - set(documented)):
        violations.add(doc_rel, start + 1, f"layer {name} is missing from the ```text layers block")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n", 1)[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                        help="repository root (default: the parent of scripts/)")
    parser.add_argument("--graph", nargs="?", const="text", choices=("text", "markdown", "mermaid"),
                        help="print the direct layer dependencies derived from CMake and exit")
    parser.add_argument("--check-doc", metavar="DOC", action="append", default=[],
                        help="also check the ```text layers block of DOC (relative to --root) against the graph")
    args = parser.parse_args(argv)
    root = os.path.abspath(args.root)
    if not os.path.isfile(os.path.join(root, "CMakeLists.txt")):
        print(f"check_layers: {root} has no CMakeLists.txt", file=sys.stderr)
        return 2

    violations = Violations()
    layers = parse_layers(root, violations)
    if args.graph:
        print(graph_text(layers, args.graph))
        for line in violations.lines:
            print(line, file=sys.stderr)
        return 1 if violations else 0

    check_graph(root, layers, violations)
    files, checked = check_includes(root, layers, violations)
    files += check_front_door_users(root, violations)
    for doc in args.check_doc:
        doc_path = doc if os.path.isabs(doc) else os.path.join(root, doc)
        check_doc(layers, doc_path, os.path.relpath(doc_path, root).replace(os.sep, "/"), violations)
    for line in violations.lines:
        print(line)
    if violations:
        print(f"check_layers: {len(violations)} violation(s)", file=sys.stderr)
        return 1
    print(f"check_layers: {len(layers)} layers, {files} files, {checked} cross-layer includes: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
