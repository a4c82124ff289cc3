"""A scenario as a JUnit ``<testcase>``, shared by ``mcar sim --format junit`` and
``mcar ci`` (which replays recorded cases, so this imports nothing of the engine)."""

from __future__ import annotations

from xml.etree import ElementTree as ET


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
