#!/usr/bin/env python3
"""The layer gate: every #include of csrc/, fmu/ and the Python binding against the layer rules of
docs/architecture.md ("What the build enforces"). ctest `layer_gate` runs it on the tree and
`layer_gate_self_test` plants one violation of each rule in a copy and asks that each is found.

    python3 tests/gates/layers.py [ROOT]          # the tree at ROOT (default: this checkout)
    python3 tests/gates/layers.py --self-test     # each rule fails on a planted violation

Exit status 1 names every include that breaks a rule (file, line, the rule) and every entry of the
allow-list that no include uses any more (remove it: the list only shrinks).

The rules, bottom up (a "folder" is a folder of csrc/; benchmarks, csrc/bench, are not checked):
  core        csrc/core includes only core/ and mbs/ headers (no stewart/ header, no platform folder).
  util        csrc/util includes util/, the public headers and what the core publishes.
  kinematics  csrc/kinematics includes kinematics/, util/, the public headers and the core's
              published header: no direction, no table/, no model.hpp.
  table       csrc/table includes table/, kinematics/, util/, the public headers: no direction, no
              model.hpp.
  drives      csrc/drives (a leg's drive, shared by the inverse and the plant as kinematics is)
              includes drives/, kinematics/, util/ and the public headers.
  model       csrc/model.hpp and model.cpp include of a direction only the header it publishes for
              the model (<direction>/<direction>_constants.hpp).
  direction   every other folder of csrc/ (inverse, forward, plant, linearize, limits, check,
              calibration, and any new one) includes its own folder, kinematics/, drives/, table/, util/,
              the public headers, model.hpp and batch_paths.hpp, and of the core only mbs/mbs.h and
              core/published.hpp: never another direction's files.
  cli         csrc/cli includes cli/ and the public headers only.
  binding     python/**/*.cpp, *.hpp include their own folder's files and the public headers only.
  public      csrc/include/stewart/*.h include only stewart/ and mbs/ headers.
  fmu-runtime fmu/runtime includes its own files, the public headers, and of a model only config.h
              and variables.def.
  fmu-model   fmu/models/<unit> includes its own folder's files, the runtime's headers and the
              public headers: no library internal, no other unit's file.
An include in <angle brackets> of a system or third-party header (Eigen, SUNDIALS), and the FMI
standard's headers (fmi2*.h, fmi3*.h), are no layer of this project and are not checked; a project
header in angle brackets is, and an include with .. in its path is refused everywhere.
"""
import re
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCE_ENDINGS = {".c", ".cc", ".cpp", ".h", ".hpp", ".inc", ".def"}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')
PUBLIC = ("stewart/", "mbs/")
THIRD_PARTY_QUOTED = re.compile(r"fmi[23]\w*\.h")
CORE_PUBLISHED = {"mbs/mbs.h", "core/published.hpp"}
SHARED = {"kinematics", "table", "util", "drives"}  # folders every direction may include
NOT_DIRECTIONS = {"core", "util", "kinematics", "table", "drives", "include", "cli", "bench"}

# What remains, by reason: each (file, included header) there is allowed. An entry no include uses
# fails the gate, so that the list shrinks as the layers are mended.
EXCEPTIONS = {
    "the 14-body mechanism the model keeps is built by inverse/full_model.*, which the plant "
    "shares: it belongs in a shared folder": [
        ("csrc/model.hpp", "inverse/full_model.hpp")],
    "the 14-body mechanism works on the core's handles and its step directly (the inverse solve's "
    "hot path); to go through core/published.hpp": [
        ("csrc/inverse/full_model.hpp", "core/mbs_handles.hpp"),
        ("csrc/inverse/full_model.cpp", "core/dynamics.hpp"),
        ("csrc/inverse/full_model.cpp", "core/euler_pairs.hpp"),
        ("csrc/inverse/full_model.cpp", "core/step.hpp")],
    "published (core/published.hpp includes it): to include that header instead": [
        ("csrc/plant/plant_integrator.cpp", "core/sundials_holder.hpp")],
    "the plant's limit warnings run the limit check on each step's pose, with its constants in "
    "the plant's handle": [
        ("csrc/plant/plant_api.cpp", "limits/limit_check.hpp"),
        ("csrc/plant/plant_object.hpp", "limits/limit_check.hpp")],
    "the parameter check refuses legs closer than they are thick, with the limit check's "
    "distances": [
        ("csrc/table/params.cpp", "limits/limit_check.hpp")],
    "the linearisation differentiates the plant's own templated equations (a dual instance)": [
        ("csrc/linearize/plant_derivatives.hpp", "plant/plant_equations.hpp"),
        ("csrc/linearize/plant_dual.cpp", "plant/plant_bodies_impl.hpp"),
        ("csrc/linearize/plant_dual.cpp", "plant/plant_equations_impl.hpp")],
    "header-only helpers the command lines share with the library (the pose columns' names, "
    "locale-free numbers, a range check); public headers for them are open work": [
        ("csrc/cli/forward_table.cpp", "kinematics/pose_names.hpp"),
        ("csrc/cli/pose_table.cpp", "kinematics/pose_names.hpp"),
        ("csrc/cli/stewart_simulate.cpp", "kinematics/pose_names.hpp"),
        ("csrc/cli/forward_table.cpp", "util/number_text.hpp"),
        ("csrc/cli/param_assignment.cpp", "util/number_text.hpp"),
        ("csrc/cli/pose_table.cpp", "util/number_text.hpp"),
        ("csrc/cli/stewart_simulate.cpp", "util/number_text.hpp"),
        ("csrc/cli/stewart_solve.cpp", "util/number_text.hpp"),
        ("csrc/cli/stewart_solve.cpp", "util/range.hpp"),
        ("csrc/cli/stewart_simulate.cpp", "util/range.hpp")],
    "stewart.head_motion moves a point through the library's own frames (tool, user, rotation "
    "order, z down); a public C call for a point's motion is open work": [
        ("python/stewart/core_cueing.cpp", "kinematics/frames.hpp")],
}
ALLOWED = {entry: reason for reason, entries in EXCEPTIONS.items() for entry in entries}


def includes(path):
    """(line number, bracket, included name) of every #include in the file."""
    out = []
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        m = INCLUDE.match(line)
        if m:
            out.append((number, m.group(1), m.group(2)))
    return out


def csrc_folder_of(name, folders):
    """The csrc folder an include "folder/x.h" names, or None."""
    head = name.split("/", 1)[0]
    return head if "/" in name and head in folders else None


def rule_of(rel):
    """The rule a file (path relative to the root, as a string) is checked by, or None."""
    parts = rel.split("/")
    if parts[0] == "csrc":
        if len(parts) == 2:
            return "model" if parts[1] in ("model.hpp", "model.cpp") else "glue"
        if parts[1] == "bench":
            return None
        if parts[1] == "include":
            return "public"
        return {"core": "core", "util": "util", "kinematics": "kinematics", "table": "table",
                "drives": "drives", "cli": "cli"}.get(parts[1], "direction")
    if parts[0] == "fmu":
        if len(parts) >= 2 and parts[1] == "runtime":
            return "fmu-runtime"
        if len(parts) >= 3 and parts[1] == "models":
            return "fmu-model"
        return None
    if parts[0] == "python" and rel.endswith((".cpp", ".hpp")):
        return "binding"
    return None


def why_not(root, rel, rule, bracket, name, folders):
    """Why the include breaks the file's rule, or None if it keeps it."""
    here = Path(rel).parent
    if ".." in Path(name).parts:
        return "an include with .. climbs out of the include paths the layers are made of"
    if bracket == '"' and THIRD_PARTY_QUOTED.fullmatch(name):
        return None  # the FMI standard's headers, quoted as the standard's own sources do
    own = "/" not in name and (root / here / name).is_file()  # a file beside it
    folder = csrc_folder_of(name, folders)
    public = name.startswith(PUBLIC) and (root / "csrc/include" / name).is_file() or \
        name.startswith("mbs/") and (root / "csrc/core/include" / name).is_file()
    if bracket == "<" and not public and folder is None and not own:
        return None  # a system or third-party header
    if rule == "core":
        if name.startswith("stewart/"):
            return "the core includes no stewart/ header"
        if public or folder == "core" or own:
            return None
        return "the core includes only core/ and mbs/ headers"
    if rule == "public":
        return None if public or own else "a public header includes only stewart/ and mbs/ headers"
    if rule == "cli":
        if public or folder == "cli" or own:
            return None
        return "a command line includes only cli/ files and the public headers"
    if rule == "binding":
        if public or own:
            return None
        return "the Python binding includes only its own files and the public headers"
    if rule in ("fmu-runtime", "fmu-model"):
        runtime = (root / "fmu/runtime" / name).is_file() and "/" not in name
        if public:
            return None
        if rule == "fmu-runtime":
            if own or name in ("config.h", "variables.def"):
                return None
            return "the FMU runtime includes of a model only config.h and variables.def"
        if own or runtime:
            return None
        return "an FMU model includes its own files, the runtime's and the public headers only"
    # the platform library (csrc/ but core, cli, include, bench)
    if public and name != "mbs/mbs.h" and name.startswith("mbs/"):
        return "the platform includes of the core only mbs/mbs.h and core/published.hpp"
    if public or own:
        return None
    if name in CORE_PUBLISHED:
        return None
    if folder == "core":
        return "the platform includes of the core only mbs/mbs.h and core/published.hpp"
    this = here.parts[1] if len(here.parts) > 1 else None
    if rule == "util":
        return None if folder == "util" else "util includes only util/ and the public headers"
    if rule == "kinematics":
        if folder in ("kinematics", "util"):
            return None
        return "kinematics includes only kinematics/, util/ and the public headers"
    if rule == "drives":
        if folder in ("drives", "kinematics", "util"):
            return None
        return "the drives include only drives/, kinematics/, util/ and the public headers"
    if rule == "table":
        if folder in ("table", "kinematics", "util"):
            return None
        return "the tables include only table/, kinematics/, util/ and the public headers"
    if rule == "model":
        if folder in SHARED:
            return None
        if folder and name == f"{folder}/{folder}_constants.hpp":
            return None
        return "the model includes of a direction only <direction>/<direction>_constants.hpp"
    if rule == "glue":
        return None  # batch.cpp: the batches of every direction, above them
    # a direction
    if folder in SHARED or folder == this or name in ("model.hpp", "batch_paths.hpp"):
        return None
    if folder:
        return f"a direction ({this}) includes no other direction's files ({folder}/)"
    return "an include that names no file of the tree"


def source_files(root):
    for top in ("csrc", "fmu", "python"):
        base = root / top
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.suffix in SOURCE_ENDINGS and path.is_file() and "__pycache__" not in path.parts:
                yield path


def check(root):
    """The breaches (rel, line, include, why) and the allow-list entries no include uses."""
    root = Path(root)
    folders = {p.name for p in (root / "csrc").iterdir() if p.is_dir()}
    breaches, used = [], set()
    for path in source_files(root):
        rel = path.relative_to(root).as_posix()
        rule = rule_of(rel)
        if rule is None:
            continue
        for number, bracket, name in includes(path):
            why = why_not(root, rel, rule, bracket, name, folders)
            if why is None:
                continue
            if (rel, name) in ALLOWED:
                used.add((rel, name))
                continue
            breaches.append((rel, number, name, why))
    stale = sorted(set(ALLOWED) - used)
    return breaches, stale


def report(root):
    breaches, stale = check(root)
    for rel, number, name, why in breaches:
        print(f"{rel}:{number}: #include \"{name}\": {why} (docs/architecture.md, "
              f"'What the build enforces'; a reasoned exception goes in EXCEPTIONS, {__file__})")
    for rel, name in stale:
        print(f"{rel}: the allow-list names #include \"{name}\", which the file no longer has: "
              f"remove the entry from EXCEPTIONS ({__file__})")
    if not breaches and not stale:
        print(f"layers kept: every include of csrc/, fmu/ and the Python binding "
              f"({len(ALLOWED)} reasoned exceptions)")
    return 1 if breaches or stale else 0


# One planted include per rule: (file to add it to, the include, words the breach must name).
PLANTED = [
    ("csrc/core/step.cpp", '#include "stewart/stewart.h"', "no stewart/ header"),
    ("csrc/core/step.cpp", '#include "kinematics/motion.hpp"', "only core/ and mbs/"),
    ("csrc/kinematics/motion.cpp", '#include "forward/branch.hpp"', "kinematics includes only"),
    ("csrc/kinematics/motion.cpp", '#include "model.hpp"', "kinematics includes only"),
    ("csrc/table/options.cpp", '#include "plant/plant_object.hpp"', "tables include only"),
    ("csrc/drives/leg_drive.cpp", '#include "model.hpp"', "drives include only"),
    ("csrc/util/range.hpp", '#include "kinematics/motion.hpp"', "util includes only"),
    ("csrc/model.hpp", '#include "forward/newton.hpp"', "only <direction>/<direction>_constants"),
    ("csrc/forward/newton.cpp", '#include "plant/plant_object.hpp"', "no other direction"),
    ("csrc/forward/newton.cpp", '#include "core/step.hpp"', "of the core only"),
    ("csrc/forward/newton.cpp", '#include <mbs/../../step.hpp>', "climbs out"),
    ("csrc/forward/newton.cpp", '#include "newton_private.hpp"', "names no file"),
    ("csrc/cli/pose_table.cpp", '#include "model.hpp"', "a command line includes only"),
    ("csrc/cli/pose_table.cpp", '#include <kinematics/frames.hpp>', "a command line includes only"),
    ("python/stewart/_core.cpp", '#include "model.hpp"', "the Python binding includes only"),
    ("csrc/include/stewart/stewart.h", '#include "model.hpp"', "a public header includes only"),
    ("fmu/runtime/values.c", '#include "step_rules.h"', "of a model only config.h"),
    ("fmu/models/plant/config.h", '#include "kinematics/motion.hpp"', "an FMU model includes"),
    ("fmu/models/plant/config.h", '#include "../inverse/outputs.h"', "climbs out"),
    ("fmu/models/plant/config.h", '#include "outputs.h"', "an FMU model includes"),
]


def self_test():
    """Each planted include is found with its rule's words, in a copy of the tree; an allow-list
    entry whose include is gone is reported; the tree itself passes."""
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "tree"
        for path in source_files(ROOT):
            target = copy / path.relative_to(ROOT)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, target)
        breaches, stale = check(copy)
        if breaches or stale:
            failures.append(f"the copy of the tree fails before any plant: {breaches} {stale}")
        for rel, line, words in PLANTED:
            target = copy / rel
            before = target.read_text()
            target.write_text(before + "\n" + line + "\n")
            found, _ = check(copy)
            target.write_text(before)
            named = [b for b in found if b[0] == rel and line.endswith(f'{b[2]}"') or
                     b[0] == rel and line.endswith(f"{b[2]}>")]
            if not named or words not in named[0][3]:
                failures.append(f"{rel}: planted {line!r} not found as '{words}' (found {found})")
        # an allowed include removed: the entry is stale
        rel, name = next(iter(ALLOWED))
        target = copy / rel
        before = target.read_text()
        target.write_text("\n".join(l for l in before.splitlines() if f'"{name}"' not in l))
        _, stale = check(copy)
        if (rel, name) not in stale:
            failures.append(f"{rel}: the allow-list entry of {name} not reported stale")
    for f in failures:
        print("FAIL", f)
    if not failures:
        print(f"the gate finds each of {len(PLANTED)} planted violations and a stale exception")
    return 1 if failures else 0


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    sys.exit(report(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT))
