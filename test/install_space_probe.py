"""Publishes textured 640x480 mono8 images on /camera/image_raw until the
nodelet answers with a bowg_ros/KeyframeStatus on /bowg/keyframe_status
(scripts/check_install_space.sh runs it against bowg.launch started from the
install space). Exit 0 with one line about the first status; 1 on a timeout.

usage: install_space_probe.py [TIMEOUT_S]
"""
import random
import sys
import threading
import time

import rospy
from bowg_ros.msg import KeyframeStatus
from sensor_msgs.msg import Image

WIDTH, HEIGHT, BLOCK = 640, 480, 8


def textured_image():
    """Random grey 8x8 blocks: corners everywhere for GFTT and ORB."""
    rng = random.Random(7)
    rows = []
    for _ in range(HEIGHT // BLOCK):
        row = bytearray()
        for _ in range(WIDTH // BLOCK):
            row += bytes([rng.randrange(256)]) * BLOCK
        rows.append(bytes(row) * BLOCK)
    return b"".join(rows)


def main():
    timeout = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    rospy.init_node("bowg_install_space_probe", anonymous=True, disable_signals=True)
    received = []
    got = threading.Event()

    def on_status(msg):
        received.append(msg)
        got.set()

    rospy.Subscriber("/bowg/keyframe_status", KeyframeStatus, on_status, queue_size=10)
    pub = rospy.Publisher("/camera/image_raw", Image, queue_size=1)
    image = Image(height=HEIGHT, width=WIDTH, encoding="mono8", is_bigendian=0, step=WIDTH,
                  data=textured_image())
    image.header.frame_id = "camera"
    deadline = time.monotonic() + timeout
    sent = 0
    # Publish until the status arrives: the nodelet may still be loading its
    # vocabulary when the first images go out.
    while not got.is_set() and time.monotonic() < deadline:
        if pub.get_num_connections() > 0:
            image.header.stamp = rospy.get_rostime()
            image.header.seq = sent
            pub.publish(image)
            sent += 1
        got.wait(0.5)
    if not received:
        print("install_space_probe: no /bowg/keyframe_status within %.0f s (%d images sent, "
              "image subscribers: %d)" % (timeout, sent, pub.get_num_connections()))
        return 1
    msg = received[0]
    print("install_space_probe: keyframe %d: %s, %d features, database %d (%d images sent)"
          % (msg.id, msg.status_text, msg.num_features, msg.database_size, sent))
    if msg.num_features == 0:
        print("install_space_probe: the textured image gave no features")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
