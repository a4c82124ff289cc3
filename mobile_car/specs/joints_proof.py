"""MuJoCo's proof of a ``joints.<joint>.gravity`` figure: the robot put in the joint's
worst pose and simulated for HOLD_SECONDS, every other joint locked there (the model's
``mcar_hold_<joint>`` equalities: :func:`mobile_car.sim.model.jointed_model`), the joint
itself held by a servo of its own (a stiff, critically damped spring at the pose: a
BAND_HZ response on what it carries). Once still, the servo's force is what gravity asks
of the joint, measured by stepping the physics rather than by the formula the figure
came from (``qfrc_bias``); the two agree within TOLERANCE. Joint limits are off for the
run: a joint at its limit would otherwise lean on it, and its servo would carry less.
"""

from __future__ import annotations

import math

from .figures import Proof

HOLD_SECONDS = 0.3
TIMESTEP = 0.0005   # s: the locks' time constant is at least twice it
HOLD_SOLREF = (0.002, 1.0)  # the locks: stiff, critically damped
BAND_HZ = 20.0
TOLERANCE = 0.01    # of the figure
FLOOR = 1e-6        # N or N·m per kg carried times g: a load of 0 is proven by ~0


def held_load(search, name: str, pose: list, load: float, unit: str) -> Proof:
    """``search``: the :class:`~mobile_car.specs.joints.PoseSearch` that found ``pose``
    [(joint, position, kind)] and ``load`` for joint ``name``."""
    import numpy as np

    mj, model = search.mj, search.model
    data = mj.MjData(model)
    joint = model.joint(name).id
    dof, address = int(model.jnt_dofadr[joint]), int(model.jnt_qposadr[joint])
    search.pose(data, {j: value for j, value, _kind in pose})
    target = float(data.qpos[address])
    kept = (model.opt.timestep, model.opt.disableflags, model.eq_data.copy(),
            model.eq_solref.copy())
    try:
        model.opt.timestep = TIMESTEP
        model.opt.disableflags |= int(mj.mjtDisableBit.mjDSBL_LIMIT)
        _lock_all_but(mj, model, data, name, search.followers)
        mj.mj_forward(model, data)
        unit_vector, row = np.zeros(model.nv), np.zeros(model.nv)
        unit_vector[dof] = 1.0
        mj.mj_mulM(model, data, row, unit_vector)
        inertia = float(row[dof])  # its own, all beyond it moving with it
        omega = 2 * math.pi * BAND_HZ
        stiffness, damping = inertia * omega ** 2, 2 * inertia * omega
        for _ in range(round(HOLD_SECONDS / TIMESTEP)):
            data.qfrc_applied[dof] = (-stiffness * (data.qpos[address] - target)
                                      - damping * data.qvel[dof])
            mj.mj_step(model, data)
        measured = abs(stiffness * float(data.qpos[address] - target))
        drift = abs(float(data.qpos[address]) - target)
    finally:
        model.opt.timestep, model.opt.disableflags = kept[0], kept[1]
        model.eq_data[:], model.eq_solref[:] = kept[2], kept[3]
    floor = FLOOR * search.carried(name) * 9.81
    agrees = abs(measured - load) <= TOLERANCE * load + floor
    moved = f"{drift * 1000:.2g} mm" if unit == "N" else f"{math.degrees(drift):.2g}°"
    return Proof(measured, agrees, f"{TOLERANCE:.0%}",
                 f"MuJoCo held it in that pose for {HOLD_SECONDS:g} s, the other joints "
                 f"locked, with a servo on it alone: {measured:.4g} {unit} ({moved} off "
                 "the pose)")


def _lock_all_but(mj, model, data, name: str, followers: dict) -> None:
    """Every hold on but ``name``'s and its followers' (their <mimic> moves them with
    it), each at the joint's position in ``data``."""
    for index in range(model.neq):
        held = model.eq(index).name.removeprefix("mcar_hold_")
        if held == model.eq(index).name:
            continue  # the importer's own (a <mimic>)
        on = held != name and followers.get(held, (None,))[0] != name
        data.eq_active[index] = on
        if on:
            joint = model.joint(held).id
            model.eq_data[index][:5] = [data.qpos[model.jnt_qposadr[joint]], 0, 0, 0, 0]
            model.eq_solref[index] = HOLD_SOLREF
