"""Reading one RGB-D camera from a ROS 2 bag (a rosbag2 folder) with the `rosbags` library, no
ROS install needed: the colour camera from its CameraInfo, and the colour frames each with the
depth image nearest in header stamp.

Colour: sensor_msgs/msg/Image rgb8, bgr8 or mono8, or sensor_msgs/msg/CompressedImage jpeg or
png; given as HxWx3 uint8 RGB. Depth, registered to colour: 16UC1 millimetres (0 = none) or
32FC1 metres (NaN = none); given as HxW float32 metres, 0 where there is none. The topics
default to those of `rslam render --format ros2` (the RealSense ROS 2 driver's).
"""
from collections import Counter
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
from rosbags.highlevel import AnyReader, AnyReaderError
from rosbags.typesys import Stores, get_typestore

COLOR_TOPIC = "/camera/color/image_raw"
COLOR_INFO_TOPIC = "/camera/color/camera_info"
DEPTH_TOPIC = "/camera/depth/image_raw"

# the Image encodings read: numpy type and channels of a pixel
_PIXELS = {"rgb8": ("u1", 3), "bgr8": ("u1", 3), "mono8": ("u1", 1), "16UC1": ("u2", 1), "32FC1": ("f4", 1)}
_COMPRESSED_FORMATS = ("jpeg", "jpg", "png")
# the message types of bags that do not store their definitions (ROS 2 Humble's SQLite bags)
_HUMBLE = get_typestore(Stores.ROS2_HUMBLE)


class BagError(Exception):
    """A bag that does not read, a topic it lacks, or an image in it that this reader cannot
    decode; the message names the bag or the topic."""


@dataclass(frozen=True)
class Camera:
    """The colour camera of a CameraInfo: pinhole intrinsics, image size in pixels, and the lens
    (`distortion_model`, e.g. plumb_bob or equidistant, and its coefficients `d`)."""
    fx: float
    fy: float
    cx: float
    cy: float
    width: int
    height: int
    distortion_model: str
    d: tuple


@dataclass(frozen=True)
class Frame:
    """A colour image with its depth: `t` the colour header stamp in seconds, `rgb` HxWx3 uint8
    in RGB order, `depth` HxW float32 metres (0 where there is none)."""
    t: float
    rgb: np.ndarray
    depth: np.ndarray


def pair_by_stamp(color_ns, depth_ns):
    """[(colour stamp, depth stamp)] in colour-stamp order: each colour stamp with the nearest
    depth stamp, if it is within half the median colour interval (with a single colour stamp:
    the same stamp); colour stamps without one are left out. A depth stamp may serve several."""
    color = np.unique(np.asarray(color_ns, dtype=np.int64))
    depth = np.unique(np.asarray(depth_ns, dtype=np.int64))
    if not len(color) or not len(depth):
        return []
    tolerance = np.median(np.diff(color)) / 2 if len(color) > 1 else 0
    after = np.searchsorted(depth, color)
    before = depth[np.maximum(after - 1, 0)]
    after = depth[np.minimum(after, len(depth) - 1)]
    nearest = np.where(color - before <= after - color, before, after)
    return [(int(c), int(d)) for c, d in zip(color, nearest) if abs(c - d) <= tolerance]


class RgbdBag:
    """The RGB-D camera of the bag at `path`. Opening it reads the colour `camera`, the median
    colour frame rate `rate_hz` (None with fewer than two colour images) and every colour and
    depth header stamp, which it pairs (`pairs`, by `pair_by_stamp`); `frames()` reads the bag
    again and decodes the paired images."""

    def __init__(self, path, color_topic=COLOR_TOPIC, depth_topic=DEPTH_TOPIC,
                 info_topic=COLOR_INFO_TOPIC):
        self.path = Path(path)
        self.color_topic = color_topic
        self.depth_topic = depth_topic
        stamps = {color_topic: [], depth_topic: []}
        with _reader(self.path) as reader:
            info = next((message for _, message in _messages(reader, info_topic)), None)
            if info is None:
                raise BagError(f"{info_topic}: no messages in {self.path}")
            for topic, message in _messages(reader, color_topic, depth_topic):
                stamps[topic].append(_nanoseconds(message.header.stamp))
        fx, fy, cx, cy = (float(info.k[i]) for i in (0, 4, 2, 5))
        self.camera = Camera(fx, fy, cx, cy, info.width, info.height, info.distortion_model,
                             tuple(float(c) for c in info.d))
        color = np.unique(stamps[color_topic])
        self.rate_hz = 1e9 / np.median(np.diff(color)) if len(color) > 1 else None
        self.pairs = pair_by_stamp(color, stamps[depth_topic])

    def frames(self):
        """The paired frames (Frame) in colour-stamp order, each once both its images have been
        read: the bag's order of messages need not be that of their stamps."""
        colors_wanted = {c for c, _ in self.pairs}
        depth_uses = Counter(d for _, d in self.pairs)
        colors, depths = {}, {}
        pairs = iter(self.pairs)
        pair = next(pairs, None)
        with _reader(self.path) as reader:
            for topic, message in _messages(reader, self.color_topic, self.depth_topic):
                stamp = _nanoseconds(message.header.stamp)
                if topic == self.color_topic and stamp in colors_wanted:
                    colors_wanted.discard(stamp)
                    colors[stamp] = _rgb(message, topic)
                elif topic == self.depth_topic and depth_uses[stamp] and stamp not in depths:
                    depths[stamp] = _depth_m(message, topic)
                while pair and pair[0] in colors and pair[1] in depths:
                    c, d = pair
                    rgb = colors.pop(c)
                    depth_uses[d] -= 1
                    depth = depths[d] if depth_uses[d] else depths.pop(d)
                    if depth.shape != rgb.shape[:2]:
                        raise BagError(f"{self.depth_topic}: the depth image at {d * 1e-9:.9f} s is "
                                       f"{depth.shape[1]}x{depth.shape[0]}, the colour image "
                                       f"{rgb.shape[1]}x{rgb.shape[0]} (depth must be registered to colour)")
                    yield Frame(c * 1e-9, rgb, depth)
                    pair = next(pairs, None)


@contextmanager
def _reader(path):
    """The bag open in an AnyReader; one that rosbags cannot read is a BagError."""
    try:
        with AnyReader([path], default_typestore=_HUMBLE) as reader:
            yield reader
    except AnyReaderError as e:
        raise BagError(f"{path}: {e}") from None


def _messages(reader, *topics):
    """(topic, message) of these topics, deserialised, in the bag's order."""
    connections = [c for c in reader.connections if c.topic in topics]
    missing = sorted(set(topics) - {c.topic for c in connections})
    if missing:
        present = ", ".join(sorted({c.topic for c in reader.connections}))
        raise BagError(f"{missing[0]}: not a topic of the bag (it has {present})")
    for connection, _, raw in reader.messages(connections=connections):
        yield connection.topic, reader.deserialize(raw, connection.msgtype)


def _nanoseconds(stamp):
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def _unsupported(topic, encoding, supported):
    return BagError(f"{topic}: encoding '{encoding}' is not one this reader decodes ({', '.join(supported)})")


def _pixels(image):
    """An Image's pixels as HxWxC, in native byte order, without the rows' padding."""
    kind, channels = _PIXELS[image.encoding]
    dtype = np.dtype(kind).newbyteorder(">" if image.is_bigendian else "<")
    rows = np.asarray(image.data).reshape(image.height, image.step)[:, :image.width * channels * dtype.itemsize]
    pixels = np.ascontiguousarray(rows).view(dtype).reshape(image.height, image.width, channels)
    return pixels.astype(dtype.newbyteorder("="))


def _rgb(message, topic):
    """HxWx3 uint8 RGB of a colour Image or CompressedImage."""
    # a CompressedImage's format: "jpeg", "png", or image_transport's "bgr8; jpeg compressed bgr8"
    if hasattr(message, "format"):
        if not any(name in message.format.lower() for name in _COMPRESSED_FORMATS):
            raise _unsupported(topic, message.format, _COMPRESSED_FORMATS)
        bgr = cv2.imdecode(np.asarray(message.data), cv2.IMREAD_COLOR)
        if bgr is None:
            t = _nanoseconds(message.header.stamp) * 1e-9
            raise BagError(f"{topic}: the '{message.format}' image at {t:.9f} s does not decode")
        return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
    if message.encoding == "rgb8":
        return _pixels(message)
    if message.encoding == "bgr8":
        return np.ascontiguousarray(_pixels(message)[..., ::-1])
    if message.encoding == "mono8":
        return np.repeat(_pixels(message), 3, axis=2)
    raise _unsupported(topic, message.encoding, ("rgb8", "bgr8", "mono8"))


def _depth_m(message, topic):
    """HxW float32 metres of a depth Image, 0 where there is none."""
    if message.encoding == "16UC1":
        return _pixels(message)[..., 0].astype(np.float32) / np.float32(1000)
    if message.encoding == "32FC1":
        # REP 118: NaN no measurement, -Inf too close, +Inf too far
        return np.nan_to_num(_pixels(message)[..., 0], nan=0, posinf=0, neginf=0)
    raise _unsupported(topic, message.encoding, ("16UC1", "32FC1"))
