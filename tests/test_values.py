"""mobile_car.values.Value: the frozen dataclass's behaviour (==, hash, repr, no assignment,
copy and pickle) for the value classes every run makes, without compiling methods; and
LoadOptions.replace, which makes a variant as dataclasses.replace did."""

from __future__ import annotations

import copy
import pickle

import pytest

from mobile_car.check.diagnostics import Diagnostic
from mobile_car.check.urdf_vocabulary import ORIGIN, Spec
from mobile_car.sim.diagnostics import SimDiagnostic
from mobile_car.values import FrozenError


def test_equal_by_class_and_fields_hashed_by_fields():
    one = Diagnostic("E104", "r.urdf", 3, "m")
    assert one == Diagnostic("E104", "r.urdf", 3, "m")
    assert one != Diagnostic("E104", "r.urdf", 4, "m")
    assert one != SimDiagnostic("E104", "r.urdf", 3, "m")  # another class: never equal
    assert one != ("E104", "r.urdf", 3, "m")
    assert len({one, Diagnostic(rule="E104", file="r.urdf", line=3, message="m")}) == 1


def test_shown_as_a_dataclass_is():
    assert repr(Diagnostic("E104", "r.urdf", None, "m")) == \
        "Diagnostic(rule='E104', file='r.urdf', line=None, message='m')"


def test_no_field_assigned_or_deleted():
    one = Diagnostic("E104", "r.urdf", 3, "m")
    with pytest.raises(AttributeError):
        one.line = 4
    with pytest.raises(FrozenError):
        del one.rule
    with pytest.raises(AttributeError):
        one.other = 1  # no __dict__ either
    assert one.line == 3


def test_copied_and_pickled_through_init():
    one = SimDiagnostic("W304", "r.urdf", 3, "m")
    for again in (copy.copy(one), copy.deepcopy(one), pickle.loads(pickle.dumps(one))):
        assert again == one and again.__class__ is SimDiagnostic
    spec = pickle.loads(pickle.dumps(ORIGIN))
    assert spec == ORIGIN and spec.attrs_ok(["xyz"]) and not spec.attrs_ok(["x"])


def test_wrong_arguments_refused():
    with pytest.raises(TypeError):
        Diagnostic("E104", "r.urdf", 3)
    assert Spec().children == {} and Spec().children is not Spec().children


def test_load_options_replace_makes_a_variant_and_refuses_an_unknown_field():
    from mobile_car.load.robot import LoadOptions

    options = LoadOptions({"a": "1"}, [], through_xacro=False)
    variant = options.replace(through_xacro=True)
    assert (variant.through_xacro, variant.mappings, options.through_xacro) == \
        (True, {"a": "1"}, False)
    with pytest.raises(TypeError, match="through_xacr"):
        options.replace(through_xacr=True)
