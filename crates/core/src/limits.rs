//! The largest inputs rslam accepts. Past each limit a reader stops with an error naming the file
//! and the limit, before it allocates for what the file claims: a header that says 10⁹ vertices
//! is refused, not believed. Each limit is far above any real dataset (Replica's largest mesh has
//! about 1.5 M vertices, TUM's longest sequence about 25 000 poses) and low enough that the memory
//! the accepted input can take fits a workstation.

/// Vertices of one mesh file (PLY, OBJ, glTF): 32 bytes each in the renderer, 3.2 GB at the limit.
pub const MAX_MESH_VERTICES: usize = 100_000_000;

/// Triangles of one mesh file, after polygons are split into fans: 1.2 GB of indices at the limit.
pub const MAX_MESH_TRIANGLES: usize = 100_000_000;

/// Bytes of one mesh file, read whole: a binary PLY of 100 M coloured vertices and triangles is
/// about 3 GB.
pub const MAX_MESH_FILE_BYTES: u64 = 4 << 30;

/// Corners of one PLY polygon (a face's list length).
pub const MAX_POLYGON_CORNERS: usize = 1_000;

/// Pixels a side of an image read or a camera given (also the common GPU texture limit).
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// Poses of one trajectory file, frames of one dataset, sequence or frame list, and rows of one
/// EuRoC data.csv (IMU samples, ground-truth states).
pub const MAX_POSES: usize = 10_000_000;

/// Bytes of one text input read whole (trajectory, frame list, associations, manifest, suite or
/// method file): a 10 M-pose TUM file is about 900 MB.
pub const MAX_TEXT_FILE_BYTES: u64 = 1 << 30;

/// Sequences of one suite.
pub const MAX_SUITE_SEQUENCES: usize = 100_000;

/// Runs of one method on one sequence (`repeats`).
pub const MAX_REPEATS: usize = 1_000;

/// Camera folders (`cam0` … `cam63`) of one EuRoC dataset.
pub const MAX_EUROC_CAMERAS: usize = 64;

/// Samples of one synthesised IMU sequence: 176 bytes each, 1.8 GB at the limit (14 h at 200 Hz).
pub const MAX_IMU_SAMPLES: usize = 10_000_000;
