"""mcar: build, check and render the mobile car's URDF/xacro description without ROS.

The library never prints, never exits and never imports click: it returns values and
raises the exceptions of :mod:`mobile_car.errors`; the ``cli`` layer turns those into
messages and exit codes.
"""

__version__ = "0.1.0"
