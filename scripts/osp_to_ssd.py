#!/usr/bin/env python3
"""Writes the SSP system structure (SystemStructure.ssd, SSP 1.0) of an OSP system structure
(OspSystemStructure.xml): the same components, initial values and connections, for masters that
read SSP (ecos, OMSimulator, fmpy.ssp). The FMUs are named resources/<file>.fmu, as an .ssp
archive holds them; the initial values are one parameter set, "initialValues", bound inline to
each component.

usage: osp_to_ssd.py OSP.xml SSD    (the build packs scenes/closed_loop's into build/ssp/<v>/)
"""
import argparse
import pathlib
import xml.etree.ElementTree as ET

OSP = "http://opensimulationplatform.com/MSMI/OSPSystemStructure"
SSD = "http://ssp-standard.org/SSP1/SystemStructureDescription"
SSC = "http://ssp-standard.org/SSP1/SystemStructureCommon"
SSV = "http://ssp-standard.org/SSP1/SystemStructureParameterValues"
PARAMETER_SET = "initialValues"


def convert(osp_path: pathlib.Path) -> str:
    """The SSD text of the OSP structure at osp_path."""
    osp = ET.parse(osp_path).getroot()
    ns = {"o": OSP}
    kinds: dict[str, dict[str, str]] = {}
    connections = []
    for connection in osp.findall("o:Connections/o:VariableConnection", ns):
        start, end = connection.findall("o:Variable", ns)
        connections.append((start.get("simulator"), start.get("name"), end.get("simulator"), end.get("name")))
        kinds.setdefault(start.get("simulator"), {})[start.get("name")] = "output"
        kinds.setdefault(end.get("simulator"), {})[end.get("name")] = "input"
    for prefix, uri in (("ssd", SSD), ("ssc", SSC), ("ssv", SSV)):
        ET.register_namespace(prefix, uri)
    name = osp_path.parent.name
    root = ET.Element(f"{{{SSD}}}SystemStructureDescription", {"version": "1.0", "name": name})
    system = ET.SubElement(root, f"{{{SSD}}}System", {"name": name})
    elements = ET.SubElement(system, f"{{{SSD}}}Elements")
    for simulator in osp.findall("o:Simulators/o:Simulator", ns):
        component = ET.SubElement(elements, f"{{{SSD}}}Component", {
            "name": simulator.get("name"), "type": "application/x-fmu-sharedlibrary",
            "source": f"resources/{pathlib.PurePosixPath(simulator.get('source')).name}"})
        connectors = ET.SubElement(component, f"{{{SSD}}}Connectors")
        for variable, kind in kinds.get(simulator.get("name"), {}).items():
            connector = ET.SubElement(connectors, f"{{{SSD}}}Connector", {"name": variable, "kind": kind})
            ET.SubElement(connector, f"{{{SSC}}}Real")
        values = simulator.findall("o:InitialValues/o:InitialValue", ns)
        if values:
            binding = ET.SubElement(ET.SubElement(component, f"{{{SSD}}}ParameterBindings"),
                                    f"{{{SSD}}}ParameterBinding")
            parameter_set = ET.SubElement(ET.SubElement(binding, f"{{{SSD}}}ParameterValues"),
                                          f"{{{SSV}}}ParameterSet",
                                          {"version": "1.0", "name": PARAMETER_SET})
            parameters = ET.SubElement(parameter_set, f"{{{SSV}}}Parameters")
            for value in values:
                (typed,) = list(value)
                parameter = ET.SubElement(parameters, f"{{{SSV}}}Parameter", {"name": value.get("variable")})
                ET.SubElement(parameter, f"{{{SSV}}}{typed.tag.split('}')[1]}", {"value": typed.get("value")})
    links = ET.SubElement(system, f"{{{SSD}}}Connections")
    for start, start_name, end, end_name in connections:
        ET.SubElement(links, f"{{{SSD}}}Connection", {"startElement": start, "startConnector": start_name,
                                                      "endElement": end, "endConnector": end_name})
    start_time = osp.findtext("o:StartTime", "0.0", ns)
    ET.SubElement(root, f"{{{SSD}}}DefaultExperiment", {"startTime": start_time})
    ET.indent(root)
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<!-- Written by scripts/osp_to_ssd.py from '
            f'{osp_path.name}: edit that file and rerun. -->\n' + ET.tostring(root, "unicode") + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("osp", type=pathlib.Path)
    parser.add_argument("ssd", type=pathlib.Path)
    args = parser.parse_args()
    args.ssd.write_text(convert(args.osp))


if __name__ == "__main__":
    main()
