#!/usr/bin/env python3
"""Writes the closed loop of docs/closed-loop.md for the machine of a platform file: the
closed-loop SSP archive with a parameter set of that machine, in SSV files (SSP 1.0 System
Structure Parameter Values), for SSP masters (ecos, OMSimulator).

The parameter set is named after the file (e.g. "rubin_camera_hexapod"); one SSV file per unit,
resources/NAME.UNIT.ssv, bound to the unit by the SSD: the platform's parameters for the inverse
unit and the plant (stewart.fmu_start_values), the combined cue moved to the machine's home
(scaled to its axis ranges with --scale-to-ranges: stewart.scenes.on_platform) for the scene
player, the PD gains of scripts/closed_loop.py's machine_gains for the controller, the plant
started on the cue, and a start value for every connected input (its source's once the units
are initialised, as scripts/osp_to_ssd.py finds them). The archive is the package's
closed_loop.ssp (stewart.ssp_path) with these added: select the set by its name (ecos:
init(parameter_set=NAME)); the thesis' set "initialValues" stays in it.

usage: machine_ssp.py PLATFORM.json OUT.ssp [--fmi 2.0|3.0] [--scale-to-ranges] [--scene combined]
                      [--osp OUT.xml]

A scene with a move (scenes/move_line.json): the move is planned on the machine (stewart.move)
and written next to OUT.ssp as OUT_trajectory.csv, which the scene player reads by its absolute
path (its String parameter trajectory_file): move the archive freely, but keep that file where it
is (or write the set again).

--osp also writes the same closed loop as an OSP system structure for libcosim
(CosimExecution.from_osp_config_file): the machine's values as its initial values, the package's
FMI 2 units by their absolute paths.
"""
import argparse
import pathlib
import tempfile
import xml.etree.ElementTree as ET
import zipfile

import closed_loop
import osp_to_ssd
import scenes
import stewart

ROOT = pathlib.Path(__file__).resolve().parents[1]
OSP_FILE = ROOT / "scenes" / "closed_loop" / "OspSystemStructure.xml"
POSE = ("x", "y", "z", "roll", "pitch", "yaw")


def machine_values(platform, scene, trajectory_path=None):
    """{unit: {variable: value}}: the closed loop's initial values for the machine (before the
    input connectors' start values). A scene with a move: the move planned on the machine at
    the scene's step, written to trajectory_path for the scene player (scenes.player_values)."""
    _, cue, cue_dot, _ = scenes.trajectory(scene, platform)
    kp, kd = closed_loop.machine_gains(platform)
    plant = stewart.fmu_start_values(platform, model="StewartPlant")
    plant.update({f"{p}0": float(v) for p, v in zip(POSE, cue[0])})
    plant.update({f"{p}_dot0": float(v) for p, v in zip(POSE, cue_dot[0])})
    if "move" in scene and trajectory_path is None:
        raise ValueError("a scene with a move needs a trajectory file to write for the player")
    return {
        "scene": scenes.player_values(scene, trajectory_path, platform),
        "inverse": {"fidelity": 2, "derivatives": 1, **stewart.fmu_start_values(platform)},
        "controller": {"kp": kp, "kd": kd},
        "plant": {"fidelity": 2, **plant},
    }


def typed(value):
    """(SSP type, text) of a value: integers as Integer, text as String, every other number as
    Real."""
    import numpy as np
    if isinstance(value, str):
        return "String", value
    if isinstance(value, (int, np.integer)):
        return "Integer", str(int(value))
    return "Real", repr(float(value))


def osp_structure(values, fmus):
    """The OSP structure of scenes/closed_loop with these initial values and the FMUs of the
    folder fmus (FMI 2: the start values are found with them), as an ElementTree root."""
    ns = {"o": osp_to_ssd.OSP}
    ET.register_namespace("", osp_to_ssd.OSP)
    root = ET.parse(OSP_FILE).getroot()
    for simulator in root.findall("o:Simulators/o:Simulator", ns):
        name = simulator.get("name")
        simulator.set("source", str(fmus / pathlib.PurePosixPath(simulator.get("source")).name))
        initial = simulator.find("o:InitialValues", ns)
        for old in list(initial):
            initial.remove(old)
        for variable, value in values[name].items():
            entry = ET.SubElement(initial, f"{{{osp_to_ssd.OSP}}}InitialValue",
                                  {"variable": variable})
            kind, text = typed(value)
            ET.SubElement(entry, f"{{{osp_to_ssd.OSP}}}{kind}", {"value": text})
    return root


def parameter_set(platform, scene, name, fmus, osp_out=None, trajectory_path=None):
    """{unit: SSV text}: each unit's initial values and input start values, the set `name`;
    the OSP structure of the machine's values written to osp_out if given; a move's trajectory
    to trajectory_path (machine_values)."""
    values = machine_values(platform, scene, trajectory_path)
    if osp_out is not None:
        ET.ElementTree(osp_structure(values, fmus)).write(osp_out, encoding="utf-8",
                                                          xml_declaration=True)
    with tempfile.TemporaryDirectory() as folder:
        osp_path = pathlib.Path(folder) / "OspSystemStructure.xml"
        ET.ElementTree(osp_structure(values, fmus)).write(osp_path, encoding="utf-8",
                                                          xml_declaration=True)
        osp = ET.parse(osp_path).getroot()
        ns = {"o": osp_to_ssd.OSP}
        connections = [tuple(v.get(k) for v in c.findall("o:Variable", ns) for k in
                             ("simulator", "name"))
                       for c in osp.findall("o:Connections/o:VariableConnection", ns)]
        starts = osp_to_ssd.input_starts(osp_path, osp, connections, ns)
    for (unit, variable), value in starts.items():
        values[unit][variable] = value
    return {unit: ssv_text(name, unit_values) for unit, unit_values in values.items()}


def ssv_text(name, values):
    """An SSV file: the parameter set `name` of {variable: value}."""
    ET.register_namespace("ssv", osp_to_ssd.SSV)
    root = ET.Element(f"{{{osp_to_ssd.SSV}}}ParameterSet", {"version": "1.0", "name": name})
    parameters = ET.SubElement(root, f"{{{osp_to_ssd.SSV}}}Parameters")
    for variable, value in values.items():
        parameter = ET.SubElement(parameters, f"{{{osp_to_ssd.SSV}}}Parameter",
                                  {"name": variable})
        kind, text = typed(value)
        ET.SubElement(parameter, f"{{{osp_to_ssd.SSV}}}{kind}", {"value": text})
    ET.indent(root)
    return ('<?xml version="1.0" encoding="UTF-8"?>\n'
            '<!-- Written by scripts/machine_ssp.py from a platform file -->\n' +
            ET.tostring(root, "unicode") + "\n")


def bound_ssd(ssd_text, name):
    """The SSD with every unit also bound to its SSV file, resources/NAME.UNIT.ssv."""
    ns = {"ssd": osp_to_ssd.SSD}
    for prefix, uri in (("ssd", osp_to_ssd.SSD), ("ssc", osp_to_ssd.SSC),
                        ("ssv", osp_to_ssd.SSV), ("oms", osp_to_ssd.OMS)):
        ET.register_namespace(prefix, uri)
    root = ET.fromstring(ssd_text)
    for component in root.findall("ssd:System/ssd:Elements/ssd:Component", ns):
        bindings = component.find("ssd:ParameterBindings", ns)
        if bindings is None:
            bindings = ET.SubElement(component, f"{{{osp_to_ssd.SSD}}}ParameterBindings")
        ET.SubElement(bindings, f"{{{osp_to_ssd.SSD}}}ParameterBinding",
                      {"source": f"resources/{name}.{component.get('name')}.ssv"})
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"


def write(platform_file, out, version="2.0", scale_to_ranges=False, scene="combined",
          fmus=None, osp_out=None):
    """Writes OUT.ssp for the platform file (and the OSP structure to osp_out if given);
    returns the parameter set's name.
    fmus: the FMI 2 units to find the start values with (default: the package's)."""
    platform_file, out = pathlib.Path(platform_file), pathlib.Path(out)
    platform = stewart.Platform.from_file(platform_file)
    moved = stewart.scenes.on_platform(scenes.load(scene), platform,
                                       scale_to_ranges=scale_to_ranges)
    name = platform_file.stem
    fmus = pathlib.Path(fmus) if fmus else stewart.fmu_path("2.0").parent
    files = parameter_set(platform, moved, name, fmus, osp_out,
                          out.with_name(f"{out.stem}_trajectory.csv"))
    archive = stewart.ssp_path(version)
    with zipfile.ZipFile(archive) as source, \
            zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "SystemStructure.ssd":
                data = bound_ssd(data.decode("utf-8"), name).encode("utf-8")
            target.writestr(item, data)
        for unit, text in files.items():
            target.writestr(f"resources/{name}.{unit}.ssv", text)
    return name


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("platform", type=pathlib.Path)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--fmi", default="2.0", choices=stewart.FMI_VERSIONS)
    parser.add_argument("--scale-to-ranges", action="store_true")
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--osp", type=pathlib.Path, help="also write the OSP structure here")
    args = parser.parse_args()
    try:
        name = write(args.platform, args.out, args.fmi, args.scale_to_ranges, args.scene,
                     osp_out=args.osp)
    except ValueError as e:  # SceneError, stewart.MoveError: the message names the cause
        raise SystemExit(f"machine_ssp: {e}") from None
    print(f"machine_ssp: wrote {args.out} (parameter set {name!r})")
    trajectory = args.out.with_name(f"{args.out.stem}_trajectory.csv")
    if "move" in scenes.load(args.scene):
        print(f"machine_ssp: the scene player plays {trajectory.resolve()} (keep it there)")


if __name__ == "__main__":
    main()
