//! Dataset layouts that SLAM systems read unchanged: Replica (NICE-SLAM, SplaTAM, Co-SLAM,
//! GO-SLAM) and TUM RGB-D (ORB-SLAM3); [`euroc`] writes and reads the EuRoC MAV (ASL) layout
//! of stereo cameras, an IMU and ground truth. [`DatasetWriter`] writes frames from many threads and
//! the manifest last; [`read_dataset`] reads either layout back.

mod atomic_write;
mod checksums;
mod codec;
mod depth_png;
mod dynamic_fractions;
pub mod euroc;
mod frames_deleted;
mod layout;
mod manifest;
mod no_symlinks;
mod orbslam3;
mod reader;
pub mod ros2;
mod verify;
mod viewpoints;
mod writer;

pub use atomic_write::write_atomically;
pub use checksums::{
    blake3_hex, content_files, is_bookkeeping, is_inside, ChecksumDifferences, Checksums,
    ContentWriter, CHECKSUM_FILE, PARTIAL_SUFFIX, RUN_FILE,
};
pub use codec::{
    decode_depth_png, decode_mask_png, decode_rgb, encode_depth_png, encode_grey16_png,
    encode_grey_png, encode_jpeg, encode_mask_png, encode_png, encode_rgb_like,
    read_grey16_high_byte, read_image_has_colour, read_image_size, read_rgb, read_rgb8,
    write_rgb_like,
};
pub use depth_png::DepthPng;
pub use dynamic_fractions::{rounded as rounded_dynamic_fraction, MASK_IDS};
pub use frames_deleted::{
    copy_without_frames, delete_frames, is_frame_file, read_frames_deleted, FramesDeleted,
    FRAMES_DELETED_FILE,
};
pub use layout::{DatasetFormat, Layout};
pub use manifest::{ItemSeverities, Manifest, MANIFEST_FILE};
pub use no_symlinks::refuse_symlinks;
pub use orbslam3::rgbd_inertial_settings;
pub use reader::{read_dataset, DatasetFrame, DatasetOverrides, SourceDataset};
pub use verify::{verify_output, Verification};
pub use viewpoints::{read_views, DatasetViews, View, ViewCamera};
pub use writer::{DatasetWriter, FrameFiles, OutputFrame};
