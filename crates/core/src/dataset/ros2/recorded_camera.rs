//! The cameras rslam perturbs in a recorded bag, found by reading the bag once: each colour image
//! topic (`Image` or `CompressedImage`; a stereo pair, infrared cameras) is a camera of its own,
//! with the intrinsics of its `CameraInfo`; a depth topic joins the colour topic it is registered
//! to (same size and intrinsics, one message per colour message by stamp), and is a camera of
//! its own otherwise (depth of its own lens, or at another rate). Each message's stamp and times
//! are kept. IMU topics are kept whole ([`RecordedImu`]) for the IMU items. Every other topic is
//! copied as it is. A bag with an image topic rslam cannot read, or two depth topics registered to
//! one colour topic, is refused, naming the bag and the topic.

use std::collections::HashMap;

use super::bag::{LogTimes, Topic};
use super::image_codec::ImageEncoding;
use super::messages::{from_cdr, CameraInfo, CompressedImage, Image, Imu, Time};
use super::recorded::{BagMessage, RecordedBag};
use super::recorded_imu::{RecordedImu, IMU_TYPE};
use crate::dataset::codec::encoded_image_size;
use crate::{printable, CoreError, Distortion, Intrinsics};

pub const IMAGE_TYPE: &str = "sensor_msgs/msg/Image";
pub const COMPRESSED_IMAGE_TYPE: &str = "sensor_msgs/msg/CompressedImage";
pub const CAMERA_INFO_TYPE: &str = "sensor_msgs/msg/CameraInfo";

/// One image message: its header's stamp and frame, and its times in the bag.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageMessage {
    pub stamp: Time,
    pub frame_id: String,
    pub times: LogTimes,
}

/// An image topic: its index among the bag's topics, encoding, size and messages in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTopic {
    pub index: usize,
    /// Its MCAP channel id.
    pub channel: u16,
    pub name: String,
    pub encoding: ImageEncoding,
    pub size: (u32, u32),
    pub messages: Vec<ImageMessage>,
}

/// A camera of a recorded bag: source frame `i` is colour message `i` and depth message `i`.
/// It has colour, depth registered to it, or both.
#[derive(Clone, Debug)]
pub struct RecordedBagCamera {
    /// `None`: depth on a camera of its own.
    pub colour: Option<ImageTopic>,
    pub depth: Option<ImageTopic>,
    pub intrinsics: Intrinsics,
    pub distortion: Option<Distortion>,
    /// The median rate of its frames' stamps.
    pub rate_hz: f64,
}

impl RecordedBagCamera {
    /// The topic whose messages are the camera's frames: its colour, else its depth.
    pub fn frames(&self) -> &ImageTopic {
        match (&self.colour, &self.depth) {
            (Some(colour), _) => colour,
            (None, Some(depth)) => depth,
            (None, None) => unreachable!("a recorded camera has colour or depth"),
        }
    }
}

/// A recorded bag's topics and its cameras, in the order their topics first appear.
#[derive(Clone, Debug)]
pub struct RecordedBagCameras {
    pub bag: RecordedBag,
    /// Every topic, in the order its first message comes.
    pub topics: Vec<Topic>,
    /// The index in `topics` of each MCAP channel id.
    pub topic_of_channel: HashMap<u16, usize>,
    pub cameras: Vec<RecordedBagCamera>,
    /// Its IMU topics, which IMU items apply to.
    pub imus: Vec<RecordedImu>,
}

/// What reading the bag found on each topic.
#[derive(Default)]
struct Found {
    topics: Vec<Topic>,
    by_channel: HashMap<u16, usize>,
    images: Vec<ImageTopic>,
    imus: Vec<RecordedImu>,
    camera_infos: HashMap<String, CameraInfo>,
}

impl RecordedBagCameras {
    pub fn read(bag: RecordedBag) -> Result<Self, CoreError> {
        let mut found = Found::default();
        for message in bag.messages()? {
            found.add(&bag, message?)?;
        }
        let bad = |message: String| CoreError::bad_file(&bag.folder, message);
        let (depths, colours): (Vec<ImageTopic>, Vec<ImageTopic>) =
            std::mem::take(&mut found.images)
                .into_iter()
                .partition(|t| t.encoding.is_depth());
        if colours.is_empty() && depths.is_empty() {
            return Err(bad(format!(
                "no image topic ({IMAGE_TYPE} or {COMPRESSED_IMAGE_TYPE}) to perturb"
            )));
        }
        let mut cameras = colours
            .into_iter()
            .map(|colour| found.camera_of(colour))
            .collect::<Result<Vec<_>, _>>()
            .map_err(bad)?;
        let mut depth_cameras = Vec::new();
        for depth in depths {
            let info = found.camera_info_of(&depth).map_err(bad)?;
            let registered = cameras.iter_mut().find(|c| {
                c.colour
                    .as_ref()
                    .is_some_and(|colour| colour.size == depth.size)
                    && k_of(info) == k_of_intrinsics(&c.intrinsics)
            });
            if let Some(camera) = registered {
                let colour = camera.frames();
                if let Some(first) = &camera.depth {
                    return Err(bad(format!(
                        "depth topics {} and {} are both registered to {}: expected one",
                        first.name, depth.name, colour.name
                    )));
                }
                if pairs_one_to_one(colour, &depth, camera.rate_hz) {
                    camera.depth = Some(depth);
                    continue;
                }
            }
            depth_cameras.push(found.camera_of(depth).map_err(bad)?);
        }
        cameras.extend(depth_cameras);
        Ok(Self {
            bag,
            topics: found.topics,
            topic_of_channel: found.by_channel,
            cameras,
            imus: found.imus,
        })
    }

    /// Whether topic `index` is one rslam writes anew (a camera's colour or depth).
    pub fn is_perturbed(&self, index: usize) -> bool {
        self.cameras.iter().any(|c| {
            [&c.colour, &c.depth]
                .into_iter()
                .flatten()
                .any(|t| t.index == index)
        })
    }
}

impl Found {
    fn add(&mut self, bag: &RecordedBag, message: BagMessage) -> Result<(), CoreError> {
        let index = match self.by_channel.get(&message.channel.id) {
            Some(&index) => index,
            None => {
                self.topics.push(Topic::recorded(&message.channel));
                self.by_channel
                    .insert(message.channel.id, self.topics.len() - 1);
                self.topics.len() - 1
            }
        };
        let topic = message.topic();
        let bad = |what: String| {
            CoreError::bad_file(
                &bag.folder,
                format!(
                    "topic {} ({}): {what}",
                    printable(topic),
                    message.type_name()
                ),
            )
        };
        let (stamp, frame_id, encoding, size) = match message.type_name() {
            IMAGE_TYPE => {
                let image: Image = from_cdr(&message.data).map_err(bad)?;
                let encoding = ImageEncoding::raw(&image.encoding).map_err(bad)?;
                let header = image.header;
                (
                    header.stamp,
                    header.frame_id,
                    encoding,
                    (image.width, image.height),
                )
            }
            COMPRESSED_IMAGE_TYPE => {
                let image: CompressedImage = from_cdr(&message.data).map_err(bad)?;
                let encoding = ImageEncoding::compressed(&image.format).map_err(bad)?;
                let size = encoded_image_size(image.data.0).map_err(bad)?;
                let header = image.header;
                (header.stamp, header.frame_id, encoding, size)
            }
            IMU_TYPE => {
                let imu: Imu = from_cdr(&message.data).map_err(bad)?;
                let times = LogTimes {
                    log_time: message.log_time,
                    publish_time: message.publish_time,
                    sequence: message.sequence,
                };
                match self.imus.iter_mut().find(|t| t.index == index) {
                    Some(topic) => topic.messages.push((imu, times)),
                    None => self.imus.push(RecordedImu {
                        index,
                        name: topic.to_string(),
                        messages: vec![(imu, times)],
                    }),
                }
                return Ok(());
            }
            CAMERA_INFO_TYPE => {
                if !self.camera_infos.contains_key(topic) {
                    let info: CameraInfo = from_cdr(&message.data).map_err(bad)?;
                    self.camera_infos.insert(topic.to_string(), info);
                }
                return Ok(());
            }
            _ => return Ok(()),
        };
        let entry = ImageMessage {
            stamp,
            frame_id,
            times: LogTimes {
                log_time: message.log_time,
                publish_time: message.publish_time,
                sequence: message.sequence,
            },
        };
        match self.images.iter_mut().find(|t| t.index == index) {
            Some(images) => {
                if images.encoding != encoding || images.size != size {
                    return Err(bad(format!(
                        "a {}x{} {} image after {}x{} {} ones: expected one encoding and size",
                        size.0,
                        size.1,
                        encoding.name(),
                        images.size.0,
                        images.size.1,
                        images.encoding.name()
                    )));
                }
                images.messages.push(entry);
            }
            None => self.images.push(ImageTopic {
                index,
                channel: message.channel.id,
                name: topic.to_string(),
                encoding,
                size,
                messages: vec![entry],
            }),
        }
        Ok(())
    }

    /// The camera whose frames are `topic`'s messages (colour, or depth on its own), with the
    /// intrinsics and lens of its `CameraInfo` and the rate of its stamps.
    fn camera_of(&self, topic: ImageTopic) -> Result<RecordedBagCamera, String> {
        let info = self.camera_info_of(&topic)?;
        let intrinsics = Intrinsics::from_pinhole((info.width, info.height), k_of(info))
            .map_err(|e| format!("the CameraInfo of {}: {e}", topic.name))?;
        if (info.width, info.height) != topic.size {
            return Err(format!(
                "{} holds {}x{} images, but its CameraInfo says {}x{}",
                topic.name, topic.size.0, topic.size.1, info.width, info.height
            ));
        }
        let distortion =
            distortion_of(info).map_err(|e| format!("the CameraInfo of {}: {e}", topic.name))?;
        let rate_hz = rate_of(&topic)?;
        let (colour, depth) = match topic.encoding.is_depth() {
            true => (None, Some(topic)),
            false => (Some(topic), None),
        };
        Ok(RecordedBagCamera {
            colour,
            depth,
            intrinsics,
            distortion,
            rate_hz,
        })
    }

    /// The `CameraInfo` beside an image topic: `camera_info` in its namespace, the driver
    /// convention (`/camera/color/image_raw` → `/camera/color/camera_info`; a compressed
    /// topic's base topic is the raw one).
    fn camera_info_of(&self, image: &ImageTopic) -> Result<&CameraInfo, String> {
        let raw = match image.encoding {
            ImageEncoding::Compressed { .. } => image
                .name
                .strip_suffix("/compressed")
                .unwrap_or(&image.name),
            _ => &image.name,
        };
        let namespace = raw.rsplit_once('/').map_or("", |(ns, _)| ns);
        let info_topic = format!("{namespace}/camera_info");
        self.camera_infos.get(&info_topic).ok_or_else(|| {
            format!(
                "no {CAMERA_INFO_TYPE} on {info_topic} for {}: the camera's intrinsics are needed",
                image.name
            )
        })
    }
}

fn k_of(info: &CameraInfo) -> [f64; 4] {
    [info.k[0], info.k[4], info.k[2], info.k[5]]
}

fn k_of_intrinsics(k: &Intrinsics) -> [f64; 4] {
    [k.fx, k.fy, k.cx, k.cy]
}

/// The lens of a `CameraInfo`: none when every coefficient is 0, radtan for `plumb_bob` (or
/// `rational_polynomial`) without higher radial terms, equidistant for `equidistant`.
fn distortion_of(info: &CameraInfo) -> Result<Option<Distortion>, String> {
    let d = &info.d;
    if d.iter().all(|&c| c == 0.0) {
        return Ok(None);
    }
    let coefficient = |i: usize| d.get(i).copied().unwrap_or(0.0);
    let model = info.distortion_model.as_str();
    match model {
        "plumb_bob" | "rational_polynomial" if d.iter().skip(4).all(|&c| c == 0.0) => {
            Ok(Some(Distortion::Radtan {
                k1: coefficient(0),
                k2: coefficient(1),
                p1: coefficient(2),
                p2: coefficient(3),
            }))
        }
        "equidistant" if d.len() == 4 => Ok(Some(Distortion::Equidistant {
            k1: d[0],
            k2: d[1],
            k3: d[2],
            k4: d[3],
        })),
        _ => Err(format!(
            "distortion '{}' with {} coefficients {d:?}: expected plumb_bob with k3 and beyond 0, or equidistant with 4",
            printable(model),
            d.len()
        )),
    }
}

/// The median rate of an image topic's stamps, which must rise.
fn rate_of(topic: &ImageTopic) -> Result<f64, String> {
    let stamps: Vec<f64> = topic.messages.iter().map(|m| m.stamp.seconds()).collect();
    median_rate(&topic.name, &stamps)
}

/// The median rate of `stamps` (seconds) of the topic `name`, which must rise.
pub(super) fn median_rate(name: &str, stamps: &[f64]) -> Result<f64, String> {
    if stamps.len() < 2 {
        return Err(format!(
            "{name} has {} message(s): a rate needs at least 2",
            stamps.len()
        ));
    }
    let mut steps: Vec<f64> = stamps.windows(2).map(|w| w[1] - w[0]).collect();
    if let Some(i) = steps.iter().position(|&s| s <= 0.0) {
        return Err(format!(
            "{name}: the message stamped {:.9} s follows one stamped {:.9} s; expected rising stamps",
            stamps[i + 1],
            stamps[i]
        ));
    }
    steps.sort_by(f64::total_cmp);
    Ok(1.0 / steps[steps.len() / 2])
}

/// Whether depth message `i` is colour message `i`'s partner for every `i`: the nearest in stamp,
/// within half a frame interval.
fn pairs_one_to_one(colour: &ImageTopic, depth: &ImageTopic, rate_hz: f64) -> bool {
    let tolerance = 0.5 / rate_hz;
    colour.messages.len() == depth.messages.len()
        && colour
            .messages
            .iter()
            .zip(&depth.messages)
            .all(|(c, d)| (c.stamp.seconds() - d.stamp.seconds()).abs() <= tolerance)
}
