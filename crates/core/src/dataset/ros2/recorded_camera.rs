//! The cameras rslam perturbs in a recorded bag, found by reading the bag once: each colour image
//! topic (`Image` or `CompressedImage`; a stereo pair, infrared cameras) is a camera of its own,
//! with the intrinsics of its `CameraInfo`; a depth topic joins the colour topic it is registered
//! to (same size and intrinsics, one message per colour message by stamp). Each message's stamp
//! and times are kept. Every other topic is copied as it is. A bag with an image topic rslam
//! cannot read, depth registered to no colour topic or not one-to-one with it is refused, naming
//! the bag and the topic.

use std::collections::HashMap;

use super::bag::{LogTimes, Topic};
use super::image_codec::ImageEncoding;
use super::messages::{from_cdr, CameraInfo, CompressedImage, Image, Time};
use super::recorded::{BagMessage, RecordedBag};
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
#[derive(Clone, Debug)]
pub struct RecordedBagCamera {
    pub colour: ImageTopic,
    pub depth: Option<ImageTopic>,
    pub intrinsics: Intrinsics,
    pub distortion: Option<Distortion>,
    /// The median rate of the colour stamps.
    pub rate_hz: f64,
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
}

/// What reading the bag found on each topic.
#[derive(Default)]
struct Found {
    topics: Vec<Topic>,
    by_channel: HashMap<u16, usize>,
    images: Vec<ImageTopic>,
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
        if colours.is_empty() {
            return Err(bad(format!(
                "no colour image topic ({IMAGE_TYPE} or {COMPRESSED_IMAGE_TYPE}) to perturb"
            )));
        }
        let mut cameras = Vec::new();
        for colour in colours {
            let info = found.camera_info_of(&colour).map_err(bad)?;
            let intrinsics = Intrinsics::from_pinhole((info.width, info.height), k_of(info))
                .map_err(|e| bad(format!("the CameraInfo of {}: {e}", colour.name)))?;
            if (info.width, info.height) != colour.size {
                return Err(bad(format!(
                    "{} holds {}x{} images, but its CameraInfo says {}x{}",
                    colour.name, colour.size.0, colour.size.1, info.width, info.height
                )));
            }
            let distortion = distortion_of(info)
                .map_err(|e| bad(format!("the CameraInfo of {}: {e}", colour.name)))?;
            let rate_hz = rate_of(&colour).map_err(bad)?;
            cameras.push(RecordedBagCamera {
                colour,
                depth: None,
                intrinsics,
                distortion,
                rate_hz,
            });
        }
        for depth in depths {
            let info = found.camera_info_of(&depth).map_err(bad)?;
            let registered = cameras.iter_mut().find(|c| {
                depth.size == c.colour.size && k_of(info) == k_of_intrinsics(&c.intrinsics)
            });
            let Some(camera) = registered else {
                return Err(bad(format!(
                    "depth topic {} is registered to no colour topic (none has its size and CameraInfo): perturbing depth on a camera of its own is not built yet",
                    depth.name
                )));
            };
            if let Some(first) = &camera.depth {
                return Err(bad(format!(
                    "depth topics {} and {} are both registered to {}: expected one",
                    first.name, depth.name, camera.colour.name
                )));
            }
            pair_one_to_one(&camera.colour, &depth, camera.rate_hz).map_err(bad)?;
            camera.depth = Some(depth);
        }
        Ok(Self {
            bag,
            topics: found.topics,
            topic_of_channel: found.by_channel,
            cameras,
        })
    }

    /// Whether topic `index` is one rslam writes anew (a camera's colour or depth).
    pub fn is_perturbed(&self, index: usize) -> bool {
        self.cameras
            .iter()
            .any(|c| c.colour.index == index || c.depth.as_ref().is_some_and(|d| d.index == index))
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

/// The median rate of a topic's stamps, which must rise.
fn rate_of(topic: &ImageTopic) -> Result<f64, String> {
    let stamps: Vec<f64> = topic.messages.iter().map(|m| m.stamp.seconds()).collect();
    if stamps.len() < 2 {
        return Err(format!(
            "{} has {} message(s): a rate needs at least 2",
            topic.name,
            stamps.len()
        ));
    }
    let mut steps: Vec<f64> = stamps.windows(2).map(|w| w[1] - w[0]).collect();
    if let Some(i) = steps.iter().position(|&s| s <= 0.0) {
        return Err(format!(
            "{}: the message stamped {:.9} s follows one stamped {:.9} s; expected rising stamps",
            topic.name,
            stamps[i + 1],
            stamps[i]
        ));
    }
    steps.sort_by(f64::total_cmp);
    Ok(1.0 / steps[steps.len() / 2])
}

/// Checks that depth message `i` is colour message `i`'s partner: the nearest in stamp, within
/// half a frame interval.
fn pair_one_to_one(colour: &ImageTopic, depth: &ImageTopic, rate_hz: f64) -> Result<(), String> {
    if colour.messages.len() != depth.messages.len() {
        return Err(format!(
            "{} has {} messages and {} {}: a camera's colour and depth must pair one to one (streams at other rates are not built yet)",
            colour.name,
            colour.messages.len(),
            depth.name,
            depth.messages.len()
        ));
    }
    let tolerance = 0.5 / rate_hz;
    for (c, d) in colour.messages.iter().zip(&depth.messages) {
        let (tc, td) = (c.stamp.seconds(), d.stamp.seconds());
        if (tc - td).abs() > tolerance {
            return Err(format!(
                "{} at {tc:.9} s has no depth on {} within {:.1} ms (the nearest in order is at {td:.9} s)",
                colour.name,
                depth.name,
                tolerance * 1e3
            ));
        }
    }
    Ok(())
}
