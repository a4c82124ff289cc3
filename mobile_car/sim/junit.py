"""A scenario as a JUnit ``<testcase>``, shared by ``mcar sim --format junit`` and
``mcar ci`` (which replays recorded cases, so this imports nothing of the engine)."""

from __future__ import annotations

from xml.etree import ElementTree as ET

from ..names import shown, shown_lines


def junit_case(parent, case: dict, **attributes):
    """One ``<testcase>`` under ``parent`` of a case dict (name, status, message, text), as
    ``mobile_car.sim.report.junit_cases`` makes them."""
    element = ET.SubElement(parent, "testcase", **attributes)
    status, message, body = case["status"], case["message"], case["text"]
    if status == "failed":
        ET.SubElement(element, "failure", message=message,
                      type=case["name"]).text = body or message
    elif status == "skipped":
        ET.SubElement(element, "skipped", message=message)
    if body and status != "failed":
        ET.SubElement(element, "system-out").text = body
    return element


def junit_document(root) -> str:
    """The report as text, names and messages escaped first (mobile_car.names): a control
    character in a file or robot name would make the XML ill-formed (XML 1.0 has no
    ESC, not even as ``&#27;``) and reach a terminal raw."""
    for element in root.iter():
        element.attrib.update({key: shown(value) for key, value in element.attrib.items()})
        if element.text:
            element.text = shown_lines(element.text)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
