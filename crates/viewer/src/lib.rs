//! The egui viewer behind `rslam view`: inspect a sequence and tune perturbations live.
//! Empty until its issue; the crate holds its place in the workspace's dependency graph.
