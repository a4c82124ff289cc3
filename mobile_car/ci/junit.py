"""JUnit XML, the report format CI servers (GitLab, Jenkins, GitHub test reporters) read.

One ``<testcase>`` per file and step: classname ``mcar.<step>``, name the file (the sim
step: one per scenario and one for its lint, classname ``mcar.sim.<scenario>``, as
``mcar sim --format junit`` makes them); a failed step has a ``<failure>`` whose message
is its first problem and whose text lists every problem as
``FILE:LINE: severity: message [RULE]``; a skipped step has ``<skipped>``.
With ``mcar ci --against REV`` every testcase of a file has the property ``mcar.diff``:
what changed in that robot since REV ("3 changes", "no change", ...).
"""

from __future__ import annotations

from xml.etree import ElementTree as ET

from ..sim.junit import junit_case, junit_document
from .pipeline import CiItem


def junit_report(items: list[CiItem], suite: str = "mcar ci") -> str:
    cases = [(item, step, case) for item in items for step in item.steps
             for case in (step.cases or [None])]
    failures = sum(1 for case in cases if _status(case) == "failed")
    skipped = sum(1 for case in cases if _status(case) == "skipped")
    seconds = sum(step.seconds for item in items for step in item.steps)
    root = ET.Element("testsuites", tests=str(len(cases)), failures=str(failures),
                      errors="0", skipped=str(skipped), time=f"{seconds:.3f}")
    testsuite = ET.SubElement(root, "testsuite", name=suite, tests=str(len(cases)),
                              failures=str(failures), errors="0", skipped=str(skipped),
                              time=f"{seconds:.3f}")
    for item, step, sub in cases:
        if sub is not None:  # the step's time is shared evenly by its testcases
            case = junit_case(testsuite, sub, classname=f"mcar.{step.name}.{sub['name']}",
                              name=item.label, file=str(item.source),
                              time=f"{step.seconds / len(step.cases):.3f}")
            if item.diff is not None:  # properties come first in a testcase
                properties = ET.Element("properties")
                ET.SubElement(properties, "property", name="mcar.diff", value=item.diff)
                case.insert(0, properties)
            continue
        case = ET.SubElement(testsuite, "testcase", classname=f"mcar.{step.name}",
                             name=item.label, file=str(item.source), time=f"{step.seconds:.3f}")
        if item.diff is not None:
            properties = ET.SubElement(case, "properties")
            ET.SubElement(properties, "property", name="mcar.diff", value=item.diff)
        if step.status == "failed":
            failure = ET.SubElement(case, "failure", message=step.message, type=step.name)
            failure.text = "\n".join(d.text() for d in step.diagnostics) or step.message
        elif step.status == "skipped":
            ET.SubElement(case, "skipped", message=step.message)
        elif step.diagnostics:  # warnings of a passed (non-strict) check
            ET.SubElement(case, "system-out").text = "\n".join(d.text() for d in step.diagnostics)
    return junit_document(root)


def _status(entry) -> str:
    _item, step, sub = entry
    return sub["status"] if sub is not None else step.status
