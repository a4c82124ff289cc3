"""Windows on a display without a window manager (the tests' Xvfb) stack in the order they
were mapped: the joint slider window and RViz both open at 0,0, and when RViz maps last
(a loaded machine starts it later than usual) it covers the sliders for good. The test
raises the slider window, as a person would click it, through libX11 (no xdotool)."""

from __future__ import annotations

import ctypes
import ctypes.util
import functools


class _ClassHint(ctypes.Structure):
    # void pointers, not c_char_p: Xlib allocated them, and they go back through XFree
    _fields_ = [("res_name", ctypes.c_void_p), ("res_class", ctypes.c_void_p)]


@functools.cache
def _x11():
    name = ctypes.util.find_library("X11")
    if name is None:
        return None
    x11 = ctypes.cdll.LoadLibrary(name)
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XDefaultRootWindow.restype = ctypes.c_ulong
    x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    x11.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_ulong),
                               ctypes.POINTER(ctypes.c_ulong),
                               ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                               ctypes.POINTER(ctypes.c_uint)]
    x11.XGetClassHint.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                  ctypes.POINTER(_ClassHint)]
    x11.XRaiseWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    x11.XFree.argtypes = [ctypes.c_void_p]
    x11.XFlush.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    return x11


def raise_windows(display: str, program: str) -> int:
    """Raise every top-level window of ``program`` (its WM_CLASS: a title may be in an
    encoding XFetchName refuses, as "Node: /joint_state_publisher_gui — Joint State
    Publisher" is); how many."""
    x11 = _x11()
    if x11 is None:
        return 0
    handle = x11.XOpenDisplay(display.encode())
    if not handle:
        return 0
    raised = 0
    try:
        root, parent = ctypes.c_ulong(), ctypes.c_ulong()
        children, count = ctypes.POINTER(ctypes.c_ulong)(), ctypes.c_uint()
        if not x11.XQueryTree(handle, x11.XDefaultRootWindow(handle), ctypes.byref(root),
                              ctypes.byref(parent), ctypes.byref(children),
                              ctypes.byref(count)):
            return 0
        windows = [children[i] for i in range(count.value)]
        if children:
            x11.XFree(children)
        for window in windows:
            hint = _ClassHint()
            if not x11.XGetClassHint(handle, window, ctypes.byref(hint)):
                continue
            names = [ctypes.string_at(p) for p in (hint.res_name, hint.res_class) if p]
            for pointer in (hint.res_name, hint.res_class):
                if pointer:
                    x11.XFree(pointer)
            if program.encode() in names:
                x11.XRaiseWindow(handle, window)
                raised += 1
        x11.XFlush(handle)
    finally:
        x11.XCloseDisplay(handle)
    return raised
