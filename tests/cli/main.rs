//! End-to-end tests of the `rslam` binary: one integration binary, one module per subcommand.

mod agents;
mod auto_exposure;
mod bench;
mod dataset_check;
mod depth_png;
mod eval;
mod eval_agents;
mod eval_recon;
mod harness;
mod imu_items;
mod list;
mod motion;
mod perturb;
mod perturb_euroc;
mod perturb_tumvi;
mod render;
mod resume;
mod rig;
mod rig_calibration;
mod rig_file;
mod rig_motion;
mod rig_rgbd;
mod scene;
mod sensor;
mod suite;
mod view;
