//! Trajectory file formats (TUM, Replica traj.txt, KITTI, EuRoC, COLMAP images.txt, nerfstudio's
//! camera paths and transforms.json): readers
//! with auto-detection, and writers (TUM, Replica).
//!
//! Readers are lenient on layout (tabs, repeated blanks, trailing blanks, `#` comments, a byte
//! order mark, CRLF) and strict on numbers: a line that does not hold what its format expects,
//! a value that is not a finite number or a zero quaternion is an error naming the file and line.
//! Non-unit quaternions are normalised.

mod colmap;
mod detect;
pub(crate) mod euroc;
mod format;
mod kitti;
pub(crate) mod lines;
mod nerfstudio;
mod read;
mod replica;
mod tum;

#[cfg(test)]
mod tests;

pub use format::{ReadOptions, TimeSource, TrajectoryFile, TrajectoryFormat, UnknownFormat};
pub use read::{read_trajectory, read_trajectory_with};
pub use replica::write_replica;
pub use tum::write_tum;
