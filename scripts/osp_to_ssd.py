#!/usr/bin/env python3
"""Writes the SSP system structure (SystemStructure.ssd, SSP 1.0) of an OSP system structure
(OspSystemStructure.xml): the same components, initial values and connections, for masters that
read SSP (ecos, OMSimulator, fmpy.ssp). The FMUs are named resources/<file>.fmu, as an .ssp
archive holds them; the initial values are one parameter set, "initialValues", bound inline to
each component. What masters need beyond that:
  * a start value for every input connector: the value its source has once every unit is
    initialised (found by initialising the OSP file's FMUs with fmpy until no value changes), so
    that no master starts an input at 0 (a pose at z = 0 is singular: the inverse unit refuses it);
  * a default experiment with the run's stop time;
  * OMSimulator's own annotation of the system (its fixed-step master and step size), without
    which OMSimulator does not load the system.

usage: osp_to_ssd.py [--stop-time 12] OSP.xml SSD
       (the build packs scenes/closed_loop's into build/ssp/<v>/)
"""
import argparse
import pathlib
import xml.etree.ElementTree as ET

OSP = "http://opensimulationplatform.com/MSMI/OSPSystemStructure"
SSD = "http://ssp-standard.org/SSP1/SystemStructureDescription"
SSC = "http://ssp-standard.org/SSP1/SystemStructureCommon"
SSV = "http://ssp-standard.org/SSP1/SystemStructureParameterValues"
OMS = "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd"
PARAMETER_SET = "initialValues"
STOP_TIME = 12.0  # [s]: the combined cue's duration (scenes/combined.json), docs/closed-loop.md


def fmu_of(osp_path, simulator):
    """The FMU of an OSP simulator (its source, relative to the OSP file)."""
    return (osp_path.parent / simulator.get("source")).resolve()


def initial_values(simulator, ns):
    """{variable: value} of an OSP simulator's initial values."""
    values = {}
    for value in simulator.findall("o:InitialValues/o:InitialValue", ns):
        (typed,) = list(value)
        kind = typed.tag.split("}")[1]
        text = typed.get("value")
        values[value.get("variable")] = (float(text) if kind == "Real" else
                                         text if kind == "String" else int(text))
    return values


def initialised_outputs(fmu, name, values, outputs):
    """The outputs of an FMI 2 unit initialised with values (fmpy)."""
    import fmpy
    from fmpy.fmi2 import FMU2Slave
    description = fmpy.read_model_description(str(fmu))
    refs = {v.name: (v.valueReference, v.type) for v in description.modelVariables}
    unit = FMU2Slave(guid=description.guid, unzipDirectory=fmpy.extract(str(fmu)),
                     modelIdentifier=description.coSimulation.modelIdentifier, instanceName=name)
    unit.instantiate()
    try:
        unit.setupExperiment(startTime=0.0)
        for variable, value in values.items():
            ref, kind = refs[variable]
            setter = {"Real": unit.setReal, "String": unit.setString}.get(kind, unit.setInteger)
            setter([ref], [value])
        unit.enterInitializationMode()
        unit.exitInitializationMode()
        return {o: unit.getReal([refs[o][0]])[0] for o in outputs}
    finally:
        unit.terminate()
        unit.freeInstance()


def unit_connectors(fmu, connected):
    """(name, kind, SSP type) of a unit's connectors, in its model description's order: the
    connected inputs and every output (a master shows its connectors' values: fmpy.ssp's result
    has nothing else)."""
    import fmpy
    connectors = []
    for variable in fmpy.read_model_description(str(fmu)).modelVariables:
        if variable.causality == "output" or connected.get(variable.name) == "input":
            kind_type = "Real" if variable.type in ("Real", "Float64") else "Integer"
            connectors.append((variable.name, variable.causality, kind_type))
    return connectors


def input_starts(osp_path, osp, connections, ns):
    """{(simulator, input): value}: each connected input's source value once every unit is
    initialised with its initial values and these inputs, in passes until no value changes (a
    unit's outputs may depend on inputs another unit's initialisation gives)."""
    simulators = osp.findall("o:Simulators/o:Simulator", ns)
    starts = {}
    for _ in range(len(simulators) + 1):
        outputs = {}
        for simulator in simulators:
            name = simulator.get("name")
            values = initial_values(simulator, ns)
            values.update({v: x for (s, v), x in starts.items() if s == name})
            wanted = sorted({v for s, v, _, _ in connections if s == name})
            found = initialised_outputs(fmu_of(osp_path, simulator), name, values, wanted)
            outputs.update({(name, v): x for v, x in found.items()})
        new = {(end, end_name): outputs[(start, start_name)]
               for start, start_name, end, end_name in connections}
        if new == starts:
            return starts
        starts = new
    raise RuntimeError(f"{osp_path}: the start values of the inputs do not settle")


def convert(osp_path: pathlib.Path, stop_time: float = STOP_TIME) -> str:
    """The SSD text of the OSP structure at osp_path (its FMUs initialised for the inputs' start
    values), running from its start time to stop_time."""
    osp = ET.parse(osp_path).getroot()
    ns = {"o": OSP}
    kinds: dict[str, dict[str, str]] = {}
    connections = []
    for connection in osp.findall("o:Connections/o:VariableConnection", ns):
        start, end = connection.findall("o:Variable", ns)
        connections.append((start.get("simulator"), start.get("name"), end.get("simulator"), end.get("name")))
        kinds.setdefault(start.get("simulator"), {})[start.get("name")] = "output"
        kinds.setdefault(end.get("simulator"), {})[end.get("name")] = "input"
    starts = input_starts(osp_path, osp, connections, ns)
    for prefix, uri in (("ssd", SSD), ("ssc", SSC), ("ssv", SSV), ("oms", OMS)):
        ET.register_namespace(prefix, uri)
    name = osp_path.parent.name
    root = ET.Element(f"{{{SSD}}}SystemStructureDescription", {"version": "1.0", "name": name})
    system = ET.SubElement(root, f"{{{SSD}}}System", {"name": name})
    elements = ET.SubElement(system, f"{{{SSD}}}Elements")
    for simulator in osp.findall("o:Simulators/o:Simulator", ns):
        simulator_name = simulator.get("name")
        component = ET.SubElement(elements, f"{{{SSD}}}Component", {
            "name": simulator_name, "type": "application/x-fmu-sharedlibrary",
            "source": f"resources/{pathlib.PurePosixPath(simulator.get('source')).name}"})
        connectors = ET.SubElement(component, f"{{{SSD}}}Connectors")
        for variable, kind, kind_type in unit_connectors(fmu_of(osp_path, simulator),
                                                         kinds.get(simulator_name, {})):
            connector = ET.SubElement(connectors, f"{{{SSD}}}Connector",
                                      {"name": variable, "kind": kind})
            ET.SubElement(connector, f"{{{SSC}}}{kind_type}")
        values = [(value.get("variable"), typed.tag.split("}")[1], typed.get("value"))
                  for value in simulator.findall("o:InitialValues/o:InitialValue", ns)
                  for typed in value]
        values += [(variable, "Real", repr(value)) for (s, variable), value in starts.items()
                   if s == simulator_name]
        if values:
            binding = ET.SubElement(ET.SubElement(component, f"{{{SSD}}}ParameterBindings"),
                                    f"{{{SSD}}}ParameterBinding")
            parameter_set = ET.SubElement(ET.SubElement(binding, f"{{{SSD}}}ParameterValues"),
                                          f"{{{SSV}}}ParameterSet",
                                          {"version": "1.0", "name": PARAMETER_SET})
            parameters = ET.SubElement(parameter_set, f"{{{SSV}}}Parameters")
            for variable, kind, value in values:
                parameter = ET.SubElement(parameters, f"{{{SSV}}}Parameter", {"name": variable})
                ET.SubElement(parameter, f"{{{SSV}}}{kind}", {"value": value})
    links = ET.SubElement(system, f"{{{SSD}}}Connections")
    for start, start_name, end, end_name in connections:
        ET.SubElement(links, f"{{{SSD}}}Connection", {"startElement": start, "startConnector": start_name,
                                                      "endElement": end, "endConnector": end_name})
    oms_annotation(system, osp.findtext("o:BaseStepSize", None, ns))
    start_time = osp.findtext("o:StartTime", "0.0", ns)
    ET.SubElement(root, f"{{{SSD}}}DefaultExperiment", {"startTime": start_time,
                                                        "stopTime": repr(float(stop_time))})
    ET.indent(root)
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<!-- Written by scripts/osp_to_ssd.py from '
            f'{osp_path.name}: edit that file and rerun. -->\n' + ET.tostring(root, "unicode") + "\n")


def oms_annotation(system, step_size):
    """OMSimulator's annotation of the system: its fixed-step master at the OSP's base step."""
    annotation = ET.SubElement(ET.SubElement(system, f"{{{SSD}}}Annotations"),
                               f"{{{SSC}}}Annotation", {"type": "org.openmodelica"})
    information = ET.SubElement(ET.SubElement(annotation, f"{{{OMS}}}Annotations"),
                                f"{{{OMS}}}SimulationInformation")
    ET.SubElement(information, f"{{{OMS}}}FixedStepMaster",
                  {"description": "oms-ma", "stepSize": step_size, "absoluteTolerance": "0.0001",
                   "relativeTolerance": "0.0001"})


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stop-time", type=float, default=STOP_TIME,
                        help="the default experiment's stop time [s] (default %(default)s)")
    parser.add_argument("osp", type=pathlib.Path)
    parser.add_argument("ssd", type=pathlib.Path)
    args = parser.parse_args()
    args.ssd.write_text(convert(args.osp, args.stop_time))


if __name__ == "__main__":
    main()
