"""What a running ROS 1 graph says about the robot, as JSON on stdout; run by Debian's
python3 (rospy, tf2_ros), never by the tests' virtualenv, which has no ROS.

    /usr/bin/python3 tf_probe.py TIMEOUT ROOT FRAME...

Waits, at most TIMEOUT seconds in all, for the master, the robot_description parameter
and the transform ROOT -> FRAME of every FRAME. Prints {"description": the parameter,
"topics": {topic: [publisher node]}, "tf": [child frames seen on /tf], "tf_static":
[...], "transforms": {FRAME: [x, y, z, qx, qy, qz, qw] (m, unit quaternion) or null
when none came in time}}.
"""

import json
import sys
import time

import rosgraph
import rospy
import tf2_ros
from tf2_msgs.msg import TFMessage


def main(timeout, root, frames):
    deadline = time.monotonic() + timeout
    master = rosgraph.Master("/mcar_tf_probe")
    while not master.is_online():
        if time.monotonic() > deadline:
            raise SystemExit("tf_probe: no ROS master at " + rosgraph.get_master_uri())
        time.sleep(0.1)
    rospy.init_node("mcar_tf_probe", anonymous=True, disable_signals=True)
    seen = {"/tf": set(), "/tf_static": set()}
    for topic in seen:
        rospy.Subscriber(topic, TFMessage,
                         lambda message, topic=topic: seen[topic].update(
                             t.child_frame_id for t in message.transforms))
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    while not rospy.has_param("/robot_description") and time.monotonic() < deadline:
        time.sleep(0.1)
    description = rospy.get_param("/robot_description", None)

    transforms = {}
    for frame in frames:
        left = max(deadline - time.monotonic(), 0.01)
        try:
            t = buffer.lookup_transform(root, frame, rospy.Time(0), rospy.Duration(left))
        except tf2_ros.TransformException:
            transforms[frame] = None
            continue
        p, q = t.transform.translation, t.transform.rotation
        transforms[frame] = [p.x, p.y, p.z, q.x, q.y, q.z, q.w]
    # the listener and our subscribers get each message separately: wait until ours saw
    # every frame the listener knows, to say on which topic each came
    found = {frame for frame, value in transforms.items() if value is not None} - {root}
    while not found <= seen["/tf"] | seen["/tf_static"] and time.monotonic() < deadline:
        time.sleep(0.05)
    publishers = {topic: sorted(nodes) for topic, nodes in master.getSystemState()[0]}
    json.dump({"description": description, "topics": publishers,
               "tf": sorted(seen["/tf"]), "tf_static": sorted(seen["/tf_static"]),
               "transforms": transforms}, sys.stdout)


if __name__ == "__main__":
    main(float(sys.argv[1]), sys.argv[2], sys.argv[3:])
